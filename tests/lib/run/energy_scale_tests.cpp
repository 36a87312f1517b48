// The gravity part of the blow-up bound (lib/dem/run/loop_state.cpp, energy_scale) by hand: the drop is
// the extent of the elements and walls along g, plus a free fall over the run where no wall lies beyond
// every element. Planted bug that turns it red: the walls left out of the extent's lower end.
#include <catch2/catch.hpp>

#include "dem/core/simulation.hpp"
#include "dem/run/loop_state.hpp"
#include "../test_support.hpp"

namespace {
constexpr double r = 0.01, mass = 2.0, g = 9.81, T = 0.5;

/// One free disk of radius r at height 0.5 m, gravity −y, a run of T; walls added by the test.
dem::Model disk_at_half_metre() {
  dem::Model m = test::make_model({{"d", 2650.0}, {"w", 0.0}}, 1e-5);
  m.gravity = {0.0, -g};
  m.numerics.duration = T;
  dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 0.5}, {}, 0.0, dem::PreMass::square, mass);
  return m;
}
}  // namespace

TEST_CASE("energy scale: the drop spans the elements and the walls along g", "[outputs]") {
  SECTION("a floor below the disk: from the disk's top to the floor") {
    dem::Model m = disk_at_half_metre();
    m.walls.push_back(test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "floor"));
    const dem::EnergyScale es = dem::energy_scale(m, 3.0);
    CHECK(es.drop == Approx(0.5 + r).epsilon(1e-14));
    CHECK(es.gravity_work == Approx(mass * g * (0.5 + r)).epsilon(1e-14));
    CHECK(es.total == Approx(3.0 + mass * g * (0.5 + r)).epsilon(1e-14));
  }
  SECTION("a floor and a lid above: from the lid to the floor") {
    dem::Model m = disk_at_half_metre();
    m.walls.push_back(test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "floor"));
    m.walls.push_back(test::segment_wall({-1.0, 2.0}, {1.0, 2.0}, 1, "lid"));
    CHECK(dem::energy_scale(m, 0.0).drop == Approx(2.0).epsilon(1e-14));
  }
  SECTION("only a lid: the disk may fall freely for the whole run") {
    dem::Model m = disk_at_half_metre();
    m.walls.push_back(test::segment_wall({-1.0, 2.0}, {1.0, 2.0}, 1, "lid"));
    CHECK(dem::energy_scale(m, 0.0).drop == Approx(2.0 - (0.5 - r) + 0.5 * g * T * T).epsilon(1e-14));
  }
}
