// The general (scalar) integration path of Simulation::integrate, taken whenever any element is fixed or
// driven, and the masked vectorised path (some elements removed from the run), must do exactly what the
// vectorised all-free path does (K17, K18, K19), and K19
// there must follow its exact discrete solution, translation and rotation.
#include <catch2/catch.hpp>
#include <cmath>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;

namespace {

constexpr double r = 0.01;

/// A small pile of spinning disks on a floor, with contacts at the start and one that forms later;
/// optionally one extra fixed disk far away (last index: the other indices do not change), and before it
/// one removed from the run (inactive, as a silo's outlet leaves a disk).
dem::Model pile(dem::Integrator integ, bool distant_fixed, bool distant_removed = false) {
  auto m = test::make_model({{"disk", 2650.0}, {"wall", 0.0}}, 1e-5);
  m.numerics.integrator = integ;
  m.gravity = {0.0, -9.81};
  dem::PairLaw law;
  law.kind = dem::LawKind::linear;
  law.linear.kn = 1e5;
  law.linear.ks = 4e4;
  law.linear.mu = 0.3;
  law.damping_ratio = 0.2;
  test::set_law(m, 0, 0, law);
  test::set_law(m, 0, 1, law);
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 0.0099}, {0.05, 0.0}, 5.0);
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0199, 0.0099}, {-0.02, 0.01}, -3.0);
  dem::add_element(m, dem::Shape::disk, 0, r, {0.00995, 0.0271}, {0.0, -0.1}, 7.0);
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0404, 0.0101}, {-0.5, 0.0}, 2.0);  // hits disk 1 later
  m.walls.push_back(test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "floor"));
  if (distant_removed) {
    const std::size_t k = dem::add_element(m, dem::Shape::disk, 0, r, {-10.0, 5.0}, {2.0, -1.0}, 4.0);
    m.elements.active[k] = 0;
  }
  if (distant_fixed) {
    const std::size_t k = dem::add_element(m, dem::Shape::disk, 0, r, {10.0, 10.0}, {1.0, 1.0}, 1.0);
    m.elements.motion[k] = dem::Motion::fixed;
  }
  return m;
}

}  // namespace

TEST_CASE("A distant fixed element changes nothing, bit for bit, K18 and K19 with spin and contacts",
          "[integration]") {
  const auto integ = GENERATE(dem::Integrator::k18, dem::Integrator::k19);
  CAPTURE(static_cast<int>(integ));
  dem::Simulation a(pile(integ, false)), b(pile(integ, true));
  std::size_t contacts_seen = 0;
  for (int k = 0; k < 1500; ++k) {
    a.step();
    b.step();
    contacts_seen = std::max(contacts_seen, a.contact_count());
  }
  CHECK(contacts_seen >= 5);  // 3 at the start, the late impact, and more
  const auto& ea = a.model().elements;
  const auto& eb = b.model().elements;
  test::check_same_state(ea, eb);
  CHECK(eb.x[4] == 10.0);  // the fixed element stays
  CHECK(eb.omega[4] == 0.0);
  CHECK(std::abs(ea.omega[0] - 5.0) > 1e-3);  // the spins were changed by the contacts
}

// Simulation::Freedom: all free (a), free where active with a removed disk (b: the masked vectorised pass),
// and element by element (c: a fixed disk as well). The removed disk keeps its state on both paths.
TEST_CASE("A removed element changes nothing, bit for bit, on the masked and the general path, K18 and K19",
          "[integration]") {
  const auto integ = GENERATE(dem::Integrator::k18, dem::Integrator::k19);
  CAPTURE(static_cast<int>(integ));
  dem::Simulation a(pile(integ, false)), b(pile(integ, false, true)), c(pile(integ, true, true));
  const dem::Elements start = b.model().elements;
  for (int k = 0; k < 1500; ++k) {
    a.step();
    b.step();
    c.step();
  }
  const auto& ea = a.model().elements;
  const auto& eb = b.model().elements;
  const auto& ec = c.model().elements;
  test::check_same_state(ea, eb);
  test::check_same_state(eb, ec);  // also the removed disk, index 4
  for (const dem::Elements* e : {&eb, &ec}) {
    CHECK(e->x[4] == start.x[4]);
    CHECK(e->y[4] == start.y[4]);
    CHECK(e->vx[4] == start.vx[4]);
    CHECK(e->vy[4] == start.vy[4]);
    CHECK(e->omega[4] == start.omega[4]);
    CHECK(e->dx[4] == start.dx[4]);
    CHECK(e->phi[4] == start.phi[4]);
  }
  CHECK(std::abs(ea.omega[0] - 5.0) > 1e-3);  // the contacts acted
}

TEST_CASE("K19 on the general path: free flight with spin follows the exact discrete solution",
          "[integration]") {
  auto m = test::make_model({{"disk", 2650.0}}, 1e-4);
  m.numerics.integrator = dem::Integrator::k19;
  const double g = -9.80665, dt = 1e-4, vx = 0.3, vy = 1.0, w = 3.0;
  m.gravity = {0.0, g};
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 2.0}, {vx, vy}, w);
  const std::size_t k = dem::add_element(m, dem::Shape::disk, 0, r, {50.0, 50.0});
  m.elements.motion[k] = dem::Motion::fixed;  // forces the general path
  dem::Simulation sim(m);
  const int n = 1000;
  for (int s = 0; s < n; ++s) sim.step();
  // (K19) with a plain start: Δy_k = v0Δt + gΔt²k + gΔt²2^−(k+1), so after n steps
  // y_n = y0 + n v0 Δt + gΔt² n(n−1)/2 + gΔt²(1 − 2^−n).
  const double y = 2.0 + n * vy * dt + g * dt * dt * n * (n - 1) / 2.0 + g * dt * dt * (1.0 - std::pow(2.0, -n));
  const auto& e = sim.model().elements;
  CHECK_THAT(e.y[0], WithinAbs(y, 1e-12));
  CHECK_THAT(e.vy[0], WithinAbs(vy + n * g * dt, 1e-12));
  CHECK_THAT(e.x[0], WithinAbs(n * vx * dt, 1e-12));
  CHECK(e.omega[0] == w);                                    // no moment: ω stays
  CHECK_THAT(e.phi[0], WithinAbs(n * w * dt, 1e-12));        // Δφ = (Δφ + ωΔt)/2 = ωΔt
  CHECK_THAT(e.dy[0], WithinAbs(vy * dt + g * dt * dt * (n - 1) + g * dt * dt * std::pow(2.0, -n), 1e-15));
}
