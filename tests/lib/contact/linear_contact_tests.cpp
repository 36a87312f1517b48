// Cundall's linear spring–dashpot contact (docs/model.md §1, K6–K14): accumulation, dashpot, no tension,
// Coulomb slider, the two end rules; and, in a two-disk run, zero force when apart and equal and
// opposite forces. Every expected number is worked out by hand in the comments from the equations.
#include <catch2/catch.hpp>
#include <cmath>

#include "dem/contact/linear_contact.hpp"
#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double tol = 1e-12;

// K_n = 2000 N/m, K_s = 500 N/m, η_n = 3 N·s/m, η_s = 1.5 N·s/m, Δt = 1 ms (1/Δt = 1000 /s).
constexpr double kn = 2000.0, ks = 500.0, eta_n = 3.0, eta_s = 1.5, inv_dt = 1000.0;

dem::LinearSpringDashpot law(double mu, dem::EndRule rule = dem::EndRule::elastic) {
  dem::LinearSpringDashpot l;
  l.kn = kn;
  l.ks = ks;
  l.mu = mu;
  l.end_rule = rule;
  return l;
}

}  // namespace

TEST_CASE("linear contact: elastic forces accumulate the increments (K6.a, K7.a, K10.a, K11.a), the dashpot does not (K6.b, K7.b, K10.b, K11.b)",
          "[contact]") {
  const auto l = law(10.0);  // μ large: never slides here
  dem::LinearContactHistory h;
  // step 1: Δu_n = 1 mm, Δu_s = 0.2 mm → e_n = 2, e_s = 0.1; d_n = 3·1e-3·1000 = 3, d_s = 1.5·0.2 = 0.3
  auto f = dem::linear_contact_force(l, eta_n, eta_s, 1e-3, 2e-4, inv_dt, h);
  CHECK_THAT(h.en, WithinRel(2.0, tol));
  CHECK_THAT(h.es, WithinRel(0.1, tol));
  CHECK_THAT(f.fn, WithinRel(5.0, tol));
  CHECK_THAT(f.fs, WithinRel(0.4, tol));
  // step 2: Δu_n = 2 mm, Δu_s = −0.1 mm → e_n = 6, e_s = 0.05; d_n = 6, d_s = −0.15
  f = dem::linear_contact_force(l, eta_n, eta_s, 2e-3, -1e-4, inv_dt, h);
  CHECK_THAT(h.en, WithinRel(6.0, tol));
  CHECK_THAT(h.es, WithinRel(0.05, tol));
  CHECK_THAT(f.fn, WithinRel(12.0, tol));
  CHECK_THAT(f.fs, WithinRel(-0.1, tol));
  // step 3: Δu_n = −0.5 mm, Δu_s = 0.3 mm → e_n = 5, e_s = 0.2; d_n = −1.5, d_s = 0.45
  f = dem::linear_contact_force(l, eta_n, eta_s, -5e-4, 3e-4, inv_dt, h);
  CHECK_THAT(h.en, WithinRel(5.0, tol));
  CHECK_THAT(h.es, WithinRel(0.2, tol));
  CHECK_THAT(f.fn, WithinRel(3.5, tol));
  CHECK_THAT(f.fs, WithinRel(0.65, tol));
  // step 4: no motion → the dashpot forces of the earlier steps are gone, only e_n, e_s remain
  f = dem::linear_contact_force(l, eta_n, eta_s, 0.0, 0.0, inv_dt, h);
  CHECK_THAT(f.fn, WithinRel(5.0, tol));
  CHECK_THAT(f.fs, WithinRel(0.2, tol));
}

TEST_CASE("linear contact: no tension (K8, K12) opens the contact and resets the history", "[contact]") {
  const auto rule = GENERATE(dem::EndRule::elastic, dem::EndRule::total);
  CAPTURE(static_cast<int>(rule));
  const auto l = law(10.0, rule);
  dem::LinearContactHistory h;
  dem::linear_contact_force(l, eta_n, eta_s, 1e-3, 2e-4, inv_dt, h);  // e_n = 2, e_s = 0.1
  // Δu_n = −1.5 mm: e_n = 2 − 3 = −1 < 0 → e_n = d_n = e_s = d_s = 0
  auto f = dem::linear_contact_force(l, eta_n, eta_s, -1.5e-3, 1e-4, inv_dt, h);
  CHECK(f.fn == 0.0);
  CHECK(f.fs == 0.0);
  CHECK(h.en == 0.0);
  CHECK(h.es == 0.0);
  // A new approach starts from zero, not from the −1 N of the opened contact:
  // Δu_n = 0.5 mm → e_n = 1, d_n = 1.5; Δu_s = 0 → f_s = 0
  f = dem::linear_contact_force(l, eta_n, eta_s, 5e-4, 0.0, inv_dt, h);
  CHECK_THAT(f.fn, WithinRel(2.5, tol));
  CHECK(f.fs == 0.0);
}

TEST_CASE("linear contact: a fresh contact moving apart carries no force", "[contact]") {
  const auto rule = GENERATE(dem::EndRule::elastic, dem::EndRule::total);
  const auto l = law(0.5, rule);
  dem::LinearContactHistory h;
  const auto f = dem::linear_contact_force(l, eta_n, eta_s, -1e-6, 3e-6, inv_dt, h);
  CHECK(f.fn == 0.0);
  CHECK(f.fs == 0.0);
  CHECK(h.en == 0.0);
  CHECK(h.es == 0.0);
}

TEST_CASE("linear contact: Coulomb slider caps |e_s| at μ e_n and drops d_s only when sliding (K13)", "[contact]") {
  const auto l = law(0.4);
  const double sign = GENERATE(1.0, -1.0);
  CAPTURE(sign);
  SECTION("sliding") {
    dem::LinearContactHistory h;
    // e_n = 2000·1e-3 = 2 → limit μ e_n = 0.8; trial e_s = 500·2e-3 = 1.0 > 0.8 → e_s = ±0.8, d_s = 0
    auto f = dem::linear_contact_force(l, eta_n, eta_s, 1e-3, sign * 2e-3, inv_dt, h);
    CHECK_THAT(h.es, WithinRel(sign * 0.8, tol));
    CHECK_THAT(f.fs, WithinRel(sign * 0.8, tol));  // no dashpot part (d_s would be ±3)
    CHECK_THAT(f.fn, WithinRel(2.0 + 3.0, tol));   // the normal dashpot stays
    // The capped value is what is stored: Δu_s = ∓0.5 mm → e_s = ±(0.8 − 0.25) = ±0.55 (sticks),
    // d_s = ∓0.75 → f_s = ∓0.2 (had the trial 1.0 been stored: e_s = ±0.75, f_s = 0)
    f = dem::linear_contact_force(l, eta_n, eta_s, 0.0, -sign * 5e-4, inv_dt, h);
    CHECK_THAT(h.es, WithinRel(sign * 0.55, tol));
    CHECK_THAT(f.fs, WithinRel(-sign * 0.2, tol));
  }
  SECTION("sticking") {
    dem::LinearContactHistory h;
    // e_s = 500·1e-3 = 0.5 < 0.8 → sticks; d_s = 1.5 → f_s = 2.0, above μ e_n: only e_s is capped
    const auto f = dem::linear_contact_force(l, eta_n, eta_s, 1e-3, sign * 1e-3, inv_dt, h);
    CHECK_THAT(h.es, WithinRel(sign * 0.5, tol));
    CHECK_THAT(f.fs, WithinRel(sign * 2.0, tol));
  }
  SECTION("the switch is at |e_s| = μ e_n") {
    // limit μ e_n = 0.8 N is reached at Δu_s = 0.8/500 = 1.6 mm
    dem::LinearContactHistory below, above;
    const double s_below = sign * 1.6e-3 * (1 - 1e-9), s_above = sign * 1.6e-3 * (1 + 1e-9);
    const auto fb = dem::linear_contact_force(l, eta_n, eta_s, 1e-3, s_below, inv_dt, below);
    const auto fa = dem::linear_contact_force(l, eta_n, eta_s, 1e-3, s_above, inv_dt, above);
    CHECK_THAT(fb.fs, WithinRel(sign * (0.8 + 2.4) * (1 - 1e-9), tol));  // sticks: e_s + d_s
    CHECK_THAT(fa.fs, WithinRel(sign * 0.8, tol));                       // slides: μ e_n only
  }
}

TEST_CASE("linear contact: end rules — elastic lets the dashpot pull, total forbids an attractive force", "[contact]") {
  dem::LinearContactHistory he, ht;
  const auto le = law(10.0, dem::EndRule::elastic), lt = law(10.0, dem::EndRule::total);
  dem::linear_contact_force(le, eta_n, eta_s, 1e-3, 1e-4, inv_dt, he);  // e_n = 2
  dem::linear_contact_force(lt, eta_n, eta_s, 1e-3, 1e-4, inv_dt, ht);
  // Δu_n = −0.9 mm: e_n = 2 − 1.8 = 0.2 ≥ 0 (still closed), d_n = −2.7 → e_n + d_n = −2.5 N
  const auto fe = dem::linear_contact_force(le, eta_n, eta_s, -9e-4, 0.0, inv_dt, he);
  const auto ft = dem::linear_contact_force(lt, eta_n, eta_s, -9e-4, 0.0, inv_dt, ht);
  CHECK_THAT(fe.fn, WithinRel(-2.5, tol));  // convention A: attractive total force
  CHECK_THAT(fe.fs, WithinRel(0.05, tol));  // e_s = 500·1e-4
  CHECK(ft.fn == 0.0);                      // convention B: f_n = max(e_n + d_n, 0)
  CHECK(ft.fs == 0.0);                      // and no shear without normal force
  CHECK_THAT(ht.en, WithinRel(0.2, tol));   // the elastic history is kept (the overlap is still there)
  // once e_n + d_n is positive again, both rules agree: Δu_n = 0 → f_n = e_n = 0.2
  const auto fe2 = dem::linear_contact_force(le, eta_n, eta_s, 0.0, 0.0, inv_dt, he);
  const auto ft2 = dem::linear_contact_force(lt, eta_n, eta_s, 0.0, 0.0, inv_dt, ht);
  CHECK_THAT(fe2.fn, WithinRel(0.2, tol));
  CHECK_THAT(ft2.fn, WithinRel(0.2, tol));
}

// Two spinning disks approach obliquely, collide and separate (no gravity). The pair force is zero
// while they are apart; while they touch, the forces are equal and opposite (K15), the moments are
// M_i = −r_i f_s with the contact's f_s, and the total momentum is conserved.
TEST_CASE("linear contact in a run: zero force when apart, equal and opposite forces, M_i = -r_i f_s",
          "[contact][simulation]") {
  auto m = test::make_model({{"disk", 2650.0}}, 1e-5);
  test::set_law(m, 0, 0, test::linear_law(1e5, 2.5e4, 0.3, 20.0, 10.0));
  const double r0 = 0.01, r1 = 0.012;
  dem::add_element(m, dem::Shape::disk, 0, r0, {0.0, 0.0}, {1.0, 0.2}, 5.0);
  dem::add_element(m, dem::Shape::disk, 0, r1, {0.026, 0.004}, {-1.0, 0.0}, -3.0);
  dem::Simulation sim(std::move(m));
  const auto& e = sim.model().elements;
  const double p0x = e.mass[0] * e.vx[0] + e.mass[1] * e.vx[1];
  const double p0y = e.mass[0] * e.vy[0] + e.mass[1] * e.vy[1];
  int apart = 0, touching = 0;
  double max_fn = 0.0;
  for (int k = 0; k < 2500; ++k) {
    // the force of step k is computed at the positions held before the step (x_k, K5)
    const double d = std::hypot(e.x[1] - e.x[0], e.y[1] - e.y[0]);
    sim.step();
    const auto c = sim.contact(0, 1, false);
    if (d > r0 + r1) {
      ++apart;
      REQUIRE(e.fx[0] == 0.0);
      REQUIRE(e.fy[0] == 0.0);
      REQUIRE(e.moment[0] == 0.0);
      REQUIRE(e.fx[1] == 0.0);
      REQUIRE(c.fn == 0.0);
    } else {
      ++touching;
      max_fn = std::max(max_fn, std::abs(c.fn));
      REQUIRE(e.fx[0] == -e.fx[1]);
      REQUIRE(e.fy[0] == -e.fy[1]);
      REQUIRE_THAT(e.moment[0], WithinAbs(-r0 * c.fs, 1e-12 * max_fn * r0));
      REQUIRE_THAT(e.moment[1], WithinAbs(-r1 * c.fs, 1e-12 * max_fn * r0));
      // force on element 0 is −f_n n − f_s t with n from 0 towards 1, t = n rotated by +90°
      REQUIRE_THAT(e.fx[0], WithinAbs(-c.fn * c.nx + c.fs * c.ny, 1e-12 * max_fn));
      REQUIRE_THAT(e.fy[0], WithinAbs(-c.fn * c.ny - c.fs * c.nx, 1e-12 * max_fn));
    }
  }
  CHECK(apart > 100);     // approach and separation
  CHECK(touching > 100);  // the collision lasts ≈ π/ω₀ ≈ 6 ms = 600 steps
  CHECK(max_fn > 1.0);
  CHECK(sim.contact_count() == 0);  // they separated again
  const double p1x = e.mass[0] * e.vx[0] + e.mass[1] * e.vx[1];
  const double p1y = e.mass[0] * e.vy[0] + e.mass[1] * e.vy[1];
  CHECK_THAT(p1x, WithinAbs(p0x, 1e-12));
  CHECK_THAT(p1y, WithinAbs(p0y, 1e-12));
}
