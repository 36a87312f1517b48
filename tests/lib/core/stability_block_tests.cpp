// The guard's two sharper bounds (docs/model.md G5 and the row sums split by partner class), each
// against its value by hand. Planted bugs that turn these red: the per-class count not capped by the
// class's size (the stiff class counted six times), and the coupling ‖A_Lu‖ taken as z·b instead of √z·b.
#include <catch2/catch.hpp>
#include <cmath>

#include "dem/core/simulation.hpp"
#include "dem/core/stability_eigen.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

namespace {
constexpr double kn = 1e5, r = 0.01;

/// One free disk (mass 1 kg) with 10 soft partners (class "soft") and, if `stiff`, one stiff partner
/// (class "stiff", K_n 100× larger), all fixed and far away, K18, no dashpots.
dem::Model disk_with_partners(bool stiff) {
  auto m = test::make_model({{"disk", 2650.0}, {"soft", 2650.0}, {"stiff", 2650.0}}, 1e-7);
  test::set_law(m, 0, 1, test::linear_law(kn, 0.0, 0.5, 0.0, 0.0));
  if (stiff) test::set_law(m, 0, 2, test::linear_law(100 * kn, 0.0, 0.5, 0.0, 0.0));
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, 1.0);
  auto fixed = [&m](std::int32_t material, double x) {
    const std::size_t i = dem::add_element(m, dem::Shape::disk, material, r, {x, 1.0}, {}, 0.0, dem::PreMass::square, 1.0);
    m.elements.motion[i] = dem::Motion::fixed;
  };
  for (int k = 0; k < 10; ++k) fixed(1, 0.1 * k);
  if (stiff) fixed(2, 5.0);
  return m;
}

/// Two free PREs (0.5 kg) bonded face to face by `face_kn` (segments at the ends, K_s = 0, no dashpots;
/// λ = 6 face_kn/m, stability_eigen_tests) and a free disk of `disk_mass` far away, a linear law
/// `disk_kn` with the blocks, K18.
dem::Model pair_and_disk(double face_kn, double disk_kn, double disk_mass) {
  dem::Model m = test::blocks_and_disk_laws(face_kn, disk_kn);
  dem::add_element(m, dem::Shape::pre, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, 0.5);
  dem::add_element(m, dem::Shape::pre, 0, r, {2 * r, 0.0}, {}, 0.0, dem::PreMass::square, 0.5);
  dem::add_element(m, dem::Shape::disk, 1, r, {1.0, 1.0}, {}, 0.0, dem::PreMass::square, disk_mass);
  return m;
}
}  // namespace

TEST_CASE("row sums split by partner class: one stiff partner counts once", "[stability]") {
  const dem::StabilityBound soft = dem::Simulation(disk_with_partners(false)).stability_bound();
  const dem::StabilityBound both = dem::Simulation(disk_with_partners(true)).stability_bound();
  // the stiff partner's single contact along the worst axis: w + b = K/m + K/√(m m_j)
  const double one_stiff = 100 * kn / 1.0 + 100 * kn / std::sqrt(1.0 * 1.0);
  CHECK_THAT(both.stiffness_rate, WithinRel(soft.stiffness_rate + one_stiff, 1e-12));
  // and far below six stiff contacts (the bound before the split): 3 w + 6 b at the very least
  CHECK(both.stiffness_rate < 0.5 * (3 * 100 * kn + 6 * 100 * kn));
  CHECK_THAT(both.limit, WithinRel(2.0 / std::sqrt(both.stiffness_rate), 1e-12));  // K18, no damping
}

TEST_CASE("block bound G5: the bonded block's row adds one load-disk contact and the coupling sqrt(z) b", "[stability]") {
  // Two free PREs bonded face to face (λ = 6 K_n/m, stability_eigen_tests) and a heavy free disk far
  // away with a linear law 10 K_n: the disk's own row is slow, so the bonded block's row sets G5.
  constexpr double m_pre = 0.5, m_disk = 50.0;
  const dem::Model m = pair_and_disk(kn, 10 * kn, m_disk);
  const dem::StabilityBound b = dem::Simulation(m).stability_bound();
  REQUIRE(b.eigen);
  // A_LL: the pair, plus one contact with the disk on a PRE (w + b); ‖A_Lu‖ ≤ √2 b (the disk can touch
  // both PREs, each once)
  const double w = 10 * kn / m_pre, coupling = 10 * kn / std::sqrt(m_pre * m_disk);
  const double lambda_l = 6 * kn / m_pre + w + coupling + std::sqrt(2.0) * coupling;
  const double exact = 2.0 / std::sqrt(lambda_l);
  CHECK(b.limit_block <= exact * (1 + 1e-12));  // the stable end of the bisection
  CHECK(b.limit_block >= exact * (1 - 2e-4));
  CHECK(b.limit >= b.limit_block);
}

TEST_CASE("block bound G5: the guard above both the Weyl sum and the row sums", "[stability]") {
  // A stiffer pair (face K_n 10×) with a light disk (0.05 kg, linear law K_n): Weyl adds the disk's
  // whole row, 2 (K/m_d + K/√(m_d m)) (two contacts on one axis, opposite sides), to the pair's λ; G5
  // takes the larger of the bonded block's row and the disk's, here the bonded block's.
  constexpr double m_disk = 0.05, m_pre = 0.5, kf = 10 * kn;
  const dem::Model m = pair_and_disk(kf, kn, m_disk);
  const dem::StabilityBound b = dem::Simulation(m).stability_bound();
  REQUIRE(b.eigen);
  const double coupling = kn / std::sqrt(m_disk * m_pre);
  const double disk_row = 2 * (kn / m_disk + coupling);
  const double lambda_l = 6 * kf / m_pre + kn / m_pre + coupling + std::sqrt(2.0) * coupling;
  REQUIRE(lambda_l > disk_row);
  CHECK(b.limit == b.limit_block);
  CHECK(b.limit_block <= 2.0 / std::sqrt(lambda_l) * (1 + 1e-12));
  CHECK(b.limit_block >= 2.0 / std::sqrt(lambda_l) * (1 - 2e-4));
  const double weyl = 2.0 / std::sqrt(6 * kf / m_pre + disk_row);  // (G4)
  CHECK(b.limit > 1.05 * weyl);
  CHECK(b.limit > b.limit_gershgorin);
  // no Coulomb shear spring (K_s = 0): sticking adds nothing, so the block bound is the sticking limit too
  CHECK(b.limit_sticking == b.limit);
}
