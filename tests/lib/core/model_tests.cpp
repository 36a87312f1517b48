// The moment of inertia of a PRE, measured: a PRE bonded to a wall and statically rotated by θ₀ about its
// centre gets the restoring moment M = −K_n a² θ₀ Σξᵢ² of its face springs (K_s = 0, no damping); after
// the first step (K17, plain start) ω = M Δt / I. M17: square mass m = 4r²lρ, I = (2/3)r²m;
// M18: disk mass m = πr²lρ, I = ½r²m.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

TEST_CASE("A PRE's angular acceleration under a known face moment gives I = (2/3) r^2 m (M17) or r^2 m/2 (M18)",
          "[pre][inertia]") {
  const auto pre_mass = GENERATE(dem::PreMass::square, dem::PreMass::disk);
  CAPTURE(static_cast<int>(pre_mass));
  const double r = 0.02, rho = 2000.0, kn = 1e6, theta0 = 1e-3, dt = 1e-6;
  auto m = test::make_model({{"block", rho}, {"wall", 0.0}}, dt);
  m.thickness = 0.5;
  test::set_law(m, 0, 1, test::bonded_face_law(4, kn, 0.0, 0.0));
  dem::add_element(m, dem::Shape::pre, 0, r, {0.0, r}, {}, 0.0, pre_mass);
  m.walls.push_back(test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "floor"));
  m.preloads.push_back({0, theta0, {0.0, r}});
  dem::Simulation sim(m);
  sim.step();
  const double l = 0.5;
  const double mass = pre_mass == dem::PreMass::square ? 4.0 * r * r * l * rho : std::numbers::pi * r * r * l * rho;
  const double inertia = pre_mass == dem::PreMass::square ? (2.0 / 3.0) * r * r * mass : 0.5 * r * r * mass;
  const double sum_xi2 = (9.0 + 1.0 + 1.0 + 9.0) / 16.0;  // ξ = ∓3/4, ∓1/4 (M13.1)
  const double moment = -kn * r * r * theta0 * sum_xi2;    // a = r for a wall (M19)
  const auto& e = sim.model().elements;
  CHECK_THAT(e.mass[0], WithinRel(mass, 1e-14));
  CHECK_THAT(e.omega[0], WithinRel(moment * dt / inertia, 1e-9));
  CHECK(std::abs(e.vx[0]) < 1e-12);  // no shear spring, no net normal force: a pure rotation
  CHECK(std::abs(e.vy[0]) < 1e-12);
}
