// Single-DOF damped oscillator: closed form and Odeint cross-check (refs §1.1).
#include "ref/oscillator.hpp"

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <numbers>

#include "ref/require.hpp"

namespace ref {

Oscillator::Oscillator(double mass, double stiffness, double damping)
    : mass_(mass), stiffness_(stiffness), damping_(damping) {
  detail::require_positive("ref::Oscillator", "mass", mass);
  detail::require_positive("ref::Oscillator", "stiffness", stiffness);
  detail::require_non_negative("ref::Oscillator", "damping", damping);
  natural_frequency_ = std::sqrt(stiffness / mass);
  damping_ratio_ = damping / (2.0 * std::sqrt(mass * stiffness));
}

namespace {

// C(z) = sum z^k/(2k)!, S(z) = sum z^k/(2k+1)! for |z| <= 1, i.e. cos/cosh(sqrt(.)) and the
// corresponding sinc; the terms fall at least as 1/(2k)!, so 20 terms reach round-off.
struct SeriesCS {
  double c;
  double s;
};

SeriesCS series_cs(double z) {
  double c = 1.0;
  double s = 1.0;
  double term_c = 1.0;
  double term_s = 1.0;
  for (int k = 1; k < 20; ++k) {
    term_c *= z / ((2.0 * k - 1.0) * (2.0 * k));
    term_s *= z / ((2.0 * k) * (2.0 * k + 1.0));
    c += term_c;
    s += term_s;
    if (std::abs(term_c) < 1e-18 && std::abs(term_s) < 1e-18) break;
  }
  return {c, s};
}

}  // namespace

OscillatorState oscillator_state(const Oscillator& oscillator, OscillatorState initial, double t) {
  constexpr const char* where = "ref::oscillator_state";
  detail::require_finite(where, "initial position", initial.position);
  detail::require_finite(where, "initial velocity", initial.velocity);
  detail::require_non_negative(where, "t", t);

  const double x0 = initial.position;
  const double v0 = initial.velocity;
  const double w0 = oscillator.natural_frequency();
  const double zeta = oscillator.damping_ratio();
  const double beta = zeta * w0;                           // (refs §1.1)
  const double d = w0 * w0 * (1.0 - zeta) * (1.0 + zeta);  // omega_d^2 (< 0: -Omega^2)
  const double z = -d * t * t;

  if (std::abs(z) <= 1.0 || d > 0.0) {
    double c = 0.0;  // cos(omega_d t) | cosh(Omega t) | 1
    double s = 0.0;  // sin(omega_d t)/omega_d | sinh(Omega t)/Omega | t
    if (std::abs(z) <= 1.0) {
      const SeriesCS cs = series_cs(z);
      c = cs.c;
      s = t * cs.s;
    } else {
      const double wd = std::sqrt(d);
      c = std::cos(wd * t);
      s = std::sin(wd * t) / wd;
    }
    const double decay = std::exp(-beta * t);
    return {decay * (x0 * c + (v0 + beta * x0) * s),             // x(t), refs §1.1
            decay * (v0 * c - (w0 * w0 * x0 + beta * v0) * s)};  // its derivative
  }

  // Over-damped with Omega t > 1: x = c1 e^{s1 t} + c2 e^{s2 t} (refs §1.1).
  const double big_omega = std::sqrt(-d);
  const double s2 = -(beta + big_omega);
  const double s1 = -(w0 * w0) / (beta + big_omega);  // = -beta + Omega without cancellation
  const double c1 = (v0 - s2 * x0) / (2.0 * big_omega);
  const double c2 = (s1 * x0 - v0) / (2.0 * big_omega);
  const double e1 = std::exp(s1 * t);
  const double e2 = std::exp(s2 * t);
  return {c1 * e1 + c2 * e2, c1 * s1 * e1 + c2 * s2 * e2};
}

OscillatorState oscillator_state_odeint(const Oscillator& oscillator, OscillatorState initial,
                                        double t) {
  constexpr const char* where = "ref::oscillator_state_odeint";
  detail::require_finite(where, "initial position", initial.position);
  detail::require_finite(where, "initial velocity", initial.velocity);
  detail::require_non_negative(where, "t", t);

  namespace odeint = boost::numeric::odeint;
  using State = std::array<double, 2>;  // {y, u} = {x/L, v/(omega0 L)}

  const double w0 = oscillator.natural_frequency();
  const double zeta = oscillator.damping_ratio();
  const double scale = std::max(std::abs(initial.position), std::abs(initial.velocity) / w0);
  if (scale == 0.0 || t == 0.0) return initial;

  // y'' + 2 zeta y' + y = 0 in tau = omega0 t.
  const auto system = [zeta](const State& s, State& dsdt, double /*tau*/) {
    dsdt[0] = s[1];
    dsdt[1] = -s[0] - 2.0 * zeta * s[1];
  };
  State s{initial.position / scale, initial.velocity / (w0 * scale)};
  constexpr double tolerance = 1e-13;
  odeint::integrate_adaptive(
      odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<State>()), system, s,
      0.0, w0 * t, 1e-3);
  return {s[0] * scale, s[1] * w0 * scale};
}

double damping_coefficient(double mass, double stiffness, double damping_ratio) {
  constexpr const char* where = "ref::damping_coefficient";
  detail::require_positive(where, "mass", mass);
  detail::require_positive(where, "stiffness", stiffness);
  detail::require_non_negative(where, "damping_ratio", damping_ratio);
  return 2.0 * damping_ratio * std::sqrt(mass * stiffness);
}

double critical_damping(double mass, double stiffness) {
  return damping_coefficient(mass, stiffness, 1.0);  // (K20), (K25.a)
}

double damping_ratio_for_restitution(double restitution) {
  if (!(restitution >= 0.0 && restitution <= 1.0))
    detail::fail("ref::damping_ratio_for_restitution", "restitution must lie in [0, 1]",
                 restitution);
  if (restitution == 0.0) return 1.0;  // limit ln e -> -inf; every zeta >= 1 gives e_A = 0
  const double log_e = std::log(restitution);
  return -log_e / std::sqrt(std::numbers::pi * std::numbers::pi + log_e * log_e);  // refs §1.2
}

}  // namespace ref
