#pragma once
// Single-degree-of-freedom damped oscillator  m x'' + eta x' + K x = 0  (refs §1.1).
// Closed form for every damping ratio, an independent Boost.Odeint integration of the same
// equation for cross-checking, and the damping-ratio / restitution relations.

namespace ref {

// A mass on a linear spring with a linear dashpot. Validated at construction.
class Oscillator {
 public:
  // Throws std::invalid_argument unless mass > 0, stiffness > 0, damping >= 0 (all finite).
  Oscillator(double mass, double stiffness, double damping);

  double mass() const { return mass_; }            // kg (per unit thickness in 2D: kg/m)
  double stiffness() const { return stiffness_; }  // N/m (2D: N/m per m = Pa)
  double damping() const { return damping_; }      // N s/m (2D: N s/m²)
  double natural_frequency() const { return natural_frequency_; }  // omega0 = sqrt(K/m), rad/s
  double damping_ratio() const { return damping_ratio_; }          // zeta = eta/(2 sqrt(m K))

 private:
  double mass_;
  double stiffness_;
  double damping_;
  double natural_frequency_;
  double damping_ratio_;
};

struct OscillatorState {
  double position;  // m
  double velocity;  // m/s
};

// Exact x(t), v(t) from x(0) = x0, v(0) = v0 (refs §1.1), t >= 0.
// One formula covers all three regimes: x = e^{-beta t}[x0 C + (v0 + beta x0) S] with
// C = cos(omega_d t), S = sin(omega_d t)/omega_d (under-damped), cosh/sinh (over-damped), and
// C = 1, S = t (critical). Near zeta = 1 (|omega_d t| <= 1 or |Omega t| <= 1) C and S are summed as
// power series in (1 - zeta^2)(omega0 t)^2, so there is no 0/0 and no branch threshold; a large
// over-damped argument uses the two-exponential form with s1 = -omega0^2/(beta + Omega) (no
// cancellation for zeta >> 1).
// Accuracy: a few ulp times (1 + omega0 t) of the scale max(|x0|, |v0|/omega0).
OscillatorState oscillator_state(const Oscillator& oscillator, OscillatorState initial, double t);

// The same initial-value problem integrated by Boost.Odeint runge_kutta_dopri5 (controlled,
// abs = rel = 1e-13) in the dimensionless variables tau = omega0 t, y = x/L, u = v/(omega0 L) with
// L = max(|x0|, |v0|/omega0). Independent of the closed form; meant for cross-checking it.
// Accuracy: |error| <~ 1e-13 L (1 + omega0 t) (measured against the closed form over
// 0 <= zeta <= 20, omega0 t <= 200: at most 4.2e-14 L (1 + omega0 t)).
OscillatorState oscillator_state_odeint(const Oscillator& oscillator, OscillatorState initial,
                                        double t);

// eta = 2 zeta sqrt(m K) (refs conventions); zeta >= 0. Exact up to rounding.
double damping_coefficient(double mass, double stiffness, double damping_ratio);

// Critical damping eta = 2 sqrt(m K) (K20, K25.a). Exact up to rounding.
double critical_damping(double mass, double stiffness);

// Convention-A inverse (refs §1.2): zeta = -ln e / sqrt(pi^2 + ln^2 e) for 0 <= e <= 1; e = 0 gives
// zeta = 1 (the limit; every zeta >= 1 gives e_A = 0). Exact up to rounding.
double damping_ratio_for_restitution(double restitution);

}  // namespace ref
