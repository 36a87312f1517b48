// index_of_id (spatial_order.hpp): the array index of an element id, for arrays in the case's order (the
// id is the index), arrays without ids (elements built by hand: the id is the index too) and reordered
// arrays (a search). Planted bug that turned this red (g578749-013): the shortcut's "or" made "and", so an
// array without ids threw "element 3 does not exist".
#include <catch2/catch.hpp>

#include <stdexcept>

#include "dem/core/elements.hpp"
#include "dem/core/spatial_order.hpp"

TEST_CASE("index_of_id: the id is the index without ids or in the case order - a search after reordering", "[spatial_order]") {
  dem::Elements none;  // no ids at all
  CHECK(dem::index_of_id(none, 3) == 3);
  dem::Elements e;
  e.id = {0, 1, 2, 3};
  CHECK(dem::index_of_id(e, 2) == 2);
  e.id = {2, 0, 3, 1};
  CHECK(dem::index_of_id(e, 0) == 1);
  CHECK(dem::index_of_id(e, 1) == 3);
  CHECK(dem::index_of_id(e, 3) == 2);
  CHECK_THROWS_AS(dem::index_of_id(e, 4), std::invalid_argument);
}
