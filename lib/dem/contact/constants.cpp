#include "dem/contact/constants.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace dem {

double hertz_2d_stiffness(double e, double nu, double r, double q, double c) {
  if (e <= 0.0 || r <= 0.0 || q <= 0.0 || nu < 0.0 || nu >= 0.5)
    throw std::invalid_argument("hertz_2d_stiffness: need E > 0, r > 0, q > 0, 0 <= nu < 0.5");
  const double pi = std::numbers::pi;
  const double b = std::sqrt((8.0 / pi) * (0.5 * r) * ((1.0 - nu * nu) / e) * q);  // (K22.b)
  return pi * e / (2.0 * (1.0 - nu * nu) * (c + 2.0 * std::log(4.0 * r / b)));     // (K23)
}

double critical_damping(double mass, double stiffness) { return 2.0 * std::sqrt(mass * stiffness); }  // (K20)

double restitution_from_damping_ratio(double zeta) {
  if (zeta < 0.0) throw std::invalid_argument("damping ratio must be >= 0");
  if (zeta >= 1.0) return 0.0;
  return std::exp(-std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta));
}

double damping_ratio_from_restitution(double e) {
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("restitution must be in (0, 1]");
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

double pre_pair_time_step(double h_n, double m, double k) { return h_n * std::sqrt(m / k); }  // (M26)

double lattice_kn(double e, double nu) { return (1.0 - nu) * e / ((1.0 + nu) * (1.0 - 2.0 * nu)); }  // (M25.l)
double lattice_ks(double e, double nu) { return (1.0 - 2.0 * nu) * lattice_kn(e, nu) / (2.0 * (1.0 - nu)); }

}  // namespace dem
