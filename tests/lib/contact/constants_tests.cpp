// Contact-constant helpers (lib/dem/contact/constants.hpp) against the numbers of the papers and docs/references.md.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "dem/contact/constants.hpp"
#include "dem/core/stability.hpp"

using Catch::Matchers::WithinRel;

namespace {
constexpr double kgf = 9.80665;  // N
}

TEST_CASE("K23 reproduces the first column of Kiyama's Table 1", "[constants]") {
  // E = 750 kgf/cm², ν = 0.3, r = 1 cm, q = 0.068 kgf/cm, c = 1.5 (docs/references.md §5.2).
  const double e = 750 * kgf / 1e-4, q = 0.068 * kgf / 1e-2, r = 0.01;
  const double kn = dem::hertz_2d_stiffness(e, 0.3, r, q, 1.5);
  const double rho_g = 2650 * kgf;          // ρg [N/m³], with the same g as kgf
  CHECK_THAT(kn / rho_g * 100.0, WithinRel(3.64e4, 2e-3));  // K_n/ρg in cm
  // η_n = 2√(m K_n), m = ρπr² per unit thickness: η_n/ρg = 21.6 cm·s (the paper prints "cm/s").
  const double m = 2650 * std::numbers::pi * r * r;
  const double eta = dem::critical_damping(m, kn);
  CHECK_THAT(eta / rho_g * 100.0, WithinRel(21.6, 3e-3));
  // Δt < η_n/K_n = 5.94e-4 s (K26).
  CHECK_THAT(eta / kn, WithinRel(5.94e-4, 2e-3));
  // K22.a's constant 2/3 gives a stiffer contact than K23's 1.5 (docs/references.md §5.1: 6.6 % at E = 750).
  CHECK(dem::hertz_2d_stiffness(e, 0.3, r, q, 2.0 / 3.0) > kn);
}

TEST_CASE("K23 rejects non-physical input", "[constants]") {
  CHECK_THROWS(dem::hertz_2d_stiffness(-1.0, 0.3, 0.01, 1.0));
  CHECK_THROWS(dem::hertz_2d_stiffness(1e7, 0.5, 0.01, 1.0));
  CHECK_THROWS(dem::hertz_2d_stiffness(1e7, 0.3, 0.0, 1.0));
  // each condition alone, and both ends of 0 <= nu < 0.5 (g578749-006 joined q <= 0 and nu < 0 by "and")
  CHECK_THROWS(dem::hertz_2d_stiffness(1e7, 0.3, 0.01, 0.0));
  CHECK_THROWS(dem::hertz_2d_stiffness(1e7, -0.1, 0.01, 1.0));
  CHECK_THROWS(dem::hertz_2d_stiffness(0.0, 0.3, 0.01, 1.0));
  CHECK(dem::hertz_2d_stiffness(1e7, 0.0, 0.01, 1.0) > 0.0);
  CHECK(dem::hertz_2d_stiffness(1e7, 0.4999, 0.01, 1.0) > 0.0);
}

TEST_CASE("Damping ratio and restitution are inverse (convention A)", "[constants]") {
  for (double zeta : {0.0, 0.1, 0.3, 0.7, 0.95}) {
    const double e = dem::restitution_from_damping_ratio(zeta);
    if (zeta > 0.0) CHECK_THAT(dem::damping_ratio_from_restitution(e), WithinRel(zeta, 1e-12));
  }
  CHECK_THAT(dem::restitution_from_damping_ratio(0.3), WithinRel(0.3723261049, 1e-9));  // docs/references.md §1.2
  CHECK(dem::restitution_from_damping_ratio(1.0) == 0.0);
  CHECK_THROWS(dem::damping_ratio_from_restitution(1.5));
}

TEST_CASE("M25.l lattice constants for the mortar", "[constants]") {
  // E = 4000 N/mm², ν = 1/6: k_n = 4285.714, k_s = 1714.286 N/mm² (docs/model.md §2; the paper rounds).
  CHECK_THAT(dem::lattice_kn(4000.0, 1.0 / 6.0), WithinRel(4285.714285714286, 1e-12));
  CHECK_THAT(dem::lattice_ks(4000.0, 1.0 / 6.0), WithinRel(1714.285714285714, 1e-12));
}

TEST_CASE("Time-step limits of one contact", "[constants][stability]") {
  // docs/references.md §1.7: Kiyama Table 2 runs, ω₀ = 4767 rad/s, ζ = 1.0019: K18 1.736e-4 s, K19 4.19e-4 s.
  const double w0 = 4767.0, zeta = 1.0019;
  CHECK_THAT(dem::stable_w(dem::Integrator::k18, zeta) / w0, WithinRel(1.736e-4, 2e-3));
  CHECK_THAT(dem::stable_w(dem::Integrator::k19, zeta) / w0, WithinRel(4.19e-4, 2e-3));
  CHECK(dem::stable_w(dem::Integrator::k19, 0.0) == 0.0);  // K19 is unstable without damping
  // M-A: N K_n = 24 kN/mm, m = 67.1 g: √(m/(N K_n)) = 5.29e-5 s, K18 limit at h_n = 1: 4.38e-5 s.
  CHECK_THAT(dem::pre_pair_time_step(1.0, 0.0671, 2.4e7), WithinRel(5.29e-5, 2e-3));
  CHECK_THAT(dem::stable_dt(dem::Integrator::k18, 0.0671, 2.4e7, 2.0 * std::sqrt(0.0671 * 2.4e7)),
             WithinRel(4.38e-5, 2e-3));
}
