#include "engine/sensitivity_delta.hpp"
#include "engine/sensitivity_estimators.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <numbers>
#include <random>
#include <stdexcept>

namespace ver::sens {

namespace {

constexpr std::size_t kGrid = 100;  // points of the density grid (SALib's)

/// The Gaussian kernel density of the values `rows` of y on the grid, Silverman's bandwidth.
std::vector<double> kde(const std::vector<double>& y, const std::vector<std::size_t>& rows, const std::vector<double>& grid) {
  const double n = static_cast<double>(rows.size());
  double m = 0.0, m2 = 0.0;
  for (std::size_t j : rows) m += y[j];
  m /= n;
  for (std::size_t j : rows) m2 += (y[j] - m) * (y[j] - m);
  const double sd = std::sqrt(m2 / (n - 1.0));
  const double h = sd * std::pow(3.0 * n / 4.0, -0.2);
  std::vector<double> f(grid.size(), 0.0);
  const double norm = 1.0 / (n * h * std::sqrt(2.0 * std::numbers::pi));
  for (std::size_t j : rows)
    for (std::size_t k = 0; k < grid.size(); ++k) {
      const double z = (grid[k] - y[j]) / h;
      f[k] += std::exp(-0.5 * z * z) * norm;
    }
  return f;
}

/// δ̂ of one input over the points `rows` (repeats allowed): classes by the rank of x among them.
double delta_hat(const std::vector<double>& x, const std::vector<double>& y, std::vector<std::size_t> rows, const std::vector<double>& grid,
                 std::size_t classes) {
  const std::size_t n = rows.size();
  const std::vector<double> fy = kde(y, rows, grid);
  std::stable_sort(rows.begin(), rows.end(), [&](std::size_t p, std::size_t q) { return x[p] < x[q]; });  // ordinal ranks
  double d = 0.0;
  for (std::size_t c = 0; c < classes; ++c) {
    const std::size_t b = c * n / classes, e = (c + 1) * n / classes;  // ranks (b, e]: m_j = j N / M
    const std::vector<std::size_t> cls(rows.begin() + static_cast<std::ptrdiff_t>(b), rows.begin() + static_cast<std::ptrdiff_t>(e));
    if (cls.empty()) continue;
    bool constant = true;
    for (std::size_t j : cls) constant = constant && y[j] == y[cls.front()];
    std::vector<double> diff(grid.size());
    if (constant || cls.size() < 2) {
      for (std::size_t k = 0; k < grid.size(); ++k) diff[k] = std::abs(fy[k]);
    } else {
      const std::vector<double> fc = kde(y, cls, grid);
      for (std::size_t k = 0; k < grid.size(); ++k) diff[k] = std::abs(fy[k] - fc[k]);
    }
    double integral = 0.0;
    for (std::size_t k = 1; k < grid.size(); ++k) integral += 0.5 * (diff[k] + diff[k - 1]) * (grid[k] - grid[k - 1]);
    d += static_cast<double>(cls.size()) / (2.0 * static_cast<double>(n)) * integral;
  }
  return d;
}

/// δ̂ of one input by histograms over the points `rows`: K cells of [lo, hi].
double histogram_hat(const std::vector<double>& x, const std::vector<double>& y, std::vector<std::size_t> rows, const std::vector<double>& grid,
                     std::size_t classes) {
  const std::size_t n = rows.size(), cells = grid.size() - 1;
  const double lo = grid.front(), hi = grid.back();
  auto cell = [&](double v) { return std::min(cells - 1, static_cast<std::size_t>(std::max(0.0, (v - lo) / (hi - lo) * static_cast<double>(cells)))); };
  std::vector<double> p(cells, 0.0);
  for (std::size_t j : rows) p[cell(y[j])] += 1.0 / static_cast<double>(n);
  std::stable_sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  double d = 0.0;
  for (std::size_t c = 0; c < classes; ++c) {
    const std::size_t b = c * n / classes, e = (c + 1) * n / classes;
    if (e == b) continue;
    std::vector<double> q(cells, 0.0);
    for (std::size_t k = b; k < e; ++k) q[cell(y[rows[k]])] += 1.0 / static_cast<double>(e - b);
    double tv = 0.0;
    for (std::size_t k = 0; k < cells; ++k) tv += std::abs(q[k] - p[k]);
    d += 0.5 * tv * static_cast<double>(e - b) / static_cast<double>(n);
  }
  return d;
}

using Hat = double (*)(const std::vector<double>&, const std::vector<double>&, std::vector<std::size_t>, const std::vector<double>&, std::size_t);

}  // namespace

/// The classes, the grid (kernel: 100 points; histogram: K + 1 cell ends) and the bias-reduced bootstrap.
static std::vector<Interval> delta_of(const std::vector<std::vector<double>>& x, const std::vector<double>& y, std::size_t resamples, double confidence,
                               std::uint64_t seed, bool histogram) {
  std::vector<std::size_t> rows;
  for (std::size_t j = 0; j < y.size(); ++j)
    if (std::isfinite(y[j])) rows.push_back(j);
  for (const auto& xi : x)
    if (xi.size() != y.size()) throw std::invalid_argument("borgonovo_delta: an input differs in length from the output");
  std::vector<Interval> out(x.size(), Interval{std::nan(""), std::nan(""), std::nan("")});
  if (rows.size() < 10) return out;
  const double n = static_cast<double>(rows.size());
  const double expo = 2.0 / (7.0 + std::tanh((1500.0 - n) / 500.0));
  const std::size_t classes = std::min<std::size_t>(static_cast<std::size_t>(std::ceil(std::pow(n, expo))), 48);
  double lo = y[rows.front()], hi = lo;
  for (std::size_t j : rows) lo = std::min(lo, y[j]), hi = std::max(hi, y[j]);
  if (!(hi > lo)) {
    for (auto& iv : out) iv = {0.0, 0.0, 0.0};
    return out;
  }
  const std::size_t points = histogram ? 2 * static_cast<std::size_t>(std::ceil(std::sqrt(n / static_cast<double>(classes)))) + 1 : kGrid;
  std::vector<double> grid(points);
  for (std::size_t k = 0; k < points; ++k) grid[k] = lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(points - 1);
  const Hat hat = histogram ? &histogram_hat : &delta_hat;
  std::mt19937_64 rng(seed);
  std::vector<std::vector<std::size_t>> draws(resamples, std::vector<std::size_t>(rows.size()));
  for (auto& d : draws)
    for (auto& j : d) j = rows[static_cast<std::size_t>(rng() % rows.size())];
  const double qlo = 0.5 * (1.0 - confidence), qhi = 1.0 - qlo;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double d0 = hat(x[i], y, rows, grid, classes);
    if (resamples == 0) {
      out[i] = {d0, d0, d0};
      continue;
    }
    std::vector<double> corrected;  // 2 δ̂ − δ̂_b (Plischke et al. 2013, eq. 30)
    for (const auto& d : draws) corrected.push_back(2.0 * d0 - hat(x[i], y, d, grid, classes));
    const double mean = std::accumulate(corrected.begin(), corrected.end(), 0.0) / static_cast<double>(corrected.size());
    out[i] = {mean, percentile(corrected, qlo), percentile(corrected, qhi)};
  }
  return out;
}

std::vector<Interval> borgonovo_delta(const std::vector<std::vector<double>>& x, const std::vector<double>& y, std::size_t resamples,
                                      double confidence, std::uint64_t seed) {
  return delta_of(x, y, resamples, confidence, seed, false);
}

std::vector<Interval> histogram_delta(const std::vector<std::vector<double>>& x, const std::vector<double>& y, std::size_t resamples,
                                      double confidence, std::uint64_t seed) {
  return delta_of(x, y, resamples, confidence, seed, true);
}

}  // namespace ver::sens
