// Oblique impact of a disk on a wall (ref/oblique_impact.hpp).
#include "ref/oblique_impact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <boost/numeric/odeint.hpp>

#include "ref/require.hpp"

namespace ref {

namespace {

void validate(const ObliqueImpact& d) {
  constexpr const char* where = "ref::oblique_impact";
  detail::require_positive(where, "m", d.m);
  detail::require_positive(where, "r", d.r);
  detail::require_positive(where, "kn", d.kn);
  detail::require_non_negative(where, "eta_n", d.eta_n);
  detail::require_non_negative(where, "ks", d.ks);
  detail::require_non_negative(where, "eta_s", d.eta_s);
  detail::require_non_negative(where, "mu", d.mu);
  detail::require_positive(where, "v", d.v);
  if (!(std::isfinite(d.theta) && d.theta >= 0.0 && d.theta < 0.5 * std::numbers::pi))
    detail::fail(where, "theta must be in [0, pi/2)", d.theta);
  detail::require_finite(where, "omega0", d.omega0);
  if (d.eta_n >= 2.0 * std::sqrt(d.m * d.kn)) detail::fail(where, "eta_n must be below critical (the contact would not end)", d.eta_n);
}

using State = std::array<double, 5>;  // δ, δ', v_t, ω, e_s

/// The shear spring e_s within its cap μ e_n, and whether it is held there: at the cap, with a free rate that
/// would carry it past the cap's own rate (a zero cap holds against any slip).
struct Shear {
  double es;
  bool held;
  double direction;  // the sign of a held spring (of the slip's push where the cap is zero)
};
Shear shear(const ObliqueImpact& d, const State& y) {
  const double limit = d.mu * std::max(d.kn * y[0], 0.0);
  const double es = std::clamp(y[4], -limit, limit);
  const double free_rate = d.ks * (y[2] + d.r * y[3]);
  const double limit_rate = d.mu * d.kn * y[1];
  if (limit == 0.0) return {0.0, std::abs(free_rate) > std::max(limit_rate, 0.0), std::copysign(1.0, free_rate)};
  const bool at_cap = std::abs(es) >= limit * (1.0 - 1e-12);
  return {es, at_cap && std::copysign(1.0, es) * free_rate > limit_rate, std::copysign(1.0, es)};
}

}  // namespace

ObliqueRebound oblique_impact(const ObliqueImpact& d) {
  validate(d);
  namespace odeint = boost::numeric::odeint;
  const double inertia = 0.5 * d.m * d.r * d.r;
  const auto system = [&](const State& y, State& dy, double /*t*/) {
    const double slip_rate = y[2] + d.r * y[3];
    const Shear e = shear(d, y);
    const bool at_cap = e.held;
    const double f = e.es + (at_cap ? 0.0 : d.eta_s * slip_rate);  // (K13.b): no dashpot at the cap
    dy[0] = y[1];
    dy[1] = -(d.kn * y[0] + d.eta_n * y[1]) / d.m;
    dy[2] = -f / d.m;
    dy[3] = -d.r * f / inertia;
    dy[4] = at_cap ? e.direction * d.mu * d.kn * y[1] : d.ks * slip_rate;
  };
  const double period = 2.0 * std::numbers::pi / std::sqrt(d.kn / d.m);
  const double h = period / 40000.0;
  State y{0.0, d.v * std::cos(d.theta), d.v * std::sin(d.theta), d.omega0, 0.0};
  odeint::runge_kutta4<State> stepper;
  double t = 0.0;
  for (long step = 0;; ++step) {
    if (step > 400000) throw std::runtime_error("ref::oblique_impact: the contact did not end within 10 normal periods");
    const State before = y;
    stepper.do_step(system, y, t, h);
    t += h;
    const double limit = d.mu * std::max(d.kn * y[0], 0.0);
    y[4] = std::clamp(y[4], -limit, limit);  // the projection onto the cap (K13.a)
    if (y[0] <= 0.0 && step > 0) {  // (K8): e_n = K_n δ reached zero between the last two steps
      const double w = before[0] / (before[0] - y[0]);
      const auto at = [&](int k) { return before[k] + w * (y[k] - before[k]); };
      return {-at(1), at(2), at(3), t - h + w * h};
    }
  }
}

}  // namespace ref
