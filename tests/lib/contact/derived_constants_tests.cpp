// Constants derived inside the core: the linear shear dashpot from a damping ratio,
// η_s = η_n √(K_s/K_n) (K20, K25), and the PRE face springs and dashpots from moduli,
// K = k A/((r₁ + r₂)N) (M6, a wall: r₂ = 0, M19), η_n = 2h√(K_n N m)/N, η_s = η_n √(K_s/K_n) (M7.3, M7.4).
#include <catch2/catch.hpp>
#include <cmath>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

TEST_CASE("Linear dashpots from a damping ratio: eta_n = 2 zeta sqrt(m K_n), eta_s = eta_n sqrt(K_s/K_n)",
          "[contact][damping]") {
  const double r = 0.01, kn = 1e5, ks = 2.5e4, zeta = 0.3, delta = 1e-4, vt = 0.2, vn = 0.05;
  auto m = test::make_model({{"disk", 2650.0}, {"wall", 0.0}}, 1e-6);
  dem::PairLaw law;
  law.kind = dem::LawKind::linear;
  law.linear.kn = kn;
  law.linear.ks = ks;
  law.linear.mu = 10.0;
  law.damping_ratio = zeta;
  law.mass_basis = dem::MassBasis::reduced;
  test::set_law(m, 0, 1, law);
  test::set_law(m, 0, 0, law);
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, r - delta}, {vt, -vn});  // on the floor
  dem::add_element(m, dem::Shape::disk, 0, r, {1.0, 0.5});                   // a pair, apart from the floor
  dem::add_element(m, dem::Shape::disk, 0, r, {1.0 + 2 * r - delta, 0.5}, {-vn, vt});
  m.walls.push_back(test::segment_wall({-0.5, 0.0}, {0.5, 0.0}, 1, "floor"));
  dem::Simulation sim(m);
  sim.step();  // a contact present at t = 0: e_n = K_n δ, e_s = 0; the first increment drives the dashpots
  const double mass = sim.model().elements.mass[0];
  {
    const double eta_n = 2 * zeta * std::sqrt(mass * kn), eta_s = eta_n * std::sqrt(ks / kn);
    const auto c = sim.contact(0, 0, true);
    CHECK_THAT(c.fn, WithinRel(kn * delta + eta_n * vn, 1e-9));
    CHECK_THAT(c.fs, WithinRel(eta_s * vt, 1e-9));
  }
  {
    const double m_eff = 0.5 * mass;  // reduced mass of two equal disks
    const double eta_n = 2 * zeta * std::sqrt(m_eff * kn), eta_s = eta_n * std::sqrt(ks / kn);
    const auto c = sim.contact(1, 2, false);
    CHECK_THAT(c.fn, WithinRel(kn * delta + eta_n * vn, 1e-9));
    CHECK_THAT(c.fs, WithinRel(-eta_s * vt, 1e-9));  // t = (0, 1): element 1 sees element 2 move by −vt
  }
}

TEST_CASE("PRE face springs and dashpots from moduli: K = k A/(r N), eta_s = eta_n sqrt(K_s/K_n)",
          "[face][damping]") {
  const double r = 0.02, l = 0.5, kn_mod = 1e8, ks_mod = 3e7, vt = 0.1, vn = 0.03, dt = 1e-7;
  const int n = 2;
  const double h = GENERATE(0.0, 0.2);
  CAPTURE(h);
  auto m = test::make_model({{"block", 2000.0}, {"wall", 0.0}}, dt);
  m.thickness = l;
  dem::PairLaw law = test::bonded_face_law(n, kn_mod, ks_mod, h);
  law.face_modulus = true;
  test::set_law(m, 0, 1, law);
  dem::add_element(m, dem::Shape::pre, 0, r, {0.0, r}, {vt, -vn});
  m.walls.push_back(test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "floor"));
  dem::Simulation sim(m);
  const double area = 2 * r * l;                     // (M1)
  const double kn = kn_mod * area / (r * n), ks = ks_mod * area / (r * n);  // (M6), wall: r₁ + r₂ → r₁
  const double mass = sim.model().elements.mass[0];
  const double eta_n = 2 * h * std::sqrt(kn * n * mass) / n, eta_s = eta_n * std::sqrt(ks / kn);
  sim.step();  // geometric start: P_e = K_n × overlap = 0, Q_e = 0; the dashpots see the first increment vΔt
  const auto c0 = sim.contact(0, 0, true);
  if (h > 0.0) {
    CHECK_THAT(c0.fs, WithinRel(n * eta_s * vt, 1e-9));
    CHECK_THAT(c0.fn, WithinRel(n * eta_n * vn, 1e-9));
  } else {
    CHECK(c0.fs == 0.0);
    CHECK(std::abs(c0.fn) < 1e-12);
  }
  // The second increments Δv = Δx + rΔφ (M15.2) and Δu = −Δy (M15.1; the ±aξΔφ parts cancel over
  // the symmetric segments) load the springs.
  const double dv = sim.model().elements.dx[0] + r * sim.model().elements.dphi[0];
  const double du = -sim.model().elements.dy[0];
  sim.step();
  const auto c1 = sim.contact(0, 0, true);
  CHECK_THAT(c1.fs, WithinRel(n * ks * dv + n * eta_s * dv / dt, 1e-9));
  CHECK_THAT(c1.fn, WithinRel(n * kn * du + n * eta_n * du / dt, 1e-9));
}
