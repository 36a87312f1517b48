// Bray & Goodman's base-friction rotation integral (M25) two ways, its root λ(psi), and the sliding
// relation M22 (refs §3.1, §3.2, §3.5). Geometry and signs: ref/base_friction.hpp.
//
// (M25), refs §3.1. Paper's hand: T = (ρ x ĝ)_z = w cos psi - h sin psi, λ = θ'/v_B. A point ρ moves
// with V = Ω ẑ x ρ, the plate with V_B = v_B ĝ; the traction is -μ_B p (V - V_B)/|V - V_B|. Then
//   (ρ x (V - V_B))_z = Ω R² - v_B T,   |V - V_B|² = v_B² (1 - 2Tλ + λ²R²),
// and the moment about P, -μ_B p |v_B|/v_B ∫ (λR² - T)/sqrt(1 - 2Tλ + λ²R²) dA, vanishes:
//   F(λ) = ∫∫ (T - λR²)/sqrt(1 - 2Tλ + λ²R²) dw dh = 0.                                      (M25)
//
// Properties used (refs §3.2):
//  - ∂/∂λ of the integrand = (T² - R²)/(1 - 2Tλ + λ²R²)^{3/2} <= 0 since |T| <= R: F is
//    non-increasing, the root is unique; F(0) = ∫T dA = W H T_cm, T_cm = (W/2) cos psi - (H/2) sin
//    psi; F(λ -> -∞) -> ∫R dA > 0. Toppling <=> F(0) < 0 <=> tan psi > W/H.
//  - 1 - 2Tλ + λ²R² = (1 - Tλ)² + (λN)², N = w sin psi + h cos psi (T² + N² = R²), so it cannot go
//    negative by rounding. It vanishes only at the instantaneous centre ρ0 = (cos psi, -sin psi)/λ,
//    the block point that moves with the plate ((w0, h0) = (-cos psi, sin psi)/|λ| while toppling).
//    There the integrand is bounded (|·| <= R) but its direction jumps.
//
// Second evaluation (refs §3.2). With d = ρ - ρ0: T = ρ·ρ0 λ, so T - λR² = -λ(|d|² + ρ0·d), and
// 1 - 2Tλ + λ²R² = λ²|d|²; hence the integrand is -sgn(λ) (|d| + ρ0·d/|d|) and
//   F = -sgn(λ) [ ∬ |d| dA + ρ0 · ∬ d/|d| dA ]
// over x = w - w0 ∈ [-w0, W - w0], y = h - h0 ∈ [-h0, H - h0]. Antiderivatives (∂²/∂x∂y of each gives
// its integrand; every x² asinh(y/|x|) term -> 0 as x -> 0):
//   ∬ r:    G(x, y)  = [2xy r + x³ asinh(y/|x|) + y³ asinh(x/|y|)] / 6,
//   ∬ x/r:  Hx(x, y) = [y r + x² asinh(y/|x|)] / 2,      ∬ y/r:  Hy(x, y) = Hx(y, x).
// Corner values grow like |ρ0|³ = |λ|⁻³ while F stays O(L³) (L = max(W, H)): the sum loses about
// (|λ|L)⁻³ relative accuracy. Below |λ|L = 0.2 the centre is more than 3.5 L from the block, the
// integrand is analytic well beyond it, and a 24 x 24 Gauss-Legendre product rule is exact to
// rounding instead (its error ~ (2·3.5)^-48).
#include "ref/base_friction.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>

#include "ref/gsl_support.hpp"
#include "ref/require.hpp"

namespace ref {

namespace {

// The problem scaled by L = max(W, H): lengths / L, λL; F = L³ F_scaled.
struct Scaled {
  double width;   // W/L
  double height;  // H/L
  double lambda;  // λL
  double cos_psi;
  double sin_psi;
};

Scaled scale(double lambda, double psi, double width, double height) {
  const double length = std::max(width, height);
  return {width / length, height / length, lambda * length, std::cos(psi), std::sin(psi)};
}

// Below this |λ|L the instantaneous centre is more than 5L from P (3.5L from the block).
constexpr double far_centre_below = 0.2;

// (T - λR²)/sqrt(1 - 2Tλ + λ²R²), the integrand of (M25) as written. Accurate while ρ0 is far from
// the block. Near ρ0 the numerator and the root are small differences of O(|ρ0|) terms and the
// quotient is noisy (relative ε|ρ0|/|d|), which an adaptive rule mistakes for structure.
double integrand_as_written(const Scaled& s, double w, double h) {
  const double t = w * s.cos_psi - h * s.sin_psi;
  const double n = w * s.sin_psi + h * s.cos_psi;
  const double a = 1.0 - t * s.lambda;
  const double d2 = a * a + (s.lambda * n) * (s.lambda * n);
  if (d2 == 0.0) return 0.0;  // ρ0 itself, a set of measure zero
  return (t - s.lambda * (w * w + h * h)) / std::sqrt(d2);
}

// The same integrand about the centre, -sgn(λ) (|d| + ρ0·d/|d|) (identity above). With ρ0 rounded
// once, w - w0 is exact near ρ0, so this is smooth in the abscissae up to the one direction jump at
// ρ0. Used for |λ|L >= far_centre_below, where |ρ0| <= 5L and the sum loses at most a few ulp.
double integrand_about_centre(const Scaled& s, double w, double h) {
  const double w0 = s.cos_psi / s.lambda;
  const double h0 = -s.sin_psi / s.lambda;
  const double x = w - w0, y = h - h0;
  const double r = std::sqrt(x * x + y * y);  // |d| <= 6L: no overflow
  if (r == 0.0) return 0.0;
  return -std::copysign(1.0, s.lambda) * (r + (w0 * x + h0 * y) / r);
}

double integrand(const Scaled& s, double w, double h) {
  return std::abs(s.lambda) < far_centre_below ? integrand_as_written(s, w, h)
                                               : integrand_about_centre(s, w, h);
}

// ---- nested adaptive quadrature -------------------------------------------------------------------
//
// Outer over h, inner over w (refs §3.2): epsabs = tol·W·H·L (m³; tol·(W/L)(H/L) in scaled units),
// epsrel = tol; the inner integrals 10x tighter so that their errors do not disturb the outer rule.
// Near ρ0 the integrand varies on the scale of the distance to ρ0. Along an inner line h = const
// the direction term ρ0·d/|d| turns over a width |h - h0| at w0, a first-order effect (about
// |ρ0||h - h0| log) that a Gauss-Kronrod rule whose outermost node misses it does not report. So the
// inner integral gets break points graded towards w0: w0 and w0 ± σ·4^k (σ = |h - h0|, k = 0, 1,
// ...) inside (0, W) (qagp); each sub-interval then lies at least a third of its length from the
// feature. The inner integral is continuous in h with a slope singularity at h0, which qagp's
// bisection towards the break point h0 resolves (a feature of width e next to it costs ~e²). This
// is refs §3.2's "pass w0 (h0) as break points", made robust for ρ0 on or near the block's edge.
// With ρ0 far away (|λ|L < far_centre_below) both levels are plain GAUSS61.

constexpr std::size_t workspace_limit = 2000;

struct BreakPoints {
  static constexpr std::size_t per_side = 40;
  double point[2 * per_side + 3];
  std::size_t count = 0;
};

// a, b and the points centre, centre ± σ 4^k that lie inside (a, b), ascending.
BreakPoints graded_break_points(double a, double b, double centre, double width) {
  const double sigma = std::max(width, 1e-14 * (b - a));
  const double reach = (b - a) + std::max(std::abs(centre - a), std::abs(centre - b));
  double above[BreakPoints::per_side], below[BreakPoints::per_side];
  std::size_t n = 0;
  for (double step = sigma; step < reach && n < BreakPoints::per_side; step *= 4.0, ++n) {
    above[n] = centre + step;
    below[n] = centre - step;
  }
  BreakPoints points;
  points.point[points.count++] = a;
  for (std::size_t i = n; i-- > 0;)
    if (below[i] > a && below[i] < b) points.point[points.count++] = below[i];
  if (centre > a && centre < b) points.point[points.count++] = centre;
  for (std::size_t i = 0; i < n; ++i)
    if (above[i] > a && above[i] < b) points.point[points.count++] = above[i];
  points.point[points.count++] = b;
  return points;
}

struct Nested {
  Scaled s;
  double inner_abs;
  double inner_rel;
  bool graded;  // break points about ρ0 (|λ|L >= far_centre_below)
  double w0, h0;
  gsl_integration_workspace* inner_workspace;
  double h = 0.0;  // current outer abscissa
  int status = GSL_SUCCESS;
};

double inner_integrand(double w, void* p) {
  const auto* q = static_cast<const Nested*>(p);
  return integrand(q->s, w, q->h);
}

// The inner integral over [0, W] at q.h. No C++ exception can arise in here (GSL calls it).
double outer_integrand(double h, void* p) {
  auto* q = static_cast<Nested*>(p);
  q->h = h;
  gsl_function f{&inner_integrand, q};
  double result = 0.0, error = 0.0;
  int status = GSL_SUCCESS;
  if (q->graded) {
    BreakPoints points = graded_break_points(0.0, q->s.width, q->w0, std::abs(h - q->h0));
    status = gsl_integration_qagp(&f, points.point, points.count, q->inner_abs, q->inner_rel,
                                  workspace_limit, q->inner_workspace, &result, &error);
  } else {
    status = gsl_integration_qag(&f, 0.0, q->s.width, q->inner_abs, q->inner_rel, workspace_limit,
                                 GSL_INTEG_GAUSS61, q->inner_workspace, &result, &error);
  }
  if (status != GSL_SUCCESS && q->status == GSL_SUCCESS) q->status = status;
  return result;
}

double moment_quadrature_scaled(const Scaled& s, double tolerance) {
  constexpr const char* where = "ref::base_friction_moment";
  detail::gsl_handler_off();
  detail::Workspace outer_workspace = detail::make_workspace(workspace_limit);
  detail::Workspace inner_workspace = detail::make_workspace(workspace_limit);
  const bool graded = std::abs(s.lambda) >= far_centre_below;
  Nested q{.s = s,
           .inner_abs = 0.1 * tolerance * s.width,
           .inner_rel = std::max(0.1 * tolerance, 1e-13),
           .graded = graded,
           .w0 = graded ? s.cos_psi / s.lambda : 0.0,  // instantaneous centre ρ0
           .h0 = graded ? -s.sin_psi / s.lambda : 0.0,
           .inner_workspace = inner_workspace.get()};
  gsl_function f{&outer_integrand, &q};
  const double outer_abs = tolerance * s.width * s.height;
  double result = 0.0, error = 0.0;
  int status = GSL_SUCCESS;
  if (graded && q.h0 > 0.0 && q.h0 < s.height) {
    double points[3] = {0.0, q.h0, s.height};
    status = gsl_integration_qagp(&f, points, 3, outer_abs, tolerance, workspace_limit,
                                  outer_workspace.get(), &result, &error);
  } else {
    status = gsl_integration_qag(&f, 0.0, s.height, outer_abs, tolerance, workspace_limit,
                                 GSL_INTEG_GAUSS61, outer_workspace.get(), &result, &error);
  }
  if (status != GSL_SUCCESS) detail::gsl_failure(where, status);
  if (q.status != GSL_SUCCESS) detail::gsl_failure(std::string(where) + " (inner)", q.status);
  return result;
}

// ---- closed form ----------------------------------------------------------------------------------

// x² asinh(y/|x|), continued by 0 at x = 0 (it vanishes like x² log|x|).
double x2_asinh(double x, double y) {
  if (x == 0.0) return 0.0;
  const double q = y / std::abs(x);
  if (!std::isfinite(q)) return 0.0;
  return x * x * std::asinh(q);
}

double antiderivative_r(double x, double y) {  // G
  return (2.0 * x * y * std::hypot(x, y) + x * x2_asinh(x, y) + y * x2_asinh(y, x)) / 6.0;
}

double antiderivative_x_over_r(double x, double y) {  // Hx
  return (y * std::hypot(x, y) + x2_asinh(x, y)) / 2.0;
}

double antiderivative_y_over_r(double x, double y) { return antiderivative_x_over_r(y, x); }  // Hy

template <class Antiderivative>
double over_rectangle(Antiderivative f, double x1, double x2, double y1, double y2) {
  return (f(x2, y2) - f(x1, y2)) - (f(x2, y1) - f(x1, y1));
}

struct GaussLegendre {
  static constexpr std::size_t order = 24;
  double node[order];    // on [0, 1]
  double weight[order];  // on [0, 1]
  GaussLegendre() {
    gsl_integration_glfixed_table* table = gsl_integration_glfixed_table_alloc(order);
    if (table == nullptr) throw std::runtime_error("ref: GSL Gauss-Legendre table allocation");
    for (std::size_t i = 0; i < order; ++i)
      gsl_integration_glfixed_point(0.0, 1.0, i, &node[i], &weight[i], table);
    gsl_integration_glfixed_table_free(table);
  }
};

double moment_closed_form_scaled(const Scaled& s) {
  if (std::abs(s.lambda) < far_centre_below) {  // Gauss-Legendre: the closed form would cancel
    static const GaussLegendre rule;
    double sum = 0.0;
    for (std::size_t j = 0; j < GaussLegendre::order; ++j) {
      double row = 0.0;
      for (std::size_t i = 0; i < GaussLegendre::order; ++i)
        row += rule.weight[i] *
               integrand_as_written(s, rule.node[i] * s.width, rule.node[j] * s.height);
      sum += rule.weight[j] * row;
    }
    return sum * s.width * s.height;
  }
  const double w0 = s.cos_psi / s.lambda;
  const double h0 = -s.sin_psi / s.lambda;
  const double x1 = -w0, x2 = s.width - w0, y1 = -h0, y2 = s.height - h0;
  const double abs_d = over_rectangle(antiderivative_r, x1, x2, y1, y2);
  const double unit_x = over_rectangle(antiderivative_x_over_r, x1, x2, y1, y2);
  const double unit_y = over_rectangle(antiderivative_y_over_r, x1, x2, y1, y2);
  return -std::copysign(1.0, s.lambda) * (abs_d + (w0 * unit_x + h0 * unit_y));
}

void require_block(const char* where, double width, double height) {
  detail::require_positive(where, "width", width);
  detail::require_positive(where, "height", height);
}

}  // namespace

double base_friction_moment(double lambda, double psi, double width, double height,
                            double tolerance) {
  constexpr const char* where = "ref::base_friction_moment";
  detail::require_finite(where, "lambda", lambda);
  detail::require_finite(where, "psi", psi);
  require_block(where, width, height);
  if (!(tolerance >= 1e-13 && tolerance <= 1e-2))
    detail::fail(where, "tolerance must lie in [1e-13, 1e-2]", tolerance);
  const double length = std::max(width, height);
  return length * length * length *
         moment_quadrature_scaled(scale(lambda, psi, width, height), tolerance);  // (M25)
}

double base_friction_moment_closed_form(double lambda, double psi, double width, double height) {
  constexpr const char* where = "ref::base_friction_moment_closed_form";
  detail::require_finite(where, "lambda", lambda);
  detail::require_finite(where, "psi", psi);
  require_block(where, width, height);
  const double length = std::max(width, height);
  return length * length * length * moment_closed_form_scaled(scale(lambda, psi, width, height));
}

double base_friction_lambda(double psi, double width, double height, MomentEvaluation evaluation) {
  constexpr const char* where = "ref::base_friction_lambda";
  detail::require_finite(where, "psi", psi);
  if (!(psi >= 0.0 && psi <= std::numbers::pi))
    detail::fail(where, "psi must lie in [0, pi] rad", psi);
  require_block(where, width, height);
  const Scaled s = scale(0.0, psi, width, height);
  // F(0) = W H T_cm (refs §3.2): the block stays on its base when T_cm >= 0.
  if (s.width * s.cos_psi - s.height * s.sin_psi >= 0.0) return 0.0;

  if (evaluation != MomentEvaluation::quadrature && evaluation != MomentEvaluation::closed_form)
    throw std::invalid_argument(std::string(where) + ": unknown MomentEvaluation");
  const auto moment = [&s, evaluation](double lambda_scaled) {
    Scaled at = s;
    at.lambda = lambda_scaled;
    return evaluation == MomentEvaluation::quadrature
               ? moment_quadrature_scaled(at, base_friction_quadrature_tolerance)
               : moment_closed_form_scaled(at);
  };
  // Bracket: λ_lo = -2^k/H until F(λ_lo) > 0 (F(-∞) = ∫R dA > 0); F(0) < 0.
  double lo = -1.0 / s.height;
  for (int k = 0; moment(lo) <= 0.0; ++k) {
    if (k > 60) throw std::runtime_error(std::string(where) + ": no bracket for the root");
    lo *= 2.0;
  }
  const double length = std::max(width, height);
  // Relative 1e-12 (refs §3.2); the absolute 1e-15 (of λL ~ 1) only ends the search for a root
  // within rounding of 0, just past the toppling angle.
  return detail::brent_root(where, moment, lo, 0.0, 1e-12, 1e-15) / length;  // (M25) solved for λ
}

double base_friction_rate(double psi, double width, double height, MomentEvaluation evaluation) {
  return -base_friction_lambda(psi, width, height, evaluation);  // dθ/dδ_B = -λ (refs §3.1)
}

// (M22), refs §3.5. Slope axes: t̂ down-slope, n̂ outward normal; ĝ = sin alpha t̂ - cos alpha n̂.
// The block slides without rotating at k v t̂, so u = (V - V_B)/v = (k - sin alpha) t̂ + cos alpha n̂
// is the same everywhere and the traction is a uniform -μ_B p û. Quasi-static balance with the
// slope's normal force N n̂ and friction -tan phi_w N t̂:
//   normal:     N = μ_B p A cos alpha/|u|,
//   tangential: -μ_B p A (k - sin alpha)/|u| = tan phi_w N  =>  k = sin alpha - tan phi_w cos alpha.
double slide_ratio(double alpha, double wall_friction_angle) {
  constexpr const char* where = "ref::slide_ratio";
  detail::require_finite(where, "alpha", alpha);
  if (!(alpha >= 0.0 && alpha <= std::numbers::pi / 2.0))
    detail::fail(where, "alpha must lie in [0, pi/2] rad", alpha);
  detail::require_finite(where, "wall_friction_angle", wall_friction_angle);
  if (!(wall_friction_angle >= 0.0 && wall_friction_angle < std::numbers::pi / 2.0))
    detail::fail(where, "wall_friction_angle must lie in [0, pi/2) rad", wall_friction_angle);
  const double k = std::sin(alpha) - std::tan(wall_friction_angle) * std::cos(alpha);  // (M22)
  return k > 0.0 ? k : 0.0;  // k <= 0: the slope's friction holds the block
}

}  // namespace ref
