// Normal impact of a linear spring-dashpot with no tension (refs §1.2).
#include "ref/impact.hpp"

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "ref/require.hpp"

namespace ref {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// omega0 t_m = g(zeta): the scaled time of maximum overlap (zero of x' for x0 = 0, v0 > 0).
double scaled_time_of_maximum_overlap(double zeta) {
  if (zeta == 1.0) return 1.0;
  if (zeta < 1.0) return std::acos(zeta) / std::sqrt((1.0 - zeta) * (1.0 + zeta));
  return std::acosh(zeta) / std::sqrt((zeta - 1.0) * (zeta + 1.0));
}

void require_damping_ratio(const char* where, double zeta) {
  detail::require_non_negative(where, "damping_ratio", zeta);
}

}  // namespace

double restitution(ContactEnd end, double damping_ratio) {
  require_damping_ratio("ref::restitution", damping_ratio);
  const double zeta = damping_ratio;
  if (end == ContactEnd::elastic_force_zero) {
    if (zeta >= 1.0) return 0.0;  // the overlap never returns to zero (refs §1.2)
    return std::exp(-std::numbers::pi * zeta / std::sqrt((1.0 - zeta) * (1.0 + zeta)));
  }
  return std::exp(-zeta * scaled_contact_duration(end, zeta));  // e_B = exp(-beta t_c)
}

double scaled_contact_duration(ContactEnd end, double damping_ratio) {
  require_damping_ratio("ref::scaled_contact_duration", damping_ratio);
  const double zeta = damping_ratio;
  if (end == ContactEnd::elastic_force_zero) {
    if (zeta >= 1.0) return infinity;
    return std::numbers::pi / std::sqrt((1.0 - zeta) * (1.0 + zeta));  // t_c = pi/omega_d
  }
  // Total force zero <=> x'' = 0; for x0 = 0 this happens at exactly twice the time of maximum
  // overlap (refs §1.2 branches reduce to this).
  return 2.0 * scaled_time_of_maximum_overlap(zeta);
}

double contact_duration(ContactEnd end, const Oscillator& contact) {
  return scaled_contact_duration(end, contact.damping_ratio()) / contact.natural_frequency();
}

MaximumOverlap maximum_overlap(const Oscillator& contact, double approach_speed) {
  detail::require_positive("ref::maximum_overlap", "approach_speed", approach_speed);
  const double w0 = contact.natural_frequency();
  const double zeta = contact.damping_ratio();
  const double tau = scaled_time_of_maximum_overlap(zeta);
  return {approach_speed / w0 * std::exp(-zeta * tau), tau / w0};
}

ImpactOutcome impact_odeint(ContactEnd end, const Oscillator& contact, double approach_speed,
                            double max_scaled_time) {
  constexpr const char* where = "ref::impact_odeint";
  detail::require_positive(where, "approach_speed", approach_speed);
  detail::require_positive(where, "max_scaled_time", max_scaled_time);

  namespace odeint = boost::numeric::odeint;
  using State = std::array<double, 2>;  // {y, u} = {x omega0/v0, x'/v0}
  constexpr double tolerance = 1e-13;
  const auto make_stepper = [] {
    return odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<State>());
  };

  const double zeta = contact.damping_ratio();
  const double w0 = contact.natural_frequency();
  // y'' + 2 zeta y' + y = 0 while in contact.
  const auto system = [zeta](const State& s, State& dsdt, double /*tau*/) {
    dsdt[0] = s[1];
    dsdt[1] = -s[0] - 2.0 * zeta * s[1];
  };
  // End conditions (positive while in contact) and the maximum-overlap condition u = 0.
  const auto end_function = [zeta, end](const State& s) {
    return end == ContactEnd::elastic_force_zero ? s[0]
                                                 : s[0] + 2.0 * zeta * s[1];  // K x [+ eta x']
  };
  const auto velocity_function = [](const State& s) { return s[1]; };

  // Smallest tau in (tau_a, tau_b] with f <= 0, given f(state(tau_a)) > 0 >= f(state(tau_b)),
  // by bisection; state(tau) comes from re-integrating from (tau_a, s_a).
  const auto locate = [&](const std::function<double(const State&)>& f, const State& s_a,
                          double tau_a, double tau_b, State& s_root) {
    const auto state_at = [&](double tau) {
      State s = s_a;
      if (tau > tau_a)
        odeint::integrate_adaptive(make_stepper(), system, s, tau_a, tau, tau - tau_a);
      return s;
    };
    double lo = tau_a;
    double hi = tau_b;
    for (int i = 0; i < 200 && hi - lo > 2.0 * std::numeric_limits<double>::epsilon() * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (f(state_at(mid)) > 0.0)
        lo = mid;
      else
        hi = mid;
    }
    const double tau = 0.5 * (lo + hi);
    s_root = state_at(tau);
    return tau;
  };

  auto stepper = make_stepper();
  State s{0.0, 1.0};
  double tau = 0.0;
  double dtau = 1e-3;
  double log_scale = 0.0;  // true scaled state = s * exp(log_scale)
  ImpactOutcome outcome{infinity, 0.0, std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::quiet_NaN()};
  bool maximum_found = false;

  while (tau < max_scaled_time) {
    const State s_prev = s;
    const double tau_prev = tau;
    while (stepper.try_step(system, s, tau, dtau) == odeint::fail) {
    }
    if (!maximum_found && velocity_function(s_prev) > 0.0 && velocity_function(s) <= 0.0) {
      State s_max{};
      const double tau_max = locate(velocity_function, s_prev, tau_prev, tau, s_max);
      outcome.maximum_overlap = s_max[0] * std::exp(log_scale) * approach_speed / w0;
      outcome.time_of_maximum_overlap = tau_max / w0;
      maximum_found = true;
    }
    if (end_function(s_prev) > 0.0 && end_function(s) <= 0.0) {
      State s_end{};
      const double tau_end = locate(end_function, s_prev, tau_prev, tau, s_end);
      outcome.duration = tau_end / w0;
      outcome.restitution = -s_end[1] * std::exp(log_scale);
      return outcome;
    }
    const double norm = std::max(std::abs(s[0]), std::abs(s[1]));
    if (norm < 0.5) {  // linear homogeneous: rescale, keep the tolerance relative
      s[0] /= norm;
      s[1] /= norm;
      log_scale += std::log(norm);
      stepper.reset();  // the FSAL derivative cache refers to the old scale
    }
  }
  return outcome;
}

}  // namespace ref
