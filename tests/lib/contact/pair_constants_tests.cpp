// Two constants the other tests do not reach: Kiyama's particle mass basis of the damping ratio
// (K20: m = the mean mass of a pair) and the face half-length of a PRE pair of unequal radii
// (M1: a = min(r₁, r₂), A = 2al, K_n = k_n A/((r₁ + r₂)N), M6).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

TEST_CASE("Mass basis 'particle': eta_n = 2 zeta sqrt(m K_n) with the mean mass of the pair (K20)",
          "[contact][damping]") {
  const double r = 0.01, kn = 1e5, zeta = 0.4, delta = 1e-4, vn = 0.05;
  auto m = test::make_model({{"disk", 2650.0}}, 1e-6);
  dem::PairLaw law;
  law.kind = dem::LawKind::linear;
  law.linear.kn = kn;
  law.linear.mu = 0.5;
  law.damping_ratio = zeta;
  law.mass_basis = dem::MassBasis::particle;
  test::set_law(m, 0, 0, law);
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, 1.0);
  dem::add_element(m, dem::Shape::disk, 0, r, {2 * r - delta, 0.0}, {-vn, 0.0}, 0.0, dem::PreMass::square, 3.0);
  dem::Simulation sim(m);
  sim.step();
  const double eta_n = 2 * zeta * std::sqrt(0.5 * (1.0 + 3.0) * kn);  // mean mass 2 kg (reduced: 0.75 kg)
  CHECK_THAT(sim.contact(0, 1, false).fn, WithinRel(kn * delta + eta_n * vn, 1e-9));
}

TEST_CASE("A PRE pair of unequal radii has the face of the smaller one: a = min(r1, r2) (M1, M6)", "[face]") {
  const double r1 = 0.02, r2 = 0.01, l = 0.5, k = 1e8, delta = 1e-6;
  const int n = 2;
  auto m = test::make_model({{"block", 2000.0}}, 1e-7);
  m.thickness = l;
  dem::PairLaw law = test::bonded_face_law(n, k, 0.0, 0.0);
  law.face_modulus = true;
  test::set_law(m, 0, 0, law);
  dem::add_element(m, dem::Shape::pre, 0, r1, {0.0, 0.0});
  dem::add_element(m, dem::Shape::pre, 0, r2, {r1 + r2 - delta, 0.0});
  dem::Simulation sim(m);
  sim.step();  // present at t = 0: P_e = K_n × overlap per segment
  const double area = 2 * std::min(r1, r2) * l;
  const double kn = k * area / ((r1 + r2) * n);
  CHECK_THAT(sim.contact(0, 1, false).fn, WithinRel(n * kn * delta, 1e-6));
}
