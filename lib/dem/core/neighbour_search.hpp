#pragma once
// O(n) neighbour search (docs/model.md §1, K27): a cell list with square cells of side 2 r_max + skin,
// producing every pair i < j whose gap is below the skin, sorted by (i, j). Buffers are reused
// between builds, so a build allocates nothing once the sizes have settled.
#include <cstdint>
#include <vector>

#include "dem/core/elements.hpp"

namespace dem {

struct CandidatePair {
  std::uint32_t i, j;
};

class NeighbourSearch {
 public:
  /// Fills `out` with all active pairs (i < j) with |x_i − x_j| < r_i + r_j + skin, sorted.
  void build(const Elements& e, double skin, std::vector<CandidatePair>& out);

 private:
  std::vector<std::uint32_t> cell_start_, cell_items_, cell_of_;
  std::vector<std::uint32_t> scratch_;
};

/// The same result by checking every pair: the oracle for tests.
void brute_force_pairs(const Elements& e, double skin, std::vector<CandidatePair>& out);

}  // namespace dem
