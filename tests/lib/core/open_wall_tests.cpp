// Opening a wall (Simulation::open_wall, a silo's gate): its contacts are dropped and no other wall's.
// Two PREs (face law) each rest on a wall of their own; the left wall is opened after 200 steps. The
// right wall's block must then go on bit for bit as in a run where nothing opens, and the left block
// falls freely.
#include <catch2/catch.hpp>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

TEST_CASE("Opening a wall drops its face contacts and no other wall's", "[walls]") {
  const dem::Case c = dem::read_case(test::source("tests/lib/fixtures/two_blocks_two_walls.toml"));
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
