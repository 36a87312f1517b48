// The eigenvalue guard of a bonded structure (stability_eigen.hpp, docs/model.md G1–G4) against modes
// known by hand. Planted bugs: an eigenvalue halved (a guard too loose by √2) or the rotation levers
// left out turn these tests red.
#include <catch2/catch.hpp>
#include <cmath>

#include "dem/core/simulation.hpp"
#include "dem/core/stability_eigen.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

namespace {
constexpr double kn = 1e5, mass = 0.5, r = 0.01;

/// Two free PREs bonded face to face (segments at the face ends, ξ = ±1, a = r; K_s = 0), no walls.
/// Modes by hand: the relative normal translation λ = 2·2K_n/m, the relative rotation θ₁ = −θ₂ with
/// energy ½ Σ K_n (aξ·2θ)², kinetic ½·2Iθ̇², I = (2/3) r² m: λ = 2·2K_n r²/I = 6K_n/m (the largest).
/// With K_s = 0 only normal springs carry dashpots, so C = (η_n/K_n) A: proportional, exact per mode.
dem::Model bonded_pair(dem::Integrator integ, double h_n, double ks = 0.0) {
  auto m = test::make_model({{"block", 2000.0}}, 1e-7);
  m.numerics.integrator = integ;
  dem::PairLaw law = test::bonded_face_law(2, kn, ks, h_n);
  law.face.positions = dem::SegmentPositions::ends;
  test::set_law(m, 0, 0, law);
  dem::add_element(m, dem::Shape::pre, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  dem::add_element(m, dem::Shape::pre, 0, r, {2 * r, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  return m;
}
}  // namespace

TEST_CASE("eigen guard: two bonded PREs are limited by their relative rotation mode 6 K_n/m", "[stability]") {
  const auto integ = GENERATE(dem::Integrator::k18, dem::Integrator::k19);
  const double h_n = GENERATE(0.0, 1.0, 3.0);
  if (integ == dem::Integrator::k19 && h_n == 0.0) return;  // K19 needs damping
  CAPTURE(static_cast<int>(integ), h_n);
  const dem::Model m = bonded_pair(integ, h_n);
  const dem::StartNetwork net = dem::start_network(m);
  REQUIRE(net.any_bond);
  REQUIRE(net.dofs == 6);
  REQUIRE(net.springs.size() == 4);  // 2 normal, 2 shear (K_s = 0)
  const double lambda = 6.0 * kn / mass;
  CHECK_THAT(dem::network_eigenvalue(net, false, false), WithinRel(lambda, 1e-9));
  // η_n per segment (M7.3): 2h√(N K_n m_eff)/N with m_eff = m/2.
  const double eta_n = 2.0 * h_n * std::sqrt(2.0 * kn * mass / 2.0) / 2.0;
  const double c = eta_n / kn * lambda;
  const double exact = dem::stable_dt_rates(integ, lambda, c, eta_n / kn);
  const dem::StabilityBound b = dem::Simulation(m).stability_bound();
  CHECK(b.eigen);
  CHECK(b.limit <= exact * (1 + 1e-9));  // never unsafe
  CHECK(b.limit >= exact * (1 - 1e-5));  // and exact here
  CHECK(b.limit_gershgorin < b.limit);   // the row sums are the more conservative bound
}

TEST_CASE("eigen guard: a PRE bonded to a fixed PRE keeps its springs to the ground 3 K_n/m", "[stability]") {
  // The same pair with one PRE fixed (ground): its springs now act on the free PRE alone. Rotation:
  // 2 K_n r² / I = 3 K_n/m (the largest), normal translation 2 K_n/m. Either element may be the fixed one.
  const std::size_t fixed = GENERATE(0u, 1u);
  CAPTURE(fixed);
  dem::Model m = bonded_pair(dem::Integrator::k18, 0.0);
  m.elements.motion[fixed] = dem::Motion::fixed;
  const dem::StartNetwork net = dem::start_network(m);
  REQUIRE(net.any_bond);
  CHECK(net.dofs == 3);
  CHECK(net.springs.size() == 4);
  const double lambda = 3.0 * kn / mass;
  CHECK_THAT(dem::network_eigenvalue(net, false, false), WithinRel(lambda, 1e-9));
  const dem::StabilityBound b = dem::Simulation(m).stability_bound();
  CHECK(b.eigen);
  CHECK(b.limit <= 2.0 / std::sqrt(lambda) * (1 + 1e-9));  // K18 without damping: 2/ω
  CHECK(b.limit >= 2.0 / std::sqrt(lambda) * (1 - 1e-5));
}

TEST_CASE("eigen guard: the regula falsi ends on the stable side within 1e-4 in a few Lanczos solves", "[stability]") {
  // Shear springs K_s = 0.3 K_n with their own dashpots: C is not proportional to A, so the root of
  // λ_max(Δt²A + 2ΔtC) = κ lies strictly inside the bracket and the regula falsi has work to do.
  const double h_n = GENERATE(0.3, 1.0);
  const double new_rate = GENERATE(0.0, 1e7);  // with and without contacts that can still form (G4)
  CAPTURE(h_n, new_rate);
  const dem::Model m = bonded_pair(dem::Integrator::k18, h_n, 0.3 * kn);
  const dem::StartNetwork net = dem::start_network(m);
  int solves = 0;
  const double dt = dem::eigen_limit(net, dem::Integrator::k18, false, new_rate, 0.0, 1e300, &solves);
  auto excess = [&](double t) { return dem::network_rate(net, t, false) + t * t * new_rate - 4.0; };  // κ = 4 (G3)
  CHECK(excess(dt) <= 0.0);                           // the stable end
  CHECK(excess(dt / (1.0 - 1e-4) * (1 + 1e-9)) > 0.0);  // the root within 1e-4 above it
  // the bracket's two ends and a few Illinois steps (5 or 6 here, where halving the bracket would take
  // about 13); where the lower end is already the root (h_n = 1 with the new contacts: the normal mode,
  // whose damping is proportional, is the top one), none
  CHECK(solves >= 2);
  CHECK(solves <= 8);
}

TEST_CASE("eigen guard: a model without bonds keeps the row-sum guard", "[stability]") {
  auto m = test::make_model({{"disk", 2650.0}}, 1e-6);
  test::set_law(m, 0, 0, test::linear_law(kn, 0.0, 0.5, 10.0, 0.0));
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  dem::add_element(m, dem::Shape::disk, 0, r, {2 * r, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  const dem::StabilityBound b = dem::Simulation(m).stability_bound();
  CHECK_FALSE(b.eigen);
  CHECK(b.limit == b.limit_gershgorin);
}

TEST_CASE("eigen guard: an unbonded free element adds its contacts that can still form", "[stability]") {
  // The bonded pair plus a free disk (another material, linear law with the blocks) far away: its
  // row-sum rates are added (G4), so the limit falls below the pair's own.
  dem::Model m = test::make_model({{"block", 2000.0}, {"disk", 2650.0}}, 1e-7);
  dem::PairLaw law = test::bonded_face_law(2, kn, 0.0, 1.0);
  law.face.positions = dem::SegmentPositions::ends;
  test::set_law(m, 0, 0, law);
  test::set_law(m, 0, 1, test::linear_law(10 * kn, 0.0, 0.5, 0.0, 0.0));
  dem::add_element(m, dem::Shape::pre, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  dem::add_element(m, dem::Shape::pre, 0, r, {2 * r, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  const double alone = dem::Simulation(m).stability_bound().limit;
  dem::add_element(m, dem::Shape::disk, 1, r, {1.0, 1.0}, {}, 0.0, dem::PreMass::square, mass);
  const dem::StabilityBound b = dem::Simulation(m).stability_bound();
  CHECK(b.eigen);
  CHECK(b.limit < 0.9 * alone);
}
