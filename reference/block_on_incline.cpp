// Rigid block on an incline: sliding, Goodman & Bray, Sagaseta (refs §2).
#include "ref/block_on_incline.hpp"

#include <cmath>
#include <numbers>

#include "ref/require.hpp"

namespace ref {

namespace {

void require_angle(const char* where, const char* name, double angle) {
  detail::require_finite(where, name, angle);
  if (!(angle >= 0.0 && angle < std::numbers::pi / 2.0))
    detail::fail(where, std::string(name) + " must lie in [0, pi/2) rad", angle);
}

}  // namespace

char mode_code(Mode mode) {
  switch (mode) {
    case Mode::stable:
      return '.';
    case Mode::slide:
      return 'S';
    case Mode::topple:
      return 'T';
    case Mode::slide_topple:
      return 'X';
  }
  throw std::invalid_argument("ref::mode_code: not a Mode");
}

double sliding_acceleration(double alpha, double phi, double g) {
  constexpr const char* where = "ref::sliding_acceleration";
  require_angle(where, "alpha", alpha);
  require_angle(where, "phi", phi);
  detail::require_non_negative(where, "g", g);
  return g * (std::sin(alpha) - std::cos(alpha) * std::tan(phi));  // (M20)
}

double slide_distance(double alpha, double phi, double g, double t) {
  detail::require_non_negative("ref::slide_distance", "t", t);
  const double a = sliding_acceleration(alpha, phi, g);
  return a > 0.0 ? 0.5 * a * t * t : 0.0;  // (M20)
}

Mode mode_goodman_bray(double alpha, double phi, double beta) {
  constexpr const char* where = "ref::mode_goodman_bray";
  require_angle(where, "alpha", alpha);
  require_angle(where, "phi", phi);
  detail::require_positive(where, "beta", beta);
  const double tan_alpha = std::tan(alpha);
  const bool slides = tan_alpha > std::tan(phi);
  const bool topples = tan_alpha > beta;
  if (slides) return topples ? Mode::slide_topple : Mode::slide;
  return topples ? Mode::topple : Mode::stable;
}

double toppling_friction_threshold(double alpha, double beta) {
  constexpr const char* where = "ref::toppling_friction_threshold";
  require_angle(where, "alpha", alpha);
  detail::require_positive(where, "beta", beta);
  const double t = std::tan(alpha);
  return ((4.0 * beta * beta + 1.0) * t + 3.0 * beta) / (3.0 * beta * t + beta * beta + 4.0);
}

Mode mode_sagaseta(double alpha, double phi, double beta) {
  constexpr const char* where = "ref::mode_sagaseta";
  require_angle(where, "alpha", alpha);
  require_angle(where, "phi", phi);
  detail::require_positive(where, "beta", beta);
  const double tan_alpha = std::tan(alpha);
  const double tan_phi = std::tan(phi);
  if (tan_alpha <= tan_phi && tan_alpha <= beta) return Mode::stable;
  if (tan_alpha > tan_phi && beta >= tan_phi) return Mode::slide;
  if (tan_phi >= toppling_friction_threshold(alpha, beta)) return Mode::topple;
  return Mode::slide_topple;
}

double sliding_angle(double phi) {
  require_angle("ref::sliding_angle", "phi", phi);
  return phi;
}

double toppling_angle(double beta) {
  detail::require_positive("ref::toppling_angle", "beta", beta);
  return std::atan(beta);
}

std::optional<double> slide_topple_angle(double phi, double beta) {
  constexpr const char* where = "ref::slide_topple_angle";
  require_angle(where, "phi", phi);
  detail::require_positive(where, "beta", beta);
  const double tan_phi = std::tan(phi);
  if (beta >= tan_phi) return std::nullopt;  // pure sliding is consistent: no slide + topple
  const double denominator = 4.0 * beta * beta + 1.0 - 3.0 * beta * tan_phi;
  if (denominator <= 0.0) return std::nullopt;  // T(alpha) < tan phi up to 90 degrees
  return std::atan((tan_phi * (beta * beta + 4.0) - 3.0 * beta) / denominator);
}

InitialMotion initial_motion(double alpha, double phi, double base, double height, double g) {
  constexpr const char* where = "ref::initial_motion";
  detail::require_positive(where, "base", base);
  detail::require_positive(where, "height", height);
  detail::require_positive(where, "g", g);
  const Mode mode = mode_sagaseta(alpha, phi, base / height);
  const double b = base;
  const double h = height;
  const double sin_a = std::sin(alpha);
  const double cos_a = std::cos(alpha);
  const double tan_phi = std::tan(phi);
  switch (mode) {
    case Mode::stable:
      return {mode, 0.0, 0.0, cos_a, -sin_a};
    case Mode::slide:
      return {mode, sliding_acceleration(alpha, phi, g), 0.0, cos_a, -tan_phi * cos_a};  // (M20)
    case Mode::topple: {
      const double d2 = b * b + h * h;
      const double theta_dd = 1.5 * g * (h * sin_a - b * cos_a) / d2;
      const double normal = (3.0 * b * h * sin_a + (b * b + 4.0 * h * h) * cos_a) / (4.0 * d2);
      const double friction = -((4.0 * b * b + h * h) * sin_a + 3.0 * b * h * cos_a) / (4.0 * d2);
      return {mode, 0.0, theta_dd, normal, friction};
    }
    case Mode::slide_topple: {
      const double theta_dd =
          6.0 * g * cos_a * (h * tan_phi - b) / (4.0 * b * b + h * h - 3.0 * b * h * tan_phi);
      const double normal = cos_a + theta_dd * b / (2.0 * g);  // N/(m g)
      const double slide = g * sin_a - tan_phi * normal * g - theta_dd * h / 2.0;
      return {mode, slide, theta_dd, normal, -tan_phi * normal};
    }
  }
  throw std::logic_error("ref::initial_motion: unreachable");
}

}  // namespace ref
