#include "engine/sensitivity_second_order.hpp"
#include "engine/sensitivity_estimators.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace ver::sens {

namespace {

/// S_jk for every pair over the rows `rows` (repeats allowed), in the order (0,1), (0,2), …, (d−2,d−1).
std::vector<double> second_order_at(const std::vector<double>& fa, const std::vector<double>& fb,
                                    const std::vector<std::vector<double>>& fab, const std::vector<std::vector<double>>& fba,
                                    const std::vector<std::size_t>& rows) {
  const std::size_t d = fab.size();
  const double n = static_cast<double>(rows.size());
  double mean = 0.0;
  for (std::size_t r : rows) mean += fa[r] + fb[r];
  mean /= 2.0 * n;
  double var = 0.0;
  for (std::size_t r : rows) var += (fa[r] - mean) * (fa[r] - mean) + (fb[r] - mean) * (fb[r] - mean);
  var /= 2.0 * n - 1.0;
  std::vector<double> first(d, 0.0), out;
  for (std::size_t i = 0; i < d; ++i) {
    double s = 0.0;
    for (std::size_t r : rows) s += fb[r] * (fab[i][r] - fa[r]);  // Saltelli 2010 first order
    first[i] = var > 0.0 ? s / n / var : 0.0;
  }
  for (std::size_t j = 0; j < d; ++j)
    for (std::size_t k = j + 1; k < d; ++k) {
      double c = 0.0;
      for (std::size_t r : rows) c += fba[j][r] * fab[k][r] - fa[r] * fb[r];  // closed V_jk (Saltelli 2002)
      out.push_back(var > 0.0 ? c / n / var - first[j] - first[k] : 0.0);
    }
  return out;
}

}  // namespace

std::vector<SecondOrderIndex> sobol_second_order(const std::vector<double>& fa, const std::vector<double>& fb,
                                                 const std::vector<std::vector<double>>& fab,
                                                 const std::vector<std::vector<double>>& fba, std::size_t resamples,
                                                 double confidence, std::uint64_t seed) {
  const std::size_t n = fa.size(), d = fab.size();
  if (fb.size() != n || fba.size() != d) throw std::invalid_argument("sobol_second_order: f(A), f(B), f(AB_i), f(BA_i) do not match");
  for (std::size_t i = 0; i < d; ++i)
    if (fab[i].size() != n || fba[i].size() != n) throw std::invalid_argument("sobol_second_order: f(AB_i) or f(BA_i) differs in length");
  std::vector<std::size_t> rows;
  for (std::size_t r = 0; r < n; ++r) {
    bool ok = std::isfinite(fa[r]) && std::isfinite(fb[r]);
    for (std::size_t i = 0; i < d && ok; ++i) ok = std::isfinite(fab[i][r]) && std::isfinite(fba[i][r]);
    if (ok) rows.push_back(r);
  }
  std::vector<SecondOrderIndex> out;
  for (std::size_t j = 0; j < d; ++j)
    for (std::size_t k = j + 1; k < d; ++k) out.push_back({j, k, {std::nan(""), std::nan(""), std::nan("")}});
  if (rows.size() < 2) return out;
  const std::vector<double> est = second_order_at(fa, fb, fab, fba, rows);
  std::vector<std::vector<double>> boot(out.size());
  std::mt19937_64 rng(seed);
  std::vector<std::size_t> sample(rows.size());
  for (std::size_t b = 0; b < resamples; ++b) {
    for (auto& s : sample) s = rows[static_cast<std::size_t>(rng() % rows.size())];
    const std::vector<double> q = second_order_at(fa, fb, fab, fba, sample);
    for (std::size_t p = 0; p < out.size(); ++p) boot[p].push_back(q[p]);
  }
  const double lo = 0.5 * (1.0 - confidence), hi = 1.0 - lo;
  for (std::size_t p = 0; p < out.size(); ++p)
    out[p].s2 = {est[p], resamples ? percentile(boot[p], lo) : est[p], resamples ? percentile(boot[p], hi) : est[p]};
  return out;
}

}  // namespace ver::sens
