#pragma once
// Fill generators for granular cases (refs §6.1): Kiyama's ordered "(s−1)/s" arrangements of equal
// disks between two vertical walls, and a reproducible random fill of a rectangle. Pure functions:
// positions and radii only; the case reader turns them into elements ([[arrangement]], cases/README.md).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "dem/core/vec2.hpp"

namespace dem {

/// Geometry of an (s−1)/s arrangement (refs §6.1, Kiyama §5(1)): rows alternate between s disks (the
/// first, bottom row) and s−1 disks; a row of s touches both side walls up to `gap`, an interior disk
/// sits on the two below it at a centre distance 2r + gap, and there is no horizontal contact:
///   d_x = (B − 2r − 2 gap)/(s − 1),  d_y = √((2r + gap)² − d_x²/4).
/// With gap = 0 this is the table of refs §6.1 (d_x, d_y, K_geom = (d_x/2)²/d_y²).
struct OrderedArrangement {
  double dx = 0.0;       ///< horizontal centre spacing in a row [m]
  double dy = 0.0;       ///< vertical spacing of consecutive rows [m]
  int s = 0;             ///< disks in the bottom row
  int rows = 0;
  std::int64_t count = 0;     ///< disks: ceil(rows/2)·s + floor(rows/2)·(s−1)
  double height = 0.0;        ///< fill height (rows − 1) d_y + 2r (+ gap to the floor) [m]
  double min_gap = 0.0;       ///< smallest surface gap between two disks or a disk and a wall [m]
  double k_geom = 0.0;        ///< tan²θ_c = (d_x/2)²/d_y², refs §6.1
};

/// Throws std::invalid_argument with the reason if the arrangement does not exist (s < 2, rows of s
/// overlapping horizontally: d_x < 2r + gap, or no diagonal contact: d_x/2 ≥ 2r + gap).
OrderedArrangement ordered_arrangement(int s, int rows, double width, double radius, double gap);

/// The row count whose disk count is nearest `target` (ties: the fewer rows); refs §6.1 "~350". Throws
/// std::invalid_argument for a target beyond 10^6 rows (never capped silently).
int rows_nearest_count(int s, std::int64_t target);

/// Centres of the arrangement in a box whose left wall is x = left and floor is y = floor (y up): the
/// bottom row at y = floor + r + gap, first disk at x = left + r + gap; row by row, left to right.
std::vector<Vec2> ordered_positions(const OrderedArrangement& a, double left, double floor, double radius, double gap);

/// Deterministic 64-bit generator (splitmix64): the same seed gives the same sequence on every
/// platform (the standard distributions are not portable), uniform() in [0, 1) with 53 bits.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

/// Radius distribution of a random fill: one radius (min = max, no list), uniform in [min, max], or a
/// list of radii drawn with the given number fractions (bidisperse: two entries).
struct RadiusDistribution {
  double min = 0.0, max = 0.0;
  std::vector<double> radii, fractions;  ///< list form (fractions sum to 1)
  double draw(SplitMix64& rng) const;
  double largest() const;
};

struct PlacedDisk {
  Vec2 centre;
  double radius = 0.0;
};

/// Random sequential addition: `count` disks with radii drawn from `dist`, centres uniform in the
/// rectangle [lo, hi] shrunk so that every disk lies inside it, no two disks closer than `gap` (surface
/// to surface). Up to `attempts` tries per disk; throws std::runtime_error naming the disk it could not
/// place (the region is too full). Reproducible from `seed`.
std::vector<PlacedDisk> random_fill(Vec2 lo, Vec2 hi, std::int64_t count, const RadiusDistribution& dist,
                                    std::uint64_t seed, double gap, std::int64_t attempts = 100000);

}  // namespace dem
