#include "dem/core/neighbour_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dem {

void NeighbourSearch::build(const Elements& e, double skin, std::vector<CandidatePair>& out) {
  out.clear();
  if (sort_into_cells(e, skin)) collect(e, skin, 0, static_cast<std::uint32_t>(e.size()), out);
}

bool NeighbourSearch::sort_into_cells(const Elements& e, double skin) {
  const std::size_t n = e.size();
  double xmin = std::numeric_limits<double>::max(), ymin = xmin;
  double xmax = std::numeric_limits<double>::lowest(), ymax = xmax, rmax = 0.0;
  std::size_t n_active = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!e.active[i]) continue;
    ++n_active;
    xmin = std::min(xmin, e.x[i]);
    xmax = std::max(xmax, e.x[i]);
    ymin = std::min(ymin, e.y[i]);
    ymax = std::max(ymax, e.y[i]);
    rmax = std::max(rmax, e.radius[i]);
  }
  extent_ = n_active == 0 ? 0.0 : std::max({std::abs(xmin), std::abs(xmax), std::abs(ymin), std::abs(ymax)});
  if (n_active < 2) return false;
  double cell = 2.0 * rmax + skin;
  // Keep the grid at most ~4 cells per element (a sparse cloud would otherwise need a huge grid).
  const double w = xmax - xmin, h = ymax - ymin;
  while ((std::floor(w / cell) + 1.0) * (std::floor(h / cell) + 1.0) > 4.0 * n_active + 16.0) cell *= 2.0;
  const auto nx = nx_ = static_cast<std::uint32_t>(std::floor(w / cell)) + 1;
  const auto ny = ny_ = static_cast<std::uint32_t>(std::floor(h / cell)) + 1;
  const double inv = 1.0 / cell;

  // Counting sort of the elements into cells.
  cell_start_.assign(static_cast<std::size_t>(nx) * ny + 1, 0);
  cell_of_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!e.active[i]) continue;
    const auto cx = std::min(nx - 1, static_cast<std::uint32_t>((e.x[i] - xmin) * inv));
    const auto cy = std::min(ny - 1, static_cast<std::uint32_t>((e.y[i] - ymin) * inv));
    cell_of_[i] = cy * nx + cx;
    ++cell_start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_items_.resize(n_active);
  scratch_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    if (e.active[i]) cell_items_[scratch_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
  return true;
}

void NeighbourSearch::collect(const Elements& e, double skin, std::uint32_t b, std::uint32_t end,
                              std::vector<CandidatePair>& out) const {
  const std::uint32_t nx = nx_, ny = ny_;
  // For each i (in index order) collect j > i in the 3×3 block of cells, then sort them.
  for (std::uint32_t i = b; i < end; ++i) {
    if (!e.active[i]) continue;
    const std::uint32_t ci = cell_of_[i];
    const std::uint32_t cx = ci % nx, cy = ci / nx;
    const std::size_t first = out.size();
    const double xi = e.x[i], yi = e.y[i], ri = e.radius[i];
    for (std::uint32_t yy = cy ? cy - 1 : 0; yy <= std::min(cy + 1, ny - 1); ++yy) {
      for (std::uint32_t xx = cx ? cx - 1 : 0; xx <= std::min(cx + 1, nx - 1); ++xx) {
        const std::uint32_t c = yy * nx + xx;
        for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
          const std::uint32_t j = cell_items_[k];
          if (j <= i) continue;
          const double ddx = e.x[j] - xi, ddy = e.y[j] - yi, cut = ri + e.radius[j] + skin;  // as the oracle
          if (ddx * ddx + ddy * ddy < cut * cut) out.push_back({i, j});
        }
      }
    }
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
              [](CandidatePair a, CandidatePair b) { return a.j < b.j; });
  }
}

void brute_force_pairs(const Elements& e, double skin, std::vector<CandidatePair>& out) {
  out.clear();
  for (std::uint32_t i = 0; i < e.size(); ++i) {
    if (!e.active[i]) continue;
    for (std::uint32_t j = i + 1; j < e.size(); ++j) {
      if (!e.active[j]) continue;
      const double ddx = e.x[j] - e.x[i], ddy = e.y[j] - e.y[i];
      const double cut = e.radius[i] + e.radius[j] + skin;
      if (ddx * ddx + ddy * ddy < cut * cut) out.push_back({i, j});
    }
  }
}

}  // namespace dem
