// Housner's rocking block (ref/rocking_block.hpp, refs §2.4).
#include "ref/rocking_block.hpp"

#include <cmath>
#include <stdexcept>

#include "ref/gsl_support.hpp"

namespace ref {

namespace {

void check(double b, double h, double theta0) {
  if (!(b > 0.0) || !(h > 0.0) || !std::isfinite(b) || !std::isfinite(h))
    throw std::invalid_argument("rocking block: b and h must be positive");
  if (!(theta0 > 0.0) || !(theta0 < std::atan2(b, h)))
    throw std::invalid_argument("rocking block: the release tilt theta0 must lie in (0, alpha), alpha = atan(b/h)");
}

double p2(double b, double h, double g) { return 3.0 * g / (4.0 * std::hypot(b, h)); }

}  // namespace

double rocking_impact_time(double b, double h, double theta0, double g) {
  check(b, h, theta0);
  const double alpha = std::atan2(b, h), q = p2(b, h, g);
  // cos(α − θ₀) − cos(α − θ) = 2 sin(α − (θ₀ + θ)/2) sin((θ₀ − θ)/2): no cancellation near θ₀. The integrand
  // 1/ω(θ) times (θ₀ − θ)^{1/2} is smooth on [0, θ₀]; QAWS supplies the weight (θ₀ − θ)^{−1/2}.
  detail::gsl_handler_off();
  detail::GuardedFunction f([&](double theta) {
    const double d = theta0 - theta;
    if (d <= 0.0) return 1.0 / std::sqrt(2.0 * q * std::sin(alpha - theta0));  // the limit at θ₀
    const double w2 = 4.0 * q * std::sin(alpha - 0.5 * (theta0 + theta)) * std::sin(0.5 * d);
    return std::sqrt(d / w2);
  });
  gsl_integration_qaws_table* table = gsl_integration_qaws_table_alloc(0.0, -0.5, 0, 0);
  if (!table) throw std::runtime_error("rocking_impact_time: GSL table allocation failed");
  auto w = detail::make_workspace(1000);
  double result = 0.0, error = 0.0;
  const int status = gsl_integration_qaws(f.gsl(), 0.0, theta0, table, 0.0, 1e-13, 1000, w.get(), &result, &error);
  gsl_integration_qaws_table_free(table);
  f.check("rocking_impact_time", status);
  return result;
}

double rocking_impact_time_linear(double b, double h, double theta0, double g) {
  check(b, h, theta0);
  const double alpha = std::atan2(b, h);
  return std::acosh(1.0 / (1.0 - theta0 / alpha)) / std::sqrt(p2(b, h, g));
}

double rocking_impact_speed(double b, double h, double theta0, double g) {
  check(b, h, theta0);
  const double alpha = std::atan2(b, h);
  return std::sqrt(2.0 * p2(b, h, g) * 2.0 * std::sin(alpha - 0.5 * theta0) * std::sin(0.5 * theta0));
}

double rocking_restitution(double b, double h) {
  if (!(b > 0.0) || !(h > 0.0)) throw std::invalid_argument("rocking block: b and h must be positive");
  const double s = std::sin(std::atan2(b, h));
  return 1.0 - 1.5 * s * s;
}

double rocking_rebound_tilt(double b, double h, double theta0) {
  check(b, h, theta0);
  const double alpha = std::atan2(b, h), r = rocking_restitution(b, h);
  const double drop = 2.0 * std::sin(alpha - 0.5 * theta0) * std::sin(0.5 * theta0);  // cos(α − θ₀) − cos α
  return alpha - std::acos(std::cos(alpha) + r * r * drop);
}

}  // namespace ref
