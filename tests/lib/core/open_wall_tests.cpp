// Opening a wall (Simulation::open_wall, a silo's gate): its contacts are dropped and no other wall's.
// Two PREs (face law) each rest on a wall of their own; the left wall is opened after 200 steps. The
// right wall's block must then go on bit for bit as in a run where nothing opens, and the left block
// falls freely.
#include <catch2/catch.hpp>

#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

namespace {

const std::string kTwoBlocks = R"([case]
title = "two PREs on two walls"
[physics]
gravity = [0.0, -9.81]
[[material]]
name = "block"
density = "2650 kg/m^3"
[[material]]
name = "wall"
[[contact]]
between = ["block", "wall"]
law = "face"
segments = 2
positions = "ends"
kn = "12 kN/mm"
ks_ratio = 0.4
friction_angle = "30 deg"
damping_ratio = 0.3
[[contact]]
between = ["block", "block"]
law = "face"
kn = "12 kN/mm"
ks_ratio = 0.4
friction_angle = "30 deg"
damping_ratio = 0.3
[[element]]
shape = "pre"
material = "block"
radius = "1 cm"
position = ["-0.1 m", "1 cm"]
[[element]]
shape = "pre"
material = "block"
radius = "1 cm"
position = ["0.1 m", "1 cm"]
[[wall]]
name = "left"
from = ["-0.2 m", "0 m"]
to = ["0 m", "0 m"]
material = "wall"
[[wall]]
name = "right"
from = ["0 m", "0 m"]
to = ["0.2 m", "0 m"]
material = "wall"
[numerics]
dt = "1e-6 s"
duration = "1 ms"
)";

}  // namespace

TEST_CASE("Opening a wall drops its face contacts and no other wall's", "[walls]") {
  const dem::Case c = dem::read_case(test::write_temp("open_wall.toml", kTwoBlocks));
  dem::Simulation opened(c.model), closed(c.model);
  for (int k = 0; k < 200; ++k) opened.step(), closed.step();
  REQUIRE(opened.model().walls[1].force.y < 0.0);  // each block presses on its wall
  REQUIRE(opened.model().walls[0].force.y < 0.0);
  opened.open_wall(0);
  for (int k = 0; k < 200; ++k) opened.step(), closed.step();
  CHECK(opened.model().walls[0].force.y == 0.0);
  CHECK(opened.model().walls[1].force.y == closed.model().walls[1].force.y);  // the right block, untouched
  const std::size_t right = opened.index_of(1), left = opened.index_of(0);
  CHECK(opened.model().elements.y[right] == closed.model().elements.y[right]);
  CHECK(opened.model().elements.vy[left] < closed.model().elements.vy[left] - 1e-3);  // the left one falls
}
