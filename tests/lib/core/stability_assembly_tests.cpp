// The time-step guard bounds the whole mass-normalised stiffness and damping matrices (block
// Gershgorin, stability.hpp), coupling terms included. A guard that took only the diagonal would pass
// the single-normal-spring tests; these cases separate the two: a disk on a wall with K_s = K_n (the
// shear spring couples x and φ: its rank-one term has norm K_s(1/m + r²/I) = 3K_s/m, the diagonal
// alone 2K_s/m), a disk pair (the spring couples the two elements) and a PRE face's moment levers.
// The guard may be conservative; each test asserts it is safe (at most the exact limit) and within 2×.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

namespace {

/// Exact limit on ω₀Δt of one damped mass (references.md §1.5), written out by hand.
double w_limit(dem::Integrator integ, double zeta) {
  if (integ == dem::Integrator::k18) return 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta);
  return std::min(2.0 * zeta, 2.0 * (std::sqrt(zeta * zeta + 3.0) - zeta));
}
/// Limit of one degree of freedom with row sums λ (stiffness/mass) and c (damping/mass).
double row_limit(dem::Integrator integ, double lambda, double c) {
  const double omega = std::sqrt(lambda);
  return w_limit(integ, c / (2.0 * omega)) / omega;
}

constexpr double kn = 1e5, mass = 0.5, r = 0.01;

}  // namespace

TEST_CASE("stability guard: a disk on a wall with K_s = K_n is limited by the full x-phi row sum",
          "[stability]") {
  const auto integ = GENERATE(dem::Integrator::k18, dem::Integrator::k19);
  const double eta = GENERATE(0.0, 60.0, 2000.0);  // K19 needs ζ > 1 to see the row (else Δt = η/K)
  CAPTURE(static_cast<int>(integ), eta);
  auto m = test::make_model({{"disk", 2650.0}, {"wall", 0.0}}, 1e-6);
  m.numerics.integrator = integ;
  test::set_law(m, 0, 1, test::linear_law(kn, kn, 0.5, eta, eta));
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, r}, {}, 0.0, dem::PreMass::square, mass);  // I = m r²/2
  m.walls.push_back(test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "floor"));
  const dem::Simulation sim(m);
  const dem::StabilityBound b = sim.stability_bound();
  // Exact modes: y (K_n/m, η/m) and the rank-one x–φ shear mode (3K_s/m, 3η_s/m).
  const double exact_sticking = std::min(row_limit(integ, kn / mass, eta / mass), row_limit(integ, 3 * kn / mass, 3 * eta / mass));
  CHECK(b.limit_sticking <= exact_sticking * (1 + 1e-12));
  CHECK(b.limit_sticking >= 0.5 * exact_sticking);
  // The refusing limit leaves out a Coulomb contact's shear spring: exactly the normal mode.
  CHECK_THAT(b.limit, WithinRel(row_limit(integ, kn / mass, eta / mass), 1e-12));
  // The diagonal alone (φ: K_s r²/I = 2K_s/m) would give a limit above the exact one.
  if (integ == dem::Integrator::k18 || eta > 1000.0)
    CHECK(row_limit(integ, 2.0 * kn / mass, 2.0 * eta / mass) > 1.05 * exact_sticking);
}

TEST_CASE("stability guard: a disk pair's spring counts on both elements' rows (2K_n/m)", "[stability]") {
  const auto integ = GENERATE(dem::Integrator::k18, dem::Integrator::k19);
  const double eta = GENERATE(0.0, 2000.0);
  CAPTURE(static_cast<int>(integ), eta);
  auto m = test::make_model({{"disk", 2650.0}}, 1e-6);
  m.numerics.integrator = integ;
  test::set_law(m, 0, 0, test::linear_law(kn, 0.0, 0.5, eta, 0.0));
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  dem::add_element(m, dem::Shape::disk, 0, r, {2 * r, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  const dem::Simulation sim(m);
  // Row x of element 0: K_n (1/√m)(1/√m + 1/√m) = 2K_n/m; the diagonal alone is K_n/m.
  CHECK_THAT(sim.stability_limit(), WithinRel(row_limit(integ, 2 * kn / mass, 2 * eta / mass), 1e-12));
}

TEST_CASE("stability guard: a PRE face's segments act on the rotation through their levers a xi", "[stability]") {
  auto m = test::make_model({{"block", 2000.0}, {"wall", 0.0}}, 1e-7);
  dem::PairLaw law = test::bonded_face_law(2, kn, 0.0, 0.0);
  law.face.positions = dem::SegmentPositions::ends;  // ξ = ±1 (M13.2)
  test::set_law(m, 0, 1, law);
  dem::add_element(m, dem::Shape::pre, 0, r, {0.0, r}, {}, 0.0, dem::PreMass::square, mass);  // I = (2/3) r² m
  m.walls.push_back(test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "floor"));
  const dem::Simulation sim(m);
  // Each segment: b = (0, −1, −aξ), a = r, I = (2/3) r² m. The levers cancel in the y–φ coupling, so the
  // exact modes are y (2K_n/m) and φ (2K_n a²/I = 3K_n/m); without the levers only 2K_n/m.
  const double exact = row_limit(dem::Integrator::k18, 3 * kn / mass, 0.0);
  CHECK(sim.stability_limit() <= exact * (1 + 1e-12));
  CHECK(sim.stability_limit() >= 0.5 * exact);
  CHECK(row_limit(dem::Integrator::k18, 2 * kn / mass, 0.0) > 1.2 * exact);
}
