// The friction the pivot of a toppling block needs, and the rotation at which it reaches the slope's
// friction (refs §3.6, §3.8). Geometry, kinematics, signs: ref/base_friction_onset.hpp and
// ref/base_friction_pre_face.hpp.
//
// Derivation. The quasi-static block carries no net force (no gravity in the plane, inertia neglected):
// the pivot's reaction R equals minus the sum of the M21 element forces, -μ_B m g u_e/S_e each, i.e.
// R = μ_B m g Σ u_e/S_e (equal masses). With the velocity of the model's rotation about I at the rate λ
// that makes its moment balance vanish (pre_face_rate), u_e/v_B = λ ẑ x (c_e - I) - ĝ and
// S_e/v_B = sqrt(|u_e/v_B|² + (λ r)²). The moment balance does not enter R except through λ.
#include "ref/base_friction_onset.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "ref/base_friction_travel.hpp"
#include "ref/gsl_support.hpp"
#include "ref/require.hpp"

namespace ref {

namespace {

constexpr double quarter_turn = std::numbers::pi / 2.0;

struct Reaction {
  double x = 0.0, y = 0.0;  // R / (μ_B m_e g), along and normal to the slope
};

// R = Σ u_e/S_e in the slope frame, lengths in units of the side s = 2r (λ s).
Reaction reaction_in_sides(double lambda_s, double theta, double alpha, int n_w, int n_h, PivotModel model) {
  constexpr double r = 0.5;
  const double c = std::cos(theta), s = std::sin(theta);
  const double gx = -std::sin(alpha), gy = -std::cos(alpha);  // ĝ, the fall line
  double ix = -r * (c - s), iy = -r;                          // I, relative to c_0: (M15.2) rolling
  if (model.law == WallTangentialLaw::exact) ix = -r * c + r * s, iy = -r * s - r * c;  // (M3.2): corner
  Reaction sum;
  for (int j = 0; j < n_h; ++j)
    for (int i = 0; i < n_w; ++i) {
      const double bx = 2.0 * r * i, by = 2.0 * r * j;
      const double dx = c * bx - s * by - ix, dy = s * bx + c * by - iy;  // c_e - I
      const double ux = -lambda_s * dy - gx, uy = lambda_s * dx - gy;     // (M21) relative velocity
      const double s_e = std::sqrt(ux * ux + uy * uy + lambda_s * lambda_s * r * r);
      sum.x += ux / s_e;
      sum.y += uy / s_e;
    }
  return sum;
}

void require_friction(const char* where, double phi_w) {
  detail::require_finite(where, "phi_w", phi_w);
  if (!(phi_w > 0.0 && phi_w < quarter_turn)) detail::fail(where, "phi_w must lie in (0, pi/2) rad", phi_w);
}

}  // namespace

double pivot_friction_demand(double theta, double alpha, double width, double height, int n_w, int n_h,
                             PivotModel model) {
  constexpr const char* where = "ref::pivot_friction_demand";
  const double rate = pre_face_rate(theta, alpha, width, height, n_w, n_h, model.law, model.lever);
  if (!(rate > 0.0)) detail::fail(where, "the block does not topple at this theta (rate 0)", theta);
  const double side = width / n_w;
  const Reaction reaction = reaction_in_sides(rate * side, theta, alpha, n_w, n_h, model);
  if (!(reaction.y > 0.0)) detail::fail(where, "the slope does not press the pivot (R_y <= 0)", reaction.y);
  return reaction.x / reaction.y;
}

double onset_rotation(double alpha, double wall_friction_angle, double width, double height, int n_w,
                      int n_h, PivotModel model) {
  constexpr const char* where = "ref::onset_rotation";
  require_friction(where, wall_friction_angle);
  const double limit = std::tan(wall_friction_angle);
  const auto excess = [&](double theta) {
    return pivot_friction_demand(theta, alpha, width, height, n_w, n_h, model) - limit;
  };
  if (excess(0.0) >= 0.0) return 0.0;  // slips at once
  constexpr double step = 0.25 * std::numbers::pi / 180.0;
  for (double lo = 0.0; lo < quarter_turn; lo += step) {
    const double hi = std::min(lo + step, quarter_turn);
    if (excess(hi) >= 0.0) return detail::brent_root(where, excess, lo, hi, 1e-12, 1e-10);
  }
  return quarter_turn;
}

double onset_travel(double alpha, double wall_friction_angle, double width, double height, int n_w,
                    int n_h, PivotModel model) {
  const double theta = onset_rotation(alpha, wall_friction_angle, width, height, n_w, n_h, model);
  if (theta >= quarter_turn) return std::numeric_limits<double>::infinity();
  return travel_at_theta(theta, alpha, [=](double psi) {
    return pre_face_rate(std::max(0.0, psi - alpha), alpha, width, height, n_w, n_h, model.law, model.lever);
  });
}

}  // namespace ref
