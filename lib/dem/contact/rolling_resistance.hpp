#pragma once
// Rolling resistance at a linear (disk) contact: the elastic–plastic spring–dashpot moment of Iwashita
// & Oda, in the form Ai, Chen, Rotter & Ooi (2011) call type C (docs/model.md §4, R1–R6). A value type
// holding the parameters, the per-contact constants and history, and one pure function that advances
// the moment by one step.
#include <cmath>

namespace dem {

/// The rolling law of a contact pair (an option of the linear law).
struct RollingLaw {
  bool enabled = false;
  double mu_r = 0.0;              // rolling friction coefficient μ_r: the moment limit is μ_r R_r e_n (R4)
  double kr = 0.0;                // rolling spring k_r [N·m/rad]; 0: from stiffness_factor (R2)
  double stiffness_factor = 0.0;  // β of k_r = β k_n μ_r² R_r² (R2; Ai et al. take β = 2.25)
  double damping_ratio = 0.0;     // ζ_r of the rolling dashpot C_r = 2 ζ_r √(I_r k_r) (R5)
};

/// What a contact's rolling carries from step to step: its constants (fixed when the contact starts) and
/// its history; zero when rolling is off or the contact does not touch.
struct RollingState {
  double mk = 0.0;   // the spring's moment on element i [N·m] (R3); on j the opposite
  double kr = 0.0;   // k_r of this pair [N·m/rad] (R2)
  double cr = 0.0;   // C_r of this pair [N·m·s/rad] (R5)
  double arm = 0.0;  // μ_r R_r [m]: the limit is arm × e_n (R4)
  double m = 0.0;    // the step's whole rolling moment on i, spring + dashpot [N·m] (R6), for outputs and sums
};

/// R_r: the rolling radius of a pair (R1); a wall (r_j = 0) gives r_i.
inline double rolling_radius(double r_i, double r_j) { return r_j > 0.0 ? r_i * r_j / (r_i + r_j) : r_i; }

/// k_r of a pair with normal spring k_n and rolling radius R_r (R2).
inline double rolling_stiffness(const RollingLaw& law, double kn, double r_r) {
  return law.kr > 0.0 ? law.kr : law.stiffness_factor * kn * law.mu_r * law.mu_r * r_r * r_r;
}

/// I_r of a pair: the inertias about the contact points, in series (R5). inertia_j ≤ 0: a wall.
inline double rolling_inertia(double inertia_i, double mass_i, double r_i, double inertia_j, double mass_j, double r_j) {
  const double a = inertia_i + mass_i * r_i * r_i;
  if (inertia_j <= 0.0) return a;
  const double b = inertia_j + mass_j * r_j * r_j;
  return a * b / (a + b);
}

/// C_r = 2 ζ_r √(I_r k_r) (R5).
inline double rolling_dashpot(const RollingLaw& law, double inertia_r, double kr) {
  return 2.0 * law.damping_ratio * std::sqrt(inertia_r * kr);
}

/// One step of the rolling moment. dtheta: the relative rotation increment Δθ_r = Δφ_i − Δφ_j of the step
/// (R1); en: the contact's elastic normal force after this step (K7.a); inv_dt = 1/Δt. Returns the moment
/// on element i (on j the opposite).
inline double rolling_moment(double dtheta, double en, double inv_dt, RollingState& s) {
  s.mk -= s.kr * dtheta;                    // (R3): the spring resists the relative rotation
  double md = -s.cr * dtheta * inv_dt;      // (R5): the dashpot
  const double limit = s.arm * en;          // (R4): full mobilisation μ_r R_r e_n
  if (std::abs(s.mk) > limit) {
    s.mk = std::copysign(limit, s.mk);      // (R4.a): the spring holds the limit
    md = 0.0;                               // (R4.b): no dashpot at full mobilisation
  }
  s.m = s.mk + md;                          // (R6)
  return s.m;
}

}  // namespace dem
