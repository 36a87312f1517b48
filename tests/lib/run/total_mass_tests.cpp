// The mass the summary and `dem2d check` state (lib/dem/run/resolved_case.hpp, total_mass): the active
// elements' masses, each counted once, a removed element's not at all. Planted bug that turns it red:
// each element's mass counted by its neighbour's active flag.
#include <catch2/catch.hpp>

#include "dem/run/resolved_case.hpp"
#include "../test_support.hpp"

TEST_CASE("total mass: the active elements' masses and a removed element's not", "[outputs]") {
  dem::Model m = test::make_model({{"d", 2650.0}}, 1e-6);
  const double masses[4] = {1.0, 2.0, 4.0, 8.0};
  for (int k = 0; k < 4; ++k)
    dem::add_element(m, dem::Shape::disk, 0, 0.01, {0.1 * k, 0.0}, {}, 0.0, dem::PreMass::square, masses[k]);
  CHECK(dem::total_mass(m) == 15.0);
  for (std::size_t removed = 0; removed < 4; ++removed) {
    CAPTURE(removed);
    dem::Model r = m;
    r.elements.active[removed] = 0;
    CHECK(dem::total_mass(r) == 15.0 - masses[removed]);
  }
}
