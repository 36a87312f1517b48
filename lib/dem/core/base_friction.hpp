#pragma once
// Base friction (M21): the body force and moment that a sliding base plate exerts on every element of
// a base-friction model (docs/model.md §2 "Base friction (M21)"; docs/references.md §3.1, §3.7). The model lies
// flat on a plate moving in its plane with velocity v_B; the gravity g_B presses each element onto the
// plate with the normal load m g_B, and the plate's Coulomb friction μ_B drags the element:
//
//   u = (ẋ − v_Bx, ẏ − v_By),  V = √(|u|² + (rθ̇)²)                                    (M21)
//   B = −(u/V) μ_B m g_B,  moment r·B_θ with B_θ = −(rθ̇/V)(2/3) μ_B m g_B.
//
// Regularisation. M21 is singular at V = 0 (direction undefined). Below the speed v_ε (a case value,
// `base_friction.regularisation_speed`) the law is linear: V is replaced by max(V, v_ε), i.e.
//   B = −u μ_B m g_B / max(V, v_ε),  r·B_θ = −(2/3) μ_B m g_B r (rθ̇) / max(V, v_ε).
// What it changes: nothing for V ≥ v_ε (M21 exactly); for V < v_ε the force is a dashpot, proportional
// to the relative velocity, continuous at V = v_ε. In both ranges |B| ≤ μ_B m g_B (equality for
// V ≥ v_ε without spin), B is anti-parallel to u and the moment opposes θ̇: the force never exceeds
// the Coulomb load and always opposes the relative motion.
//
// Time step. Below v_ε the law is a dashpot of rate c = μ_B g_B / v_ε per unit mass on ẋ, ẏ and
// c_θ = (2/3) μ_B m g_B r² / (v_ε I) on θ̇ (= c for the square-mass PRE, M17; (4/3)c for disk mass).
// It acts on the velocity of the previous step (v_{k−1}, the array of Kiyama's cycle), so the explicit
// update of a free element is v_k − v_B = (1 − cΔt)(v_{k−1} − v_B): stable for cΔt < 2 and monotone
// (no overshoot past the plate velocity) for cΔt ≤ 1. The case reader refuses cΔt > 1 unless
// numerics.allow_unstable; the assembly's time-step guard (stability.hpp) can add these rates to its
// damping rows with `base_friction_rates`.
#include <cmath>
#include <cstdint>
#include <vector>

#include "dem/core/elements.hpp"
#include "dem/core/vec2.hpp"
#include "dem/core/velocity_history.hpp"

namespace dem {

/// The base plate of a base-friction model. Disabled unless the case has a [base_friction] table.
struct BasePlate {
  bool enabled = false;
  Vec2 velocity;                      // constant plate velocity v_B [m/s], used when drive < 0
  std::int32_t drive = -1;            // or a velocity history: index into Model::drives
  double normal_gravity = 9.80665;    // g_B, the gravity pressing the model onto the plate [m/s²]
  double regularisation_speed = 0.0;  // v_ε [m/s], > 0 when enabled
  std::vector<double> friction;       // μ_B per material (index as Model::materials), 0: no base friction
};

/// Displacement of the plate since the start: the vector, and the travel δ_B = ∫|v_B| dt [m].
struct BasePlateTravel {
  Vec2 displacement;
  double travel = 0.0;
};

struct BaseFrictionForce {
  double fx = 0.0, fy = 0.0;  // [N]
  double moment = 0.0;        // r·B_θ [N·m]
};

/// (M21), regularised below v_eps (see the header comment), on one element of mass m and radius r
/// moving with velocity `relative_velocity` relative to the plate and spinning at omega [rad/s].
inline BaseFrictionForce base_friction_force(double mu, double mass, double radius, double g_normal,
                                             double v_eps, Vec2 relative_velocity, double omega) {
  const double spin = radius * omega;  // rθ̇
  const double v2 = relative_velocity.x * relative_velocity.x + relative_velocity.y * relative_velocity.y + spin * spin;
  const double v = std::sqrt(v2);
  const double scale = mu * mass * g_normal / (v > v_eps ? v : v_eps);  // μ_B m g_B / max(V, v_ε)
  BaseFrictionForce f;
  f.fx = -scale * relative_velocity.x;                  // (M21) B_x
  f.fy = -scale * relative_velocity.y;                  // (M21) B_y
  f.moment = -radius * (2.0 / 3.0) * scale * spin;      // (M21) r·B_θ
  return f;
}

/// Damping rate per unit mass of the linear range, c = μ_B g_B / v_ε [1/s].
inline double base_friction_rate(double mu, double g_normal, double v_eps) { return mu * g_normal / v_eps; }

/// The rotational rate of the linear range, c_θ = (2/3) μ_B m g_B r² / (v_ε I) [1/s].
inline double base_friction_rotational_rate(double mu, double g_normal, double v_eps, double mass,
                                            double radius, double inertia) {
  return (2.0 / 3.0) * mu * mass * g_normal * radius * radius / (v_eps * inertia);
}

struct BaseFrictionRates {
  double translation = 0.0, rotation = 0.0;  // c, c_θ [1/s]
};

/// The dashpot rates element i feels from the plate (zero without base friction): for the time-step
/// guard, which may add them to the element's damping rows (x, y: translation; θ: rotation).
BaseFrictionRates base_friction_rates(const BasePlate& plate, const Elements& e, std::size_t i);

/// The largest of those rates over the free active elements [1/s].
double max_base_friction_rate(const BasePlate& plate, const Elements& e);

/// The plate velocity at time t [m/s].
Vec2 plate_velocity(const BasePlate& plate, const std::vector<VelocityHistory>& drives, double t);

/// Adds (M21) to the force and moment of every active free element, with the element velocities of
/// the arrays (v_{k−1}) relative to the plate velocity v_plate.
void add_base_friction(Elements& e, const BasePlate& plate, Vec2 v_plate);

}  // namespace dem
