// Quasi-static rotation rate implied by the PRE model for a rigid block of square PREs toppling in a
// base-friction model: geometry, kinematics and the moment balance in ref/base_friction_pre_face.hpp.
//
// Derivation of the instantaneous centre (linearised law): c_0 = (r - r θ, r (cos θ + sin θ)), so
// ċ_0 = Ω (-r, r (cos θ - sin θ)). A point p moves with ċ_0 + Ω ẑ x (p - c_0); it is at rest for
// p - c_0 = (-r (cos θ - sin θ), -r). Exact law: the corner is fixed, I = c_0 + R(θ)(-r, -r).
// Moment of an element's force F_e = -μ_B m_e g u_e/S_e (at c_e) about A: (c_e - A) x F_e; its spin
// moment -(2/3) μ_B m_e g r (r Ω)/S_e (M21). Dividing by -μ_B m_e g (m_e equal) gives the terms of G.
// G(0) = -Σ (c_e - A) x ĝ < 0 iff the plate's drag (along ĝ, through the centroid) turns the block
// counter-clockwise about A; G(λ -> ∞) -> Σ [(c_e - A)·(c_e - I) + (2/3) r²]/sqrt(|c_e - I|² + r²) > 0.
#include "ref/base_friction_pre_face.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "ref/base_friction_travel.hpp"
#include "ref/gsl_support.hpp"
#include "ref/require.hpp"

namespace ref {

namespace {

struct Block {
  double side;  // s = 2 r
  int n_w;
  int n_h;
};

Block require_block(const char* where, double theta, double alpha, double width, double height,
                    int n_w, int n_h) {
  detail::require_finite(where, "theta", theta);
  detail::require_finite(where, "alpha", alpha);
  if (!(theta >= 0.0 && theta <= std::numbers::pi)) detail::fail(where, "theta must lie in [0, pi] rad", theta);
  if (!(alpha >= 0.0 && alpha < 0.5 * std::numbers::pi))
    detail::fail(where, "alpha must lie in [0, pi/2) rad", alpha);
  detail::require_positive(where, "width", width);
  detail::require_positive(where, "height", height);
  if (n_w < 1) detail::fail(where, "n_w must be >= 1", n_w);
  if (n_h < 1) detail::fail(where, "n_h must be >= 1", n_h);
  const double side_w = width / n_w, side_h = height / n_h;
  if (!(std::abs(side_w - side_h) <= 1e-9 * std::max(side_w, side_h)))
    detail::fail(where, "elements must be square: W/n_w must equal H/n_h (W/n_w given)", side_w);
  return {0.5 * (side_w + side_h), n_w, n_h};
}

// G in units of the side s (lengths / s, λ s); G = s³ · moment_in_sides.
double moment_in_sides(double lambda_s, double theta, double alpha, const Block& block,
                       WallTangentialLaw law, WallLever lever) {
  constexpr double r = 0.5;
  const double c = std::cos(theta), s = std::sin(theta);
  const double gx = -std::sin(alpha), gy = -std::cos(alpha);  // ĝ, the fall line
  // Points relative to c_0.
  double ax = -r, ay = -r;  // A: resultant point of (M12) in the wall frame
  if (lever == WallLever::rotated_corner) {
    ax = -r * c + r * s;  // the rotated body corner R(θ)(-r, -r)
    ay = -r * s - r * c;
  }
  double ix, iy;                  // I: instantaneous centre
  if (law == WallTangentialLaw::linearised) {
    ix = -r * (c - s);  // (M15.2): disk-like rolling of c_0
    iy = -r;
  } else {
    ix = -r * c + r * s;  // (M3.2): the real corner R(θ)(-r, -r) is fixed
    iy = -r * s - r * c;
  }
  double sum = 0.0;
  for (int j = 0; j < block.n_h; ++j) {
    for (int i = 0; i < block.n_w; ++i) {
      const double bx = 2.0 * r * i, by = 2.0 * r * j;  // body offset of element (i, j)
      const double ex = c * bx - s * by, ey = s * bx + c * by;  // c_e - c_0
      const double dx = ex - ix, dy = ey - iy;                  // c_e - I
      const double ux = -lambda_s * dy - gx, uy = lambda_s * dx - gy;  // λ ẑ x (c_e - I) - ĝ
      const double s_e = std::sqrt(ux * ux + uy * uy + lambda_s * lambda_s * r * r);
      const double moment = (ex - ax) * uy - (ey - ay) * ux;  // ((c_e - A) x u_e)_z
      sum += (moment + (2.0 / 3.0) * r * r * lambda_s) / s_e;  // (M21) about A (M12)
    }
  }
  return sum;
}

}  // namespace

double pre_face_moment(double lambda, double theta, double alpha, double width, double height,
                       int n_w, int n_h, WallTangentialLaw law, WallLever lever) {
  constexpr const char* where = "ref::pre_face_moment";
  detail::require_finite(where, "lambda", lambda);
  const Block block = require_block(where, theta, alpha, width, height, n_w, n_h);
  const double side = block.side;
  return side * side * side * moment_in_sides(lambda * side, theta, alpha, block, law, lever);
}

double pre_face_rate(double theta, double alpha, double width, double height, int n_w, int n_h,
                     WallTangentialLaw law, WallLever lever) {
  constexpr const char* where = "ref::pre_face_rate";
  const Block block = require_block(where, theta, alpha, width, height, n_w, n_h);
  const auto moment = [&](double lambda_s) { return moment_in_sides(lambda_s, theta, alpha, block, law, lever); };
  if (moment(0.0) >= 0.0) return 0.0;  // the drag turns the block up-slope about A: no toppling
  double hi = 1.0 / block.n_h;         // λ_hi = 1/H in units of 1/s
  for (int k = 0; moment(hi) <= 0.0; ++k) {
    if (k > 60) throw std::runtime_error(std::string(where) + ": no bracket for the root");
    hi *= 2.0;
  }
  return detail::brent_root(where, moment, 0.0, hi, 1e-13, 1e-16) / block.side;
}

double theta_at_travel_pre_face(double travel, double alpha, double width, double height, int n_w,
                                int n_h, WallTangentialLaw law, WallLever lever) {
  pre_face_moment(0.0, 0.0, alpha, width, height, n_w, n_h, law, lever);  // validates the arguments
  return theta_at_travels(std::vector<double>{travel}, alpha,
                          [=](double psi) {
                            return pre_face_rate(std::max(0.0, psi - alpha), alpha, width, height, n_w, n_h, law, lever);
                          })
      .front();
}

}  // namespace ref
