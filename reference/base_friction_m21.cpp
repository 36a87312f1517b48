// Quasi-static rotation rate of a rigid block under Matsui's per-element base friction (M21),
// refs §3.7. Geometry, signs and the moment balance: ref/base_friction_m21.hpp.
//
// Derivation. Rotation about P at Ω, plate velocity v_B ĝ, λ = Ω/v_B. Element e at c_e moves with
// V_e = Ω ẑ x c_e; its relative velocity u_e = V_e - V_B has (as in M25, with ρ -> c_e)
//   (c_e x u_e)_z = v_B (λ|c_e|² - T_e),   |u_e|² = v_B² (1 - 2 T_e λ + λ²|c_e|²),
// and S_e² = |u_e|² + (rΩ)² = v_B² (1 - 2 T_e λ + λ²(|c_e|² + r²)). The moment about P of the
// element's force (at c_e) plus its spin moment -(2/3) μ_B m_e g r (rΩ)/S_e is
//   -μ_B m_e g v_B [λ(|c_e|² + (2/3) r²) - T_e] / S_e.
// Summing over e (m_e ∝ s², so weights s² make F21 comparable with F of M25), the zero moment
// is F21(λ) = 0 of the header. F21(0) = s² Σ T_e = W H T_cm because the centres average to the block
// centre; F21(λ -> -∞) = s² Σ (|c|² + (2/3) r²)/sqrt(|c|² + r²) > 0. Unlike F of (M25), F21 need not
// be monotone (∂/∂λ of a term has numerator T² - |c|² - (2/3) r² - λ T r²/3), so the root is taken
// in the bracket [λ_lo, 0) found as for M25; the unit tests check that this bracket holds one sign
// change only.
#include "ref/base_friction_m21.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "ref/gsl_support.hpp"
#include "ref/require.hpp"

namespace ref {

namespace {

struct Lattice {
  double side;  // s = W/n_w = H/n_h
  int n_w;
  int n_h;
};

Lattice require_lattice(const char* where, double width, double height, int n_w, int n_h) {
  detail::require_positive(where, "width", width);
  detail::require_positive(where, "height", height);
  if (n_w < 1) detail::fail(where, "n_w must be >= 1", n_w);
  if (n_h < 1) detail::fail(where, "n_h must be >= 1", n_h);
  const double side_w = width / n_w;
  const double side_h = height / n_h;
  if (!(std::abs(side_w - side_h) <= 1e-9 * std::max(side_w, side_h)))
    detail::fail(where, "elements must be square: W/n_w must equal H/n_h (W/n_w given)", side_w);
  return {0.5 * (side_w + side_h), n_w, n_h};
}

// F21 in units of the side s (lengths / s, λ s): F21 = s³ · moment_in_sides.
double moment_in_sides(double lambda_s, double cos_psi, double sin_psi, const Lattice& lattice) {
  constexpr double r2 = 0.25;  // (r/s)², r = s/2
  double sum = 0.0;
  for (int j = 0; j < lattice.n_h; ++j) {
    const double ch = j + 0.5;
    for (int i = 0; i < lattice.n_w; ++i) {
      const double cw = i + 0.5;
      const double t = cw * cos_psi - ch * sin_psi;           // T_e
      const double n = cw * sin_psi + ch * cos_psi;           // T_e² + n² = |c_e|²
      const double a = 1.0 - t * lambda_s;
      const double s2 = a * a + lambda_s * lambda_s * (n * n + r2);  // 1 - 2Tλ + λ²(|c|² + r²)
      sum += (t - lambda_s * (cw * cw + ch * ch + (2.0 / 3.0) * r2)) / std::sqrt(s2);  // (M21)
    }
  }
  return sum;
}

}  // namespace

double m21_moment(double lambda, double psi, double width, double height, int n_w, int n_h) {
  constexpr const char* where = "ref::m21_moment";
  detail::require_finite(where, "lambda", lambda);
  detail::require_finite(where, "psi", psi);
  const Lattice lattice = require_lattice(where, width, height, n_w, n_h);
  const double s = lattice.side;
  return s * s * s * moment_in_sides(lambda * s, std::cos(psi), std::sin(psi), lattice);
}

double m21_lambda(double psi, double width, double height, int n_w, int n_h) {
  constexpr const char* where = "ref::m21_lambda";
  detail::require_finite(where, "psi", psi);
  if (!(psi >= 0.0 && psi <= std::numbers::pi))
    detail::fail(where, "psi must lie in [0, pi] rad", psi);
  const Lattice lattice = require_lattice(where, width, height, n_w, n_h);
  const double c = std::cos(psi), s = std::sin(psi);
  // F21(0) = W H T_cm: no toppling when T_cm >= 0 (same condition as M25).
  if (width * c - height * s >= 0.0) return 0.0;
  const auto moment = [&](double lambda_s) { return moment_in_sides(lambda_s, c, s, lattice); };
  double lo = -1.0 / lattice.n_h;  // λ_lo = -1/H in units of 1/s
  for (int k = 0; moment(lo) <= 0.0; ++k) {
    if (k > 60) throw std::runtime_error(std::string(where) + ": no bracket for the root");
    lo *= 2.0;
  }
  return detail::brent_root(where, moment, lo, 0.0, 1e-13, 1e-16) / lattice.side;
}

double m21_rate(double psi, double width, double height, int n_w, int n_h) {
  return -m21_lambda(psi, width, height, n_w, n_h);  // dθ/dδ_B = -λ21
}

}  // namespace ref
