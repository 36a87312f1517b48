#include "dem/core/stability.hpp"

#include <cmath>
#include <limits>

namespace dem {

double stable_w(Integrator integrator, double zeta) {
  if (integrator == Integrator::k18) return 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta);  // refs §1.5
  return std::min(2.0 * zeta, 2.0 * (std::sqrt(zeta * zeta + 3.0) - zeta));               // refs §1.5
}

double stable_dt(Integrator integrator, double mass, double stiffness, double eta) {
  const double omega = std::sqrt(stiffness / mass);
  const double zeta = eta / (2.0 * std::sqrt(mass * stiffness));
  return stable_w(integrator, zeta) / omega;
}

// An assembly's modes are bounded by Gershgorin's theorem: ω_max² ≤ max_i λ_i with λ_i the absolute
// row sum of the mass-normalised stiffness matrix. With the damping row c_i, the mode is given the
// damping ratio ζ = c_i/(2√λ_i) (exact for one contact; for stiffness-proportional damping c_i/λ_i =
// η/K, the K19 Hopf bound Δt < η/K, is then exact for every mode).
double stable_dt_gershgorin(Integrator integrator, double stiffness_row, double damping_row) {
  if (stiffness_row <= 0.0) return std::numeric_limits<double>::infinity();
  const double omega = std::sqrt(stiffness_row);
  const double zeta = damping_row / (2.0 * omega);
  return stable_w(integrator, zeta) / omega;
}

}  // namespace dem
