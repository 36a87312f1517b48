#include "dem/cases/generators.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <unordered_map>

namespace dem {

OrderedArrangement ordered_arrangement(int s, int rows, double width, double radius, double gap) {
  if (s < 2) throw std::invalid_argument("s must be at least 2 (rows of s and s - 1 disks)");
  if (rows < 1) throw std::invalid_argument("rows must be at least 1");
  if (!(radius > 0.0) || !(gap >= 0.0) || !(width > 0.0)) throw std::invalid_argument("need width > 0, radius > 0, gap >= 0");
  OrderedArrangement a;
  a.s = s;
  a.rows = rows;
  const double contact = 2.0 * radius + gap;                    // centre distance of diagonal neighbours
  a.dx = (width - 2.0 * radius - 2.0 * gap) / (s - 1);          // the row of s touches both walls (up to gap)
  if (!(a.dx >= contact))
    throw std::invalid_argument("the disks of a row of s overlap (d_x = " + std::to_string(a.dx) +
                                " m < 2r + gap): fewer disks per row or a wider box");
  if (!(a.dx / 2.0 < contact))
    throw std::invalid_argument("d_x/2 >= 2r + gap: a disk cannot rest on the two below it (more disks per row)");
  a.dy = std::sqrt(contact * contact - 0.25 * a.dx * a.dx);
  a.count = static_cast<std::int64_t>((rows + 1) / 2) * s + static_cast<std::int64_t>(rows / 2) * (s - 1);
  a.height = (rows - 1) * a.dy + 2.0 * radius + gap;
  a.min_gap = gap;
  if (rows >= 3) a.min_gap = std::min(a.min_gap, 2.0 * a.dy - 2.0 * radius);  // rows k and k+2, one above the other
  a.min_gap = std::min(a.min_gap, a.dx - 2.0 * radius);                         // neighbours in a row
  a.k_geom = 0.25 * a.dx * a.dx / (a.dy * a.dy);
  return a;
}

int rows_nearest_count(int s, std::int64_t target) {
  if (s < 2 || target < 1) throw std::invalid_argument("need s >= 2 and a target count >= 1");
  int best = 1;
  std::int64_t best_err = -1;
  constexpr int kMaxRows = 1000000;  // as `rows` allows
  for (int rows = 1; rows <= kMaxRows; ++rows) {
    const std::int64_t n = static_cast<std::int64_t>((rows + 1) / 2) * s + static_cast<std::int64_t>(rows / 2) * (s - 1);
    const std::int64_t err = std::llabs(n - target);
    if (best_err < 0 || err < best_err) best = rows, best_err = err;  // strict: ties keep the fewer rows
    if (n >= target) return best;
  }
  // never capped silently: a target beyond the largest arrangement is refused
  throw std::invalid_argument("a count of " + std::to_string(target) + " disks needs more than " + std::to_string(kMaxRows) +
                              " rows of (s-1)/s; give at most that many rows");
}

std::vector<Vec2> ordered_positions(const OrderedArrangement& a, double left, double floor, double radius, double gap) {
  std::vector<Vec2> out;
  out.reserve(static_cast<std::size_t>(a.count));
  const double x0 = left + radius + gap;
  for (int k = 0; k < a.rows; ++k) {
    const bool full = k % 2 == 0;
    const int n = full ? a.s : a.s - 1;
    const double y = floor + radius + gap + k * a.dy;
    for (int j = 0; j < n; ++j) out.push_back({x0 + (full ? 0.0 : 0.5 * a.dx) + j * a.dx, y});
  }
  return out;
}

double RadiusDistribution::draw(SplitMix64& rng) const {
  if (!radii.empty()) {
    const double u = rng.uniform();
    double acc = 0.0;
    for (std::size_t k = 0; k < radii.size(); ++k) {
      acc += fractions[k];
      if (u < acc) return radii[k];
    }
    return radii.back();
  }
  if (max > min) return min + (max - min) * rng.uniform();
  return min;
}

double RadiusDistribution::largest() const {
  return radii.empty() ? max : *std::max_element(radii.begin(), radii.end());
}

std::vector<PlacedDisk> random_fill(Vec2 lo, Vec2 hi, std::int64_t count, const RadiusDistribution& dist,
                                    std::uint64_t seed, double gap, std::int64_t attempts) {
  const double rmax = dist.largest();
  if (!(rmax > 0.0)) throw std::invalid_argument("random fill: radii must be positive");
  if (!(hi.x - lo.x > 2.0 * rmax) || !(hi.y - lo.y > 2.0 * rmax))
    throw std::invalid_argument("random fill: the region is narrower than the largest disk");
  SplitMix64 rng(seed);
  // cell list of placed disks, cells of side 2 rmax + gap: a disk overlaps only disks in the 3 × 3 cells
  const double cell = 2.0 * rmax + gap;
  auto key = [&](Vec2 p) {
    const auto cx = static_cast<std::int64_t>(std::floor((p.x - lo.x) / cell));
    const auto cy = static_cast<std::int64_t>(std::floor((p.y - lo.y) / cell));
    return std::pair{cx, cy};
  };
  auto hash = [](std::int64_t cx, std::int64_t cy) { return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff); };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
  std::vector<PlacedDisk> out;
  out.reserve(static_cast<std::size_t>(count));
  for (std::int64_t n = 0; n < count; ++n) {
    const double r = dist.draw(rng);
    bool placed = false;
    for (std::int64_t t = 0; t < attempts && !placed; ++t) {
      const Vec2 p{lo.x + r + (hi.x - lo.x - 2.0 * r) * rng.uniform(), lo.y + r + (hi.y - lo.y - 2.0 * r) * rng.uniform()};
      const auto [cx, cy] = key(p);
      bool free = true;
      for (std::int64_t a = cx - 1; a <= cx + 1 && free; ++a)
        for (std::int64_t b = cy - 1; b <= cy + 1 && free; ++b) {
          auto it = cells.find(hash(a, b));
          if (it == cells.end()) continue;
          for (std::size_t k : it->second)
            if (norm(out[k].centre - p) < out[k].radius + r + gap) { free = false; break; }
        }
      if (free) {
        cells[hash(cx, cy)].push_back(out.size());
        out.push_back({p, r});
        placed = true;
      }
    }
    if (!placed)
      throw std::runtime_error("random fill: could not place disk " + std::to_string(n) + " of " + std::to_string(count) +
                               " in " + std::to_string(attempts) + " attempts (the region is too full; random "
                               "sequential addition jams near an area fraction of 0.55)");
  }
  return out;
}

}  // namespace dem
