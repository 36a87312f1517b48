// A disk beyond the end of a segment wall touches the wall's end point: the closest point is clamped to
// the segment, the normal runs along the line from the centre to the end point, the overlap is
// r − |centre − end|.
#include <catch2/catch.hpp>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("A disk beyond either end of a segment wall is pushed along the line from the end point", "[walls]") {
  const double r = 0.06, kn = 1e5, dt = 1e-6;
  auto m = test::make_model({{"disk", 2650.0}, {"wall", 0.0}}, dt);
  test::set_law(m, 0, 1, test::linear_law(kn, 0.0, 0.5, 0.0, 0.0));
  dem::add_element(m, dem::Shape::disk, 0, r, {1.03, 0.04});   // beyond b = (1, 0): |d| = 0.05
  dem::add_element(m, dem::Shape::disk, 0, r, {-0.03, 0.04});  // beyond a = (0, 0)
  m.walls.push_back(test::segment_wall({0.0, 0.0}, {1.0, 0.0}, 1, "short"));
  dem::Simulation sim(m);
  sim.step();
  const double overlap = r - 0.05;
  const auto cb = sim.contact(0, 0, true), ca = sim.contact(1, 0, true);
  CHECK_THAT(cb.nx, WithinAbs(-0.6, 1e-14));  // from the centre towards the end point
  CHECK_THAT(cb.ny, WithinAbs(-0.8, 1e-14));
  CHECK_THAT(ca.nx, WithinAbs(0.6, 1e-14));
  CHECK_THAT(ca.ny, WithinAbs(-0.8, 1e-14));
  CHECK_THAT(cb.fn, WithinRel(kn * overlap, 1e-10));
  CHECK_THAT(ca.fn, WithinRel(kn * overlap, 1e-10));
  const auto& e = sim.model().elements;
  const double dv = kn * overlap * dt / e.mass[0];
  CHECK_THAT(e.vx[0], WithinRel(0.6 * dv, 1e-10));
  CHECK_THAT(e.vy[0], WithinRel(0.8 * dv, 1e-10));
  CHECK_THAT(e.vx[1], WithinRel(-0.6 * dv, 1e-10));
  CHECK_THAT(sim.model().walls[0].force.y, WithinRel(-2 * 0.8 * kn * overlap, 1e-10));
}
