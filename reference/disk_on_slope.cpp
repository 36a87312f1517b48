// A disk released on a slope: sticking on the shear spring, then Coulomb sliding (ref/disk_on_slope.hpp).
#include "ref/disk_on_slope.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ref/oscillator.hpp"
#include "ref/require.hpp"

namespace ref {

namespace {

void validate(const DiskOnSlope& d, double t) {
  constexpr const char* where = "ref::disk_on_slope";
  detail::require_positive(where, "m", d.m);
  detail::require_positive(where, "kn", d.kn);
  detail::require_positive(where, "s", d.s);
  detail::require_non_negative(where, "zeta", d.zeta);
  if (!(std::isfinite(d.alpha) && d.alpha > 0.0 && d.alpha < 0.5 * std::numbers::pi))
    detail::fail(where, "alpha must be in (0, pi/2)", d.alpha);
  if (!(std::isfinite(d.phi) && d.phi >= 0.0 && d.phi < 0.5 * std::numbers::pi))
    detail::fail(where, "phi must be in [0, pi/2)", d.phi);
  detail::require_positive(where, "g", d.g);
  detail::require_non_negative(where, "t", t);
}

/// The sticking phase: s(t), s'(t) of (m/3) s'' + η_s s' + K_s s = (m/3) g sin α from rest.
struct StickPhase {
  Oscillator slip;
  double s_eq;
  OscillatorState at(double t) const {
    const OscillatorState y = oscillator_state(slip, {-s_eq, 0.0}, t);  // s = s_eq + y
    return {s_eq + y.position, y.velocity};
  }
};

StickPhase stick_phase(const DiskOnSlope& d) {
  const double ks = d.s * d.kn;                                              // (K24)
  const double eta_s = damping_coefficient(d.m, d.kn, d.zeta) * std::sqrt(d.s);  // (K25.b)
  return {Oscillator(d.m / 3.0, ks, eta_s), d.m * d.g * std::sin(d.alpha) / (3.0 * ks)};
}

/// The first time ≤ t_end at which K_s s reaches μN, or a negative value if it does not.
double slip_onset(const DiskOnSlope& d, const StickPhase& p, double t_end) {
  const double limit = std::tan(d.phi) * d.m * d.g * std::cos(d.alpha) / (d.s * d.kn);  // μN/K_s (K13, K28)
  const double h = 2.0 * std::numbers::pi / p.slip.natural_frequency() / 400.0;
  double lo = 0.0;
  for (double hi = h;; hi += h) {
    const double end = std::min(hi, t_end);
    if (p.at(end).position >= limit) {
      double a = lo, b = end;
      for (int k = 0; k < 200 && b - a > 1e-15 * b; ++k) {
        const double c = 0.5 * (a + b);
        (p.at(c).position >= limit ? b : a) = c;
      }
      return b;
    }
    if (end >= t_end) return -1.0;
    lo = end;
  }
}

DiskMotion sticking(const DiskOnSlope& d, const StickPhase& p, double t) {
  const OscillatorState s = p.at(t);
  const double drive = d.g * std::sin(d.alpha);
  const double v = (2.0 / 3.0) * drive * t + s.velocity / 3.0;
  return {drive * t * t / 3.0 + s.position / 3.0, v, v - s.velocity, false};
}

}  // namespace

DiskMotion disk_on_slope(const DiskOnSlope& d, double t) {
  validate(d, t);
  const StickPhase p = stick_phase(d);
  const double t1 = slip_onset(d, p, t);
  if (t1 < 0.0) return sticking(d, p, t);
  const DiskMotion at1 = sticking(d, p, t1);
  const double mu_g = std::tan(d.phi) * d.g * std::cos(d.alpha), a = d.g * std::sin(d.alpha) - mu_g, tau = t - t1;
  return {at1.x + at1.v * tau + 0.5 * a * tau * tau, at1.v + a * tau, at1.spin_speed + 2.0 * mu_g * tau, true};
}

}  // namespace ref
