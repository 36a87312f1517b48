// The order in which a Morris trajectory moves its factors is a uniformly drawn permutation
// (verification/engine/sensitivity_sampling.hpp, Fisher–Yates): over many trajectories every one of the
// d! orders occurs, about equally often, and every factor is moved first. A shuffle that skipped its last
// swap (a generated mutant, issue 40) always moved the first two factors in the same relative order.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "engine/sensitivity_sampling.hpp"

using namespace ver::sens;

TEST_CASE("Morris: the factor order of a trajectory is a uniform permutation", "[sensitivity][morris]") {
  for (const std::size_t d : {2u, 3u}) {
    const std::size_t r = 1200;
    std::map<std::vector<std::size_t>, int> seen;
    for (const auto& tr : morris_trajectories(r, d, 4, 11)) {
      std::vector<std::size_t> sorted = tr.order;
      std::sort(sorted.begin(), sorted.end());
      for (std::size_t i = 0; i < d; ++i) REQUIRE(sorted[i] == i);  // a permutation
      ++seen[tr.order];
    }
    const std::size_t orders = d == 2 ? 2 : 6;
    CHECK(seen.size() == orders);
    for (const auto& [order, count] : seen) {  // binomial: mean r/d!, sd < 20 for r = 1200
      const double mean = double(r) / double(orders);
      CHECK(std::abs(count - mean) < 5.0 * std::sqrt(mean));
    }
  }
}
