// Drives are sampled at mid-step: the displacement of step k is v((k + ½)Δt)Δt, for walls and for
// driven elements. For a velocity ramp v = a t the sum is exact: x_n = x_0 + a t²/2 (t = nΔt).
#include <catch2/catch.hpp>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;

TEST_CASE("A wall and an element driven by a velocity ramp are exactly at x0 + a t^2/2 after n steps",
          "[walls][drive]") {
  const double dt = 1e-4, a = 2.0;
  auto m = test::make_model({{"disk", 2650.0}, {"wall", 0.0}}, dt);
  dem::VelocityHistory ramp;
  ramp.t = {0.0, 1.0};
  ramp.v = {{0.0, 0.0}, {a, -0.5 * a}};
  m.drives.push_back(ramp);
  dem::Wall w = test::segment_wall({-1.0, -5.0}, {1.0, -5.0}, 1, "floor");
  w.drive = 0;
  m.walls.push_back(w);
  const std::size_t i = dem::add_element(m, dem::Shape::disk, 0, 0.01, {0.0, 3.0});
  m.elements.motion[i] = dem::Motion::driven;
  m.elements.drive[i] = 0;
  dem::Simulation sim(m);
  const int n = 1000;
  for (int k = 0; k < n; ++k) sim.step();
  const double t = n * dt;  // 0.1 s; sampling at the start (end) of the step would be off by ∓a tΔt/2 = 1e-5 m
  const auto& wall = sim.model().walls[0];
  CHECK_THAT(wall.a.x, WithinAbs(-1.0 + 0.5 * a * t * t, 1e-13));
  CHECK_THAT(wall.b.x, WithinAbs(1.0 + 0.5 * a * t * t, 1e-13));
  CHECK_THAT(wall.a.y, WithinAbs(-5.0 - 0.25 * a * t * t, 1e-13));
  const auto& e = sim.model().elements;
  CHECK_THAT(e.x[i], WithinAbs(0.5 * a * t * t, 1e-13));
  CHECK_THAT(e.y[i], WithinAbs(3.0 - 0.25 * a * t * t, 1e-13));
  CHECK_THAT(e.vx[i], WithinAbs(a * (t - 0.5 * dt), 1e-13));  // the velocity of the last step, at its middle
}
