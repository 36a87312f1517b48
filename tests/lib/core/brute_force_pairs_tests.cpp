// The brute-force oracle of the neighbour search (neighbour_search.hpp, brute_force_pairs) writes exactly
// the pairs closer than r_i + r_j + skin into `out`, whatever `out` held before (a vector reused between
// rebuilds): the oracle the cell search is compared with must not carry old pairs. Planted bug that turned
// this red (g578749-009): out.clear() dropped.
#include <catch2/catch.hpp>

#include <vector>

#include "dem/core/neighbour_search.hpp"
#include "../test_support.hpp"

TEST_CASE("brute_force_pairs replaces what out held with exactly the close pairs", "[neighbour]") {
  auto m = test::make_model({{"sand", 2650.0}}, 1e-5);
  for (const double x : {0.0, 0.021, 0.05, 0.0705}) dem::add_element(m, dem::Shape::disk, 0, 0.01, {x, 0.0});
  std::vector<dem::CandidatePair> out = {{7, 9}, {0, 3}};  // stale
  dem::brute_force_pairs(m.elements, 0.002, out);          // cut 0.022: gaps 0.021, 0.029, 0.0205
  REQUIRE(out.size() == 2);
  CHECK((out[0].i == 0 && out[0].j == 1));
  CHECK((out[1].i == 2 && out[1].j == 3));
  dem::brute_force_pairs(m.elements, 0.0, out);  // cut 0.02: none
  CHECK(out.empty());
}
