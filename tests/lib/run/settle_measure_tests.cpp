// The normalisation of the settling criterion (lib/dem/run/quantities.hpp, mean_increment; [stop]
// settled_increment and Kiyama's settled_increment_factor): the mean of |Δx| and |Δy| over the two
// translational degrees of freedom of each active free element, so the count is 2 per free element and
// fixed, driven and removed elements count for nothing (their increments are not the packing's).
// Planted bug that turned this red: one degree of freedom per element (n += 1).
#include <catch2/catch.hpp>

#include "dem/core/simulation.hpp"
#include "dem/run/quantities.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

TEST_CASE("mean_increment: the mean of |dx| and |dy| over 2 degrees of freedom per active free element", "[run][settle]") {
  auto m = test::make_model({{"sand", 2650.0}}, 1e-5);
  for (int k = 0; k < 5; ++k) dem::add_element(m, dem::Shape::disk, 0, 0.01, {0.03 * k, 0.0});
  m.elements.motion[2] = dem::Motion::fixed;
  m.elements.motion[3] = dem::Motion::driven;
  dem::VelocityHistory still;
  still.t = {0.0};
  still.v = {{0.0, 0.0}};
  m.drives.push_back(still);
  m.elements.drive[3] = 0;
  dem::Simulation sim(m);
  dem::Elements& e = sim.model().elements;
  e.active[4] = 0;  // removed (a discharged disk)
  const double dx[5] = {1e-3, 0.0, 7.0, 5.0, 9.0}, dy[5] = {-2e-3, 1e-3, 7.0, 5.0, 9.0};
  for (int k = 0; k < 5; ++k) e.dx[k] = dx[k], e.dy[k] = dy[k], e.dphi[k] = 3.0;  // rotations do not count
  const double expected = (1e-3 + 2e-3 + 0.0 + 1e-3) / 4.0;
  CHECK_THAT(dem::mean_increment(sim), WithinRel(expected, 1e-15));
  CHECK_THAT(dem::compile_quantity("mean_increment", sim.model())(sim), WithinRel(expected, 1e-15));
  // a second set: three free elements
  e.motion[2] = dem::Motion::free;
  CHECK_THAT(dem::mean_increment(sim), WithinRel((4e-3 + 14.0) / 6.0, 1e-15));
}
