#include "engine/sensitivity_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

#include <gsl/gsl_qrng.h>

#include "engine/sensitivity_scramble.hpp"

namespace ver::sens {

double value_at(const Parameter& p, double u) {
  if (p.distribution != Distribution::uniform && p.distribution != Distribution::log_uniform) return quantile_of(p, u);
  if (p.integer) {  // each integer low … high equally likely for u uniform in [0, 1]
    const double span = p.high - p.low;
    return p.low + std::min(std::floor(u * (span + 1.0)), span);
  }
  if (p.log_uniform) return std::exp(std::log(p.low) + u * (std::log(p.high) - std::log(p.low)));
  return p.low + u * (p.high - p.low);
}

Matrix sobol_points(std::size_t n, std::size_t d, std::uint64_t scramble) {
  if (d < 1 || d > gsl_qrng_sobol->max_dimension)
    throw std::invalid_argument("sobol_points: dimension must be 1..40 (GSL's Sobol' generator)");
  std::unique_ptr<gsl_qrng, decltype(&gsl_qrng_free)> q(gsl_qrng_alloc(gsl_qrng_sobol, static_cast<unsigned>(d)),
                                                        &gsl_qrng_free);
  Matrix m;
  m.reserve(n);
  if (n > 0) m.emplace_back(d, 0.0);  // GSL starts after the origin; put it back (net property)
  std::vector<double> x(d);
  while (m.size() < n) {
    gsl_qrng_get(q.get(), x.data());
    m.push_back(x);
  }
  if (scramble != kUnscrambled)
    for (std::size_t k = 0; k < d; ++k) {
      const OwenScramble perm(scramble, k);
      for (auto& row : m) row[k] = perm(row[k]);
    }
  return m;
}

SaltelliDesign saltelli_design(std::size_t n, std::size_t d, std::uint64_t scramble, bool second_order) {
  const Matrix p = sobol_points(n, 2 * d, scramble);
  SaltelliDesign s;
  for (const auto& row : p) {
    s.a.emplace_back(row.begin(), row.begin() + static_cast<std::ptrdiff_t>(d));
    s.b.emplace_back(row.begin() + static_cast<std::ptrdiff_t>(d), row.end());
  }
  s.ab.assign(d, s.a);
  for (std::size_t i = 0; i < d; ++i)
    for (std::size_t j = 0; j < n; ++j) s.ab[i][j][i] = s.b[j][i];
  if (second_order) {
    s.ba.assign(d, s.b);
    for (std::size_t i = 0; i < d; ++i)
      for (std::size_t j = 0; j < n; ++j) s.ba[i][j][i] = s.a[j][i];
  }
  return s;
}

double morris_delta(int levels) { return static_cast<double>(levels) / (2.0 * (levels - 1)); }

std::vector<MorrisTrajectory> morris_trajectories(std::size_t r, std::size_t d, int levels, std::uint64_t seed) {
  if (levels < 2 || levels % 2 != 0) throw std::invalid_argument("morris: levels must be even and >= 2");
  std::mt19937_64 rng(seed);
  auto draw = [&](std::uint64_t n) { return static_cast<std::size_t>(rng() % n); };  // platform-independent
  const double delta = morris_delta(levels);
  const double step = 1.0 / (levels - 1);
  std::vector<MorrisTrajectory> out;
  for (std::size_t t = 0; t < r; ++t) {
    MorrisTrajectory tr;
    std::vector<double> x(d);
    for (auto& xi : x) xi = step * static_cast<double>(draw(static_cast<std::uint64_t>(levels)));
    tr.order.resize(d);
    for (std::size_t i = 0; i < d; ++i) tr.order[i] = i;
    for (std::size_t i = d; i > 1; --i) std::swap(tr.order[i - 1], tr.order[draw(i)]);  // Fisher–Yates
    tr.points.push_back(x);
    for (std::size_t i : tr.order) {
      x[i] = x[i] + delta <= 1.0 + 1e-12 ? x[i] + delta : x[i] - delta;
      tr.points.push_back(x);
    }
    out.push_back(std::move(tr));
  }
  return out;
}

std::vector<double> oat_grid(std::size_t n) {
  if (n < 2) throw std::invalid_argument("oat: at least two points");
  std::vector<double> u(n);
  for (std::size_t k = 0; k < n; ++k) u[k] = static_cast<double>(k) / static_cast<double>(n - 1);
  return u;
}

}  // namespace ver::sens
