#pragma once
// O(n) neighbour search (docs/model.md §1, K27): a cell list with square cells of side 2 r_max + skin,
// producing every pair i < j whose gap is below the skin, sorted by (i, j). Buffers are reused
// between builds, so a build allocates nothing once the sizes have settled.
//
// On several threads the build is two phases: sort_into_cells() on one thread, then collect() over
// disjoint ranges of i on any threads at once; the parts concatenated in the order of their ranges are
// build()'s list, element for element, however the i are split.
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
  /// The first phase: the cell grid and the elements sorted into it. false: fewer than two active
  /// elements (no pairs; collect() must not be called).
  bool sort_into_cells(const Elements& e, double skin);
  /// The largest |x| or |y| of an active element at the last sort_into_cells (0 if none).
  double extent() const { return extent_; }
  /// The second phase: appends to `out` the pairs whose first element i lies in [b, end), sorted by (i, j).
  /// Reads only; threads may call it at once on disjoint ranges (each with its own `out`).
  void collect(const Elements& e, double skin, std::uint32_t b, std::uint32_t end,
               std::vector<CandidatePair>& out) const;

 private:
  std::vector<std::uint32_t> cell_start_, cell_items_, cell_of_;
  std::vector<std::uint32_t> scratch_;
  std::uint32_t nx_ = 0, ny_ = 0;
  double extent_ = 0.0;
};

/// The same result by checking every pair: the oracle for tests.
void brute_force_pairs(const Elements& e, double skin, std::vector<CandidatePair>& out);

}  // namespace dem
