// Rolling resistance (docs/model.md §4, R1–R6): the pure law (spring, limit, dashpot off at the limit,
// unloading), its constants (R_r, k_r, I_r, C_r), and in runs: the pair's moments equal and opposite, a rigid
// rotation of a pair free of rolling moment, the guard counting the rolling spring, the energy it stores.
// Every expected number is worked out by hand in the comments from the equations.
#include <catch2/catch.hpp>
#include <cmath>

#include "dem/cases/case_file.hpp"
#include "dem/contact/rolling_resistance.hpp"
#include "dem/core/simulation.hpp"
#include "dem/core/stability.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// k_r = 2 N·m/rad, C_r = 0.5 N·m·s/rad, limit arm μ_r R_r = 1e-3 m, Δt = 1 ms.
dem::RollingState state() {
  dem::RollingState s;
  s.kr = 2.0, s.cr = 0.5, s.arm = 1e-3;
  return s;
}
constexpr double inv_dt = 1000.0;

}  // namespace

TEST_CASE("Rolling constants: R_r, k_r from β or given, I_r in series, C_r (R1, R2, R5)", "[rolling]") {
  CHECK_THAT(dem::rolling_radius(0.02, 0.01), WithinRel(0.02 * 0.01 / 0.03, 1e-15));  // r_i r_j/(r_i + r_j)
  CHECK(dem::rolling_radius(0.02, 0.0) == 0.02);                                     // a wall: r_i
  dem::RollingLaw law;
  law.enabled = true, law.mu_r = 0.1, law.stiffness_factor = 2.25;
  // β k_n μ_r² R_r² = 2.25 × 1e6 × 0.01 × 1e-4 = 2.25
  CHECK_THAT(dem::rolling_stiffness(law, 1e6, 0.01), WithinRel(2.25, 1e-14));
  law.kr = 7.0;  // given: taken as is
  CHECK(dem::rolling_stiffness(law, 1e6, 0.01) == 7.0);
  // I + m r² of each in series: (1 + 1·1)·(2 + 1·4)/(2 + 6) = 2·6/8 = 1.5; a wall: the element's own
  CHECK_THAT(dem::rolling_inertia(1.0, 1.0, 1.0, 2.0, 1.0, 2.0), WithinRel(1.5, 1e-15));
  CHECK(dem::rolling_inertia(1.0, 1.0, 1.0, 0.0, 0.0, 0.0) == 2.0);
  law.damping_ratio = 0.25;  // 2 ζ_r √(I_r k_r) = 0.5 √(1.5 × 6) = 1.5
  CHECK_THAT(dem::rolling_dashpot(law, 1.5, 6.0), WithinRel(1.5, 1e-15));
}

TEST_CASE("The rolling spring loads, is held at μ_r R_r e_n without dashpot, and unloads (R3, R4, R6)", "[rolling]") {
  dem::RollingState s = state();
  // Δθ = 1e-4: M_k = −2e-4; M_d = −0.5 × 1e-4 × 1000 = −0.05; limit 1e-3 × 100 N = 0.1: elastic
  double m = dem::rolling_moment(1e-4, 100.0, inv_dt, s);
  CHECK_THAT(s.mk, WithinAbs(-2e-4, 1e-18));
  CHECK_THAT(m, WithinAbs(-2e-4 - 0.05, 1e-15));
  CHECK(s.m == m);
  // a large rotation: M_k = −2e-4 − 2 × 0.1 = −0.2002 > limit 0.1 in size: held at −0.1, no dashpot
  m = dem::rolling_moment(0.1, 100.0, inv_dt, s);
  CHECK(s.mk == -0.1);
  CHECK(m == -0.1);
  // the limit follows e_n: at 20 N it is 0.02
  m = dem::rolling_moment(0.0, 20.0, inv_dt, s);
  CHECK(m == -0.02);
  // turning back unloads elastically, with its dashpot: −0.02 + 2 × 1e-3 = −0.018, M_d = +0.5
  m = dem::rolling_moment(-1e-3, 20.0, inv_dt, s);
  CHECK_THAT(s.mk, WithinAbs(-0.018, 1e-15));
  CHECK_THAT(m, WithinAbs(-0.018 + 0.5, 1e-15));
}

TEST_CASE("Rolling in a run: equal and opposite moments, none for a rigid turn, energy stored, guard", "[rolling]") {
  // Two disks pressed together by gravity onto a wall? Simpler: two disks touching, no gravity, one spinning.
  const std::vector<std::string> base = {"physics.gravity.magnitude=0 m/s^2"};
  const dem::Case c = dem::read_case(test::source("tests/lib/fixtures/rolling_pair.toml"), base);
  dem::Simulation sim(c.model);
  sim.keep_contact_forces(true);
  for (int k = 0; k < 20; ++k) sim.step();
  const dem::ContactView v = sim.contact(0, 1, false);
  REQUIRE(v.links == 1);
  // the disk turned counter-clockwise relative to its partner: the moment on it is clockwise (negative)
  CHECK(v.mr < 0.0);
  const dem::Elements& e = sim.model().elements;
  // the moments on the two disks: −r f_s ∓ M_r; their difference is 2 M_r beyond the shear's equal radii
  CHECK_THAT(e.moment[0] - e.moment[1], WithinRel(2.0 * v.mr, 1e-12));
  CHECK(sim.energies().elastic > 0.0);

  // A rigid rotation of the pair (both turning together about the contact point, the line of centres with
  // them) gives no rolling moment: Δθ_r = Δφ_i − Δφ_j = 0.
  dem::Case rigid = dem::read_case(test::source("tests/lib/fixtures/rolling_pair.toml"),
                                   {"physics.gravity.magnitude=0 m/s^2", "element.0.angular_velocity=1 rad/s",
                                    "element.1.angular_velocity=1 rad/s", "element.0.velocity=[0.0, -0.01]",
                                    "element.1.velocity=[0.0, 0.01]"});
  dem::Simulation turn(rigid.model);
  turn.keep_contact_forces(true);
  for (int k = 0; k < 20; ++k) turn.step();
  CHECK(turn.contact(0, 1, false).mr == 0.0);

  // The guard counts the rolling spring: a stiffer one lowers the bound.
  const dem::Case soft = dem::read_case(test::source("tests/lib/fixtures/rolling_pair.toml"), base);
  const dem::Case stiff = dem::read_case(test::source("tests/lib/fixtures/rolling_pair.toml"),
                                         {"physics.gravity.magnitude=0 m/s^2", "contact.0.rolling.stiffness=1e3 N*m/rad"});
  const double limit_soft = dem::assembly_stability_bound(soft.model, {}).limit;
  const double limit_stiff = dem::assembly_stability_bound(stiff.model, {}).limit;
  CHECK(limit_stiff < 0.5 * limit_soft);
}
