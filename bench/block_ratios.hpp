#pragma once
// The ratio of two sides' speeds, block pair by block pair (dem2d_alternate, dem2d_divisible; bench/journal.md,
// "Ratios interleaved block by block").
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace bench {

/// The q-quantile of v, linear between order statistics.
inline double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (v[hi] - v[lo]) * (pos - static_cast<double>(lo));
}

struct BlockRatios {
  std::size_t pairs = 0;                  // block pairs counted
  double median = 0.0, q1 = 0.0, q3 = 0.0;  // of time of A / time of B per pair: the speed ratio B / A
};

/// Time of A / time of B for each pair of blocks (the same steps), without the first pair unless it is the only
/// one (warm-up: a pool of threads starts, the caches fill); its median and quartiles.
inline BlockRatios block_ratios(const std::vector<double>& a_seconds, const std::vector<double>& b_seconds) {
  std::vector<double> r;
  const std::size_t pairs = std::min(a_seconds.size(), b_seconds.size());
  for (std::size_t p = pairs > 1 ? 1 : 0; p < pairs; ++p) r.push_back(a_seconds[p] / b_seconds[p]);
  return {r.size(), quantile(r, 0.5), quantile(r, 0.25), quantile(r, 0.75)};
}

}  // namespace bench
