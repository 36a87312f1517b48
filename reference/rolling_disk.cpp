// A disk with rolling resistance on a wall (ref/rolling_disk.hpp).
#include "ref/rolling_disk.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <boost/numeric/odeint.hpp>

#include "ref/require.hpp"

namespace ref {

namespace {

void validate(const RollingDisk& d, double t) {
  constexpr const char* where = "ref::rolling_disk";
  detail::require_positive(where, "m", d.m);
  detail::require_positive(where, "r", d.r);
  detail::require_positive(where, "g", d.g);
  if (!(std::isfinite(d.alpha) && d.alpha >= 0.0 && d.alpha < 0.5 * std::numbers::pi))
    detail::fail(where, "alpha must be in [0, pi/2)", d.alpha);
  detail::require_positive(where, "ks", d.ks);
  detail::require_non_negative(where, "eta_s", d.eta_s);
  detail::require_non_negative(where, "mu", d.mu);
  detail::require_positive(where, "kr", d.kr);
  detail::require_non_negative(where, "cr", d.cr);
  detail::require_non_negative(where, "mu_r", d.mu_r);
  detail::require_finite(where, "v0", d.v0);
  detail::require_non_negative(where, "t", t);
}

using State = std::array<double, 6>;  // x, v, φ, ω, e_s, M_k

/// A spring held at ±limit while its rate pushes it outward: its rate, and whether it is held.
struct Held {
  double rate;
  bool held;
};
Held spring_rate(double value, double rate, double limit) {
  const bool held = std::abs(value) >= limit && value * rate > 0.0;
  return {held ? 0.0 : rate, held};
}

struct Forces {
  double f, m;  // the contact's shear force F and rolling moment M on the disk
  double es_rate, mk_rate;
};

Forces forces(const RollingDisk& d, const State& y) {
  const double n = d.m * d.g * std::cos(d.alpha);
  const double slip_rate = y[1] + d.r * y[3];  // s' = v + r φ'
  const double shear_limit = d.mu * n, roll_limit = d.mu_r * d.r * n;
  const Held es = spring_rate(y[4], d.ks * slip_rate, shear_limit);     // (K10, K13)
  const Held mk = spring_rate(y[5], -d.kr * y[3], roll_limit);          // (R3, R4)
  const double e_s = std::clamp(y[4], -shear_limit, shear_limit);
  const double m_k = std::clamp(y[5], -roll_limit, roll_limit);
  return {e_s + (es.held ? 0.0 : d.eta_s * slip_rate), m_k + (mk.held ? 0.0 : -d.cr * y[3]), es.rate, mk.rate};
}

}  // namespace

RollingDiskState rolling_disk(const RollingDisk& d, double t) {
  validate(d, t);
  namespace odeint = boost::numeric::odeint;
  const double inertia = 0.5 * d.m * d.r * d.r;
  const double g_t = d.g * std::sin(d.alpha);
  const auto system = [&](const State& y, State& dy, double /*t*/) {
    const Forces f = forces(d, y);
    dy[0] = y[1];
    dy[1] = g_t - f.f / d.m;
    dy[2] = y[3];
    dy[3] = (-d.r * f.f + f.m) / inertia;
    dy[4] = f.es_rate;
    dy[5] = f.mk_rate;
  };
  State y{0.0, d.v0, 0.0, -d.v0 / d.r, 0.0, 0.0};
  if (t > 0.0) {
    // Steps no longer than a tenth of the fastest period (the shear and the rolling oscillators) so that no
    // switch of a held spring is stepped over unseen.
    const double w = std::max(std::sqrt(3.0 * d.ks / d.m), std::sqrt(d.kr / (3.0 * inertia)));
    const double max_dt = 0.1 * 2.0 * std::numbers::pi / w;
    auto stepper = odeint::make_dense_output(1e-12, 1e-12, max_dt, odeint::runge_kutta_dopri5<State>());
    stepper.initialize(y, 0.0, std::min(max_dt, t) * 1e-3);
    for (long step = 0; stepper.current_time() < t; ++step) {
      if (step > 50000000) throw std::runtime_error("ref::rolling_disk: too many steps");
      stepper.do_step(system);
    }
    stepper.calc_state(t, y);
  }
  const Forces f = forces(d, y);
  return {y[0], y[1], y[3], f.m};
}

double rolling_stop_distance(double v0, double mu_r, double g) {
  detail::require_finite("ref::rolling_stop_distance", "v0", v0);
  detail::require_positive("ref::rolling_stop_distance", "mu_r", mu_r);
  detail::require_positive("ref::rolling_stop_distance", "g", g);
  return 3.0 * v0 * v0 / (4.0 * mu_r * g);  // v0²/(2a), a = (2/3) μ_r g
}

double rolling_stop_time(double v0, double mu_r, double g) {
  detail::require_finite("ref::rolling_stop_time", "v0", v0);
  detail::require_positive("ref::rolling_stop_time", "mu_r", mu_r);
  detail::require_positive("ref::rolling_stop_time", "g", g);
  return 3.0 * std::abs(v0) / (2.0 * mu_r * g);
}

double rolling_slope_acceleration(double alpha, double mu_r, double g) {
  if (!(std::isfinite(alpha) && alpha >= 0.0 && alpha < 0.5 * std::numbers::pi))
    detail::fail("ref::rolling_slope_acceleration", "alpha must be in [0, pi/2)", alpha);
  detail::require_non_negative("ref::rolling_slope_acceleration", "mu_r", mu_r);
  detail::require_positive("ref::rolling_slope_acceleration", "g", g);
  // (m + I/r²) a = m g sin α − μ_r m g cos α with I = ½ m r²; no motion while the moment holds
  return std::max(0.0, (2.0 / 3.0) * g * (std::sin(alpha) - mu_r * std::cos(alpha)));
}

double rolling_rigid_velocity(double v0, double alpha, double mu_r, double g, double t) {
  constexpr const char* where = "ref::rolling_rigid_velocity";
  detail::require_non_negative(where, "v0", v0);
  if (!(std::isfinite(alpha) && alpha >= 0.0 && alpha < 0.5 * std::numbers::pi)) detail::fail(where, "alpha must be in [0, pi/2)", alpha);
  detail::require_non_negative(where, "mu_r", mu_r);
  detail::require_positive(where, "g", g);
  detail::require_non_negative(where, "t", t);
  return std::max(0.0, v0 + (2.0 / 3.0) * g * (std::sin(alpha) - mu_r * std::cos(alpha)) * t);
}

int rolling_disk_mode(double alpha, double mu, double mu_r) {
  constexpr const char* where = "ref::rolling_disk_mode";
  if (!(std::isfinite(alpha) && alpha >= 0.0 && alpha < 0.5 * std::numbers::pi)) detail::fail(where, "alpha must be in [0, pi/2)", alpha);
  detail::require_non_negative(where, "mu", mu);
  detail::require_non_negative(where, "mu_r", mu_r);
  const double t = std::tan(alpha);
  if (t <= mu && t <= mu_r) return 0;  // friction F = m g sin α and moment F r both held
  // The cap is reached first by the friction (μ ≤ μ_r): F = μ N turns the disk by μ N r < μ_r r N, which the
  // rolling spring holds, so it slides without turning.
  if (mu <= mu_r) return 1;
  // μ_r < μ, tan α > μ_r: the moment is at its cap μ_r r N. Rolling without slip, a = r ω̇:
  // (m + I/r²) a = m g (sin α − μ_r cos α) needs F = m g sin α − m a = m g (sin α + 2 μ_r cos α)/3 ≤ μ N,
  // that is tan α ≤ 3μ − 2μ_r; beyond it the disk slides at F = μ N and spins up at (μ − μ_r) r N/I.
  return t <= 3.0 * mu - 2.0 * mu_r ? 2 : 3;
}

double rolling_spring_moment(double kr, double kn, double mu_r, double radius, double approach, double rotation) {
  constexpr const char* where = "ref::rolling_spring_moment";
  detail::require_positive(where, "kr", kr);
  detail::require_positive(where, "kn", kn);
  detail::require_non_negative(where, "mu_r", mu_r);
  detail::require_positive(where, "radius", radius);
  detail::require_non_negative(where, "approach", approach);
  detail::require_non_negative(where, "rotation", rotation);
  const double en = kn * (approach + (radius - approach) * (1.0 - std::cos(rotation)));
  return std::min(kr * rotation, mu_r * radius * en);  // R_r = r at a wall (R1)
}

double rolling_pair_spring_moment(double kr, double kn, double mu_r, double r_i, double r_j, double approach, double rotation) {
  constexpr const char* where = "ref::rolling_pair_spring_moment";
  detail::require_positive(where, "kr", kr);
  detail::require_positive(where, "kn", kn);
  detail::require_non_negative(where, "mu_r", mu_r);
  detail::require_positive(where, "r_i", r_i);
  detail::require_positive(where, "r_j", r_j);
  detail::require_non_negative(where, "approach", approach);
  detail::require_non_negative(where, "rotation", rotation);
  // the centres, a_i = r_i − δ/2 and a_j = r_j − δ/2 from the turning point, end a_i² + a_j² + 2 a_i a_j cos θ apart
  const double a_i = r_i - 0.5 * approach, a_j = r_j - 0.5 * approach;
  const double distance = std::sqrt(a_i * a_i + a_j * a_j + 2.0 * a_i * a_j * std::cos(rotation));
  const double en = kn * (r_i + r_j - distance);
  return std::min(kr * rotation, mu_r * r_i * r_j / (r_i + r_j) * en);
}

}  // namespace ref
