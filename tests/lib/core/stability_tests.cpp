// The time-step guard (stability.hpp, Simulation::stability_limit): for one contact it is the exact
// limit of docs/references.md §1.5; more contacts on one element lower it; a bonded PRE lattice's limit is
// well below the single-pair limit (docs/references.md §4.6), and the lattice really is unstable at the
// pair limit while it is stable at the guard's Δt.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "dem/core/simulation.hpp"
#include "dem/core/stability.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

namespace {

/// Exact limit on ω₀Δt of one damped mass (docs/references.md §1.5), written out by hand.
double w_limit(dem::Integrator integ, double zeta) {
  if (integ == dem::Integrator::k18) return 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta);
  return std::min(2.0 * zeta, 2.0 * (std::sqrt(zeta * zeta + 3.0) - zeta));
}

constexpr double kn = 1e5, mass = 0.5, r = 0.01;

/// One disk of mass 0.5 kg between walls; ks = 0 so that only the normal springs count.
dem::Model disk_model(dem::Integrator integ, double zeta, bool second_wall) {
  auto m = test::make_model({{"disk", 2650.0}, {"wall", 0.0}}, 1e-6);
  m.numerics.integrator = integ;
  dem::PairLaw law;
  law.kind = dem::LawKind::linear;
  law.linear.kn = kn;
  law.linear.ks = 0.0;
  law.linear.mu = 0.5;
  law.damping_ratio = zeta;  // η = 2ζ√(m K) for a wall contact
  test::set_law(m, 0, 1, law);
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, r}, {}, 0.0, dem::PreMass::square, mass);
  m.walls.push_back(test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "floor"));
  if (second_wall) m.walls.push_back(test::segment_wall({-1.0, 2 * r}, {1.0, 2 * r}, 1, "ceiling"));
  return m;
}

}  // namespace

TEST_CASE("stability guard: one disk on a wall gets the exact single-contact limit (K18, K19)", "[stability]") {
  const auto integ = GENERATE(dem::Integrator::k18, dem::Integrator::k19);
  const double zeta = GENERATE(0.1, 0.3, 1.0, 1.5);
  CAPTURE(static_cast<int>(integ), zeta);
  const dem::Simulation sim(disk_model(integ, zeta, false));
  const double omega = std::sqrt(kn / mass), eta = 2.0 * zeta * std::sqrt(mass * kn);
  CHECK_THAT(sim.stability_limit(), WithinRel(dem::stable_dt(integ, mass, kn, eta), 1e-12));
  CHECK_THAT(sim.stability_limit(), WithinRel(w_limit(integ, zeta) / omega, 1e-12));
  if (integ == dem::Integrator::k19 && zeta <= 1.0)
    CHECK_THAT(sim.stability_limit(), WithinRel(eta / kn, 1e-12));  // Kiyama's K26: Δt < η/K
}

TEST_CASE("stability guard: a disk between two walls has the limit of K = 2K_n, eta = 2 eta_n", "[stability]") {
  const auto integ = GENERATE(dem::Integrator::k18, dem::Integrator::k19);
  const double zeta = GENERATE(0.1, 0.3, 1.0);
  CAPTURE(static_cast<int>(integ), zeta);
  const dem::Simulation one(disk_model(integ, zeta, false)), two(disk_model(integ, zeta, true));
  // total stiffness 2K, dashpot 2η: ω = √(2K/m), ζ' = 2η/(2√(2Km)) = √2 ζ
  const double expected = w_limit(integ, std::sqrt(2.0) * zeta) / std::sqrt(2.0 * kn / mass);
  CHECK_THAT(two.stability_limit(), WithinRel(expected, 1e-12));
  if (integ == dem::Integrator::k18) {
    CHECK(two.stability_limit() < one.stability_limit());
  } else if (std::sqrt(2.0) * zeta <= 1.0) {
    // K19's limit η/K (ζ' ≤ 1) does not change when K and η double together
    CHECK_THAT(two.stability_limit(), WithinRel(one.stability_limit(), 1e-12));
  }
}

TEST_CASE("stability guard: a disk with several disk contacts is below the single-pair limit", "[stability]") {
  const auto integ = GENERATE(dem::Integrator::k18, dem::Integrator::k19);
  auto m = test::make_model({{"disk", 2650.0}}, 1e-6);
  m.numerics.integrator = integ;
  dem::PairLaw law;
  law.linear.kn = kn;
  law.linear.ks = 0.25 * kn;
  law.linear.mu = 0.5;
  law.damping_ratio = 0.7;  // of the pair, reduced mass
  test::set_law(m, 0, 0, law);
  auto pair = m;
  dem::add_element(pair, dem::Shape::disk, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  dem::add_element(pair, dem::Shape::disk, 0, r, {2 * r, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  // a disk touching four others (a square arrangement)
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  for (const auto& p : {dem::Vec2{2 * r, 0}, dem::Vec2{-2 * r, 0}, dem::Vec2{0, 2 * r}, dem::Vec2{0, -2 * r}})
    dem::add_element(m, dem::Shape::disk, 0, r, p, {}, 0.0, dem::PreMass::square, mass);
  const dem::Simulation sim_pair(pair), sim_many(m);
  // exact limit of the normal mode of the pair: m_eff = m/2, ζ = 0.7
  const double pair_limit = w_limit(integ, 0.7) / std::sqrt(kn / (0.5 * mass));
  CHECK(sim_pair.stability_limit() <= pair_limit * (1 + 1e-12));  // the guard is conservative
  CHECK(sim_many.stability_limit() < sim_pair.stability_limit());
  CHECK(sim_many.stability_limit() < 0.75 * pair_limit);
}

TEST_CASE("stability guard: two contacts of a disk may lie on one axis (the worst arrangement is found)", "[stability]") {
  // Three equal disks, so each can touch two others: the worst arrangement puts both contacts on one
  // axis (0 and 180 degrees), λ = 2(K/m + K/√(m m)) = 4K/m exactly (block Gershgorin, ks = 0). A search
  // that misses positions near the normal to the first contact finds less (an unsafe bound).
  auto m = test::make_model({{"disk", 2650.0}}, 1e-6);
  dem::PairLaw law;
  law.linear.kn = kn;
  law.linear.ks = 0.0;
  law.linear.mu = 0.5;
  law.damping_ratio = 0.3;
  test::set_law(m, 0, 0, law);
  for (const double x : {-2 * r, 0.0, 2 * r}) dem::add_element(m, dem::Shape::disk, 0, r, {x, 0.0}, {}, 0.0, dem::PreMass::square, mass);
  const dem::StabilityBound b = dem::assembly_stability_bound(m, {});
  CHECK_THAT(b.stiffness_rate, WithinRel(4.0 * kn / mass, 1e-12));
  CHECK(b.element_contacts == 2);
}

namespace {

/// A bonded 3 × 3 lattice of PREs (r = 1 cm, square mass), N = 2 segments, h_n = 1, k_s/k_n = 0.4.
dem::Model lattice(int columns, int rows, double dt, std::uint64_t seed) {
  auto m = test::make_model({{"mortar", 2000.0}}, dt);
  m.numerics.integrator = dem::Integrator::k18;
  dem::PairLaw law = test::bonded_face_law(2, 1e6, 4e5, 1.0);  // h_n = 1.0
  test::set_law(m, 0, 0, law);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);  // small random velocities [m/s]
  for (int b = 0; b < rows; ++b)
    for (int a = 0; a < columns; ++a)
      dem::add_element(m, dem::Shape::pre, 0, r, {2 * r * a, 2 * r * b}, {u(rng), u(rng)}, 10 * u(rng));
  return m;
}

double kinetic(const dem::Simulation& s) { return s.energies().kinetic; }

}  // namespace

TEST_CASE("stability guard: a bonded PRE lattice is limited well below the pair limit, and that matters",
          "[stability][face]") {
  const double m_pre = 4 * r * r * 2000.0;  // (M17)
  // one bonded pair: whole face N K_n = 2e6 N/m, reduced mass m/2, damping ratio h_n = 1 (M7.3)
  const double pair_limit = w_limit(dem::Integrator::k18, 1.0) / std::sqrt(2e6 / (0.5 * m_pre));
  const dem::Simulation pair(lattice(2, 1, 1e-7, 1)), grid(lattice(3, 3, 1e-7, 1));
  CHECK(pair.stability_limit() <= pair_limit * (1 + 1e-12));
  const double guard = grid.stability_limit();
  CHECK(guard < 0.6 * pair_limit);
  CAPTURE(pair_limit, guard);

  // Run 3000 steps at 0.99 × the guard and at 0.99 × the pair limit.
  auto grows = [&](double dt) {
    dem::Simulation s(lattice(3, 3, dt, 7));
    const double e0 = kinetic(s);
    double e_max = e0;
    for (int k = 0; k < 3000; ++k) {
      s.step();
      const double ek = kinetic(s);
      if (!std::isfinite(ek)) return 1e300;
      e_max = std::max(e_max, ek);
    }
    return e_max / e0;
  };
  CHECK(grows(0.99 * guard) < 10.0);      // bounded (decays: every contact is critically damped)
  CHECK(grows(0.99 * pair_limit) > 1e6);  // the collective mode blows up
}
