#include "engine/sensitivity_estimators.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace ver::sens {

namespace {

struct Point {
  std::vector<double> first, total, first_janon;
};

/// An index as numerator / variance: 0 for an output that does not vary, NaN (not computable) when either
/// overflowed or is not finite: outputs near ±1.7e308 give an infinite variance, and x / inf = 0 would
/// read as "nothing matters".
double index_ratio(double num, double var) {
  if (!std::isfinite(num) || !std::isfinite(var)) return std::nan("");
  return var > 0.0 ? num / var : 0.0;
}

/// The estimators over the rows `rows` (indices into the outputs, repeats allowed).
Point estimate(const std::vector<double>& fa, const std::vector<double>& fb, const std::vector<std::vector<double>>& fab,
               const std::vector<std::size_t>& rows, const MeanNoise* nz) {
  const std::size_t d = fab.size();
  const double n = static_cast<double>(rows.size());
  double mean = 0.0;
  for (std::size_t j : rows) mean += fa[j] + fb[j];
  mean /= 2.0 * n;
  double var = 0.0;
  for (std::size_t j : rows) var += (fa[j] - mean) * (fa[j] - mean) + (fb[j] - mean) * (fb[j] - mean);
  var /= 2.0 * n - 1.0;
  if (nz) {  // the noise left in the means inflates Var Y by the mean of their variances (sensitivity_noise.hpp)
    double left = 0.0;
    for (std::size_t j : rows) left += 0.5 * (nz->a[j] + nz->b[j]);
    var -= left / n;
  }
  Point p{std::vector<double>(d, 0.0), std::vector<double>(d, 0.0), std::vector<double>(d, 0.0)};
  for (std::size_t i = 0; i < d; ++i) {
    double s = 0.0, t = 0.0;
    double yy = 0.0, ym = 0.0, y2 = 0.0;  // Janon: Σ Y Y^i, Σ (Y + Y^i)/2, Σ (Y² + Y^i²)/2
    for (std::size_t j : rows) {
      s += fb[j] * (fab[i][j] - fa[j]);                      // Saltelli 2010 first order
      t += (fa[j] - fab[i][j]) * (fa[j] - fab[i][j]);        // Jansen total
      yy += fb[j] * fab[i][j];
      ym += 0.5 * (fb[j] + fab[i][j]);
      y2 += 0.5 * (fb[j] * fb[j] + fab[i][j] * fab[i][j]);
      if (nz) {  // E (e_A − e_AB)² = σ²_A + σ²_AB; E (e_B² + e_AB²)/2 = (σ²_B + σ²_AB)/2
        t -= nz->a[j] + nz->ab[i][j];
        y2 -= 0.5 * (nz->b[j] + nz->ab[i][j]);
      }
    }
    p.first[i] = index_ratio(s / n, var);
    p.total[i] = index_ratio(t / (2.0 * n), var);
    const double m = ym / n, den = y2 / n - m * m;           // Janon et al. 2014 first order
    p.first_janon[i] = index_ratio(yy / n - m * m, den);
  }
  return p;
}

}  // namespace

double percentile(std::vector<double> v, double q) {
  // NaN is not ordered (std::sort needs a strict weak order): a sample holding one has no percentile.
  if (std::any_of(v.begin(), v.end(), [](double x) { return std::isnan(x); })) return std::nan("");
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t k = static_cast<std::size_t>(std::floor(pos));
  if (k + 1 >= v.size()) return v.back();
  return v[k] + (pos - static_cast<double>(k)) * (v[k + 1] - v[k]);
}

SobolIndices sobol_indices(const std::vector<double>& fa, const std::vector<double>& fb,
                           const std::vector<std::vector<double>>& fab, std::size_t resamples, double confidence,
                           std::uint64_t seed, const MeanNoise* noise) {
  const std::size_t n = fa.size(), d = fab.size();
  if (noise && (noise->a.size() != n || noise->b.size() != n || noise->ab.size() != d))
    throw std::invalid_argument("sobol_indices: the noise of the means differs in shape from the outputs");
  if (fb.size() != n) throw std::invalid_argument("sobol_indices: f(A) and f(B) differ in length");
  for (const auto& c : fab)
    if (c.size() != n) throw std::invalid_argument("sobol_indices: f(AB_i) differs in length from f(A)");
  std::vector<std::size_t> rows;
  for (std::size_t j = 0; j < n; ++j) {
    bool ok = std::isfinite(fa[j]) && std::isfinite(fb[j]);
    for (std::size_t i = 0; i < d && ok; ++i) ok = std::isfinite(fab[i][j]);
    if (ok) rows.push_back(j);
  }
  SobolIndices out;
  out.rows_used = rows.size();
  out.first.resize(d);
  out.total.resize(d);
  out.first_janon.resize(d);
  if (rows.size() < 2) {
    for (auto* v : {&out.first, &out.total, &out.first_janon})
      for (auto& x : *v) x = {std::nan(""), std::nan(""), std::nan("")};
    return out;
  }
  const Point p = estimate(fa, fb, fab, rows, noise);
  {
    double mean = 0.0;
    for (std::size_t j : rows) mean += fa[j] + fb[j];
    mean /= 2.0 * static_cast<double>(rows.size());
    for (std::size_t j : rows) out.variance += (fa[j] - mean) * (fa[j] - mean) + (fb[j] - mean) * (fb[j] - mean);
    out.variance /= 2.0 * static_cast<double>(rows.size()) - 1.0;
    if (noise) {
      double left = 0.0;
      for (std::size_t j : rows) left += 0.5 * (noise->a[j] + noise->b[j]);
      out.variance -= left / static_cast<double>(rows.size());
    }
  }
  std::mt19937_64 rng(seed);
  std::vector<std::vector<double>> bs_first(d), bs_total(d), bs_janon(d);
  std::vector<std::size_t> sample(rows.size());
  for (std::size_t b = 0; b < resamples; ++b) {
    for (auto& s : sample) s = rows[static_cast<std::size_t>(rng() % rows.size())];
    const Point q = estimate(fa, fb, fab, sample, noise);
    for (std::size_t i = 0; i < d; ++i) {
      bs_first[i].push_back(q.first[i]);
      bs_total[i].push_back(q.total[i]);
      bs_janon[i].push_back(q.first_janon[i]);
    }
  }
  const double lo = 0.5 * (1.0 - confidence), hi = 1.0 - lo;
  for (std::size_t i = 0; i < d; ++i) {
    out.first[i] = {p.first[i], resamples ? percentile(bs_first[i], lo) : p.first[i],
                    resamples ? percentile(bs_first[i], hi) : p.first[i]};
    out.total[i] = {p.total[i], resamples ? percentile(bs_total[i], lo) : p.total[i],
                    resamples ? percentile(bs_total[i], hi) : p.total[i]};
    out.first_janon[i] = {p.first_janon[i], resamples ? percentile(bs_janon[i], lo) : p.first_janon[i],
                          resamples ? percentile(bs_janon[i], hi) : p.first_janon[i]};
  }
  return out;
}

SobolAsymptoticSd sobol_asymptotic_sd(const std::vector<double>& fa, const std::vector<double>& fb,
                                      const std::vector<std::vector<double>>& fab) {
  const std::size_t n = fa.size(), d = fab.size();
  if (fb.size() != n || n < 2) throw std::invalid_argument("sobol_asymptotic_sd: f(A), f(B) of equal length >= 2");
  double mu = 0.0;
  for (std::size_t j = 0; j < n; ++j) mu += fa[j] + fb[j];
  mu /= 2.0 * static_cast<double>(n);
  std::vector<double> w(n);
  double v = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    w[j] = 0.5 * ((fa[j] - mu) * (fa[j] - mu) + (fb[j] - mu) * (fb[j] - mu));
    v += w[j];
  }
  v /= static_cast<double>(n);
  SobolAsymptoticSd out;
  auto sd = [&](const std::vector<double>& z) {
    double mz = 0.0;
    for (double x : z) mz += x;
    mz /= static_cast<double>(n);
    const double si = mz / v;
    double m = 0.0, m2 = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double psi = z[j] - si * w[j];
      m += psi;
      m2 += psi * psi;
    }
    m /= static_cast<double>(n);
    return std::sqrt(std::max(0.0, m2 / static_cast<double>(n) - m * m)) / v;
  };
  for (std::size_t i = 0; i < d; ++i) {
    if (fab[i].size() != n) throw std::invalid_argument("sobol_asymptotic_sd: f(AB_i) differs in length from f(A)");
    std::vector<double> z1(n), zt(n);
    for (std::size_t j = 0; j < n; ++j) {
      z1[j] = fb[j] * (fab[i][j] - fa[j]);
      zt[j] = 0.5 * (fa[j] - fab[i][j]) * (fa[j] - fab[i][j]);
    }
    out.first.push_back(sd(z1));
    out.total.push_back(sd(zt));
    // Janon et al. 2014 (asymptotic normality): σ_∞² = Var[(Y − μ_i)(Y^i − μ_i) − S ((Y − μ_i)² + (Y^i − μ_i)²)/2] / V_i²
    // with Y = f(B), Y^i = f(AB_i) (they share x_i), μ_i, V_i their pooled mean and variance.
    double mi = 0.0;
    for (std::size_t j = 0; j < n; ++j) mi += 0.5 * (fb[j] + fab[i][j]);
    mi /= static_cast<double>(n);
    double c = 0.0, vi = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      c += (fb[j] - mi) * (fab[i][j] - mi);
      vi += 0.5 * ((fb[j] - mi) * (fb[j] - mi) + (fab[i][j] - mi) * (fab[i][j] - mi));
    }
    c /= static_cast<double>(n);
    vi /= static_cast<double>(n);
    const double sj = vi > 0.0 ? c / vi : 0.0;
    double m = 0.0, m2 = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double a = fb[j] - mi, b = fab[i][j] - mi;
      const double psi = a * b - sj * 0.5 * (a * a + b * b);
      m += psi;
      m2 += psi * psi;
    }
    m /= static_cast<double>(n);
    out.first_janon.push_back(vi > 0.0 ? std::sqrt(std::max(0.0, m2 / static_cast<double>(n) - m * m)) / vi : 0.0);
  }
  return out;
}

double normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("normal_quantile: 0 < p < 1");
  // Acklam's rational approximation (relative error 1.15e-9), then one Halley step on
  // Φ(x) − p = 0 with Φ from std::erfc: the error falls to round-off.
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01, -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00, 3.754408661907416e+00};
  const double p_low = 0.02425;
  double x;
  if (p < p_low || p > 1.0 - p_low) {
    const double q = std::sqrt(-2.0 * std::log(p < p_low ? p : 1.0 - p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
    if (p > 1.0 - p_low) x = -x;
  } else {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }
  const double e = 0.5 * std::erfc(-x / std::sqrt(2.0)) - p;
  const double u = e * std::sqrt(2.0 * 3.14159265358979323846) * std::exp(0.5 * x * x);
  return x - u / (1.0 + 0.5 * x * u);
}

namespace {

struct EffectStats {
  double mu, mu_star, sigma;
};

EffectStats effect_stats(const std::vector<double>& ee) {
  const double n = static_cast<double>(ee.size());
  double mu = 0.0, mu_star = 0.0;
  for (double e : ee) {
    mu += e;
    mu_star += std::abs(e);
  }
  mu = n > 0 ? mu / n : std::nan("");
  mu_star = n > 0 ? mu_star / n : std::nan("");
  double var = 0.0;
  for (double e : ee) var += (e - mu) * (e - mu);
  return {mu, mu_star, n > 1 ? std::sqrt(var / (n - 1.0)) : std::nan("")};
}

}  // namespace

MorrisEffects morris_effects(const std::vector<MorrisTrajectory>& tr, const std::vector<std::vector<double>>& f,
                             std::size_t d, std::size_t resamples, double confidence, std::uint64_t seed) {
  if (f.size() != tr.size()) throw std::invalid_argument("morris_effects: one output row per trajectory");
  std::vector<std::vector<double>> ee(d);
  for (std::size_t t = 0; t < tr.size(); ++t) {
    if (f[t].size() != tr[t].points.size()) throw std::invalid_argument("morris_effects: one output per point");
    for (std::size_t k = 0; k < tr[t].order.size(); ++k) {
      const std::size_t i = tr[t].order[k];
      const double dx = tr[t].points[k + 1][i] - tr[t].points[k][i];
      const double e = (f[t][k + 1] - f[t][k]) / dx;
      if (std::isfinite(e)) ee[i].push_back(e);
    }
  }
  MorrisEffects m;
  std::mt19937_64 rng(seed);
  const double lo = 0.5 * (1.0 - confidence), hi = 1.0 - lo;
  const double z = normal_quantile(hi);
  for (std::size_t i = 0; i < d; ++i) {
    const EffectStats st = effect_stats(ee[i]);
    m.mu.push_back(st.mu);
    m.mu_star.push_back(st.mu_star);
    m.sigma.push_back(st.sigma);
    m.effects.push_back(ee[i].size());
    std::vector<double> b_mu, b_star, b_sigma, sample(ee[i].size());
    for (std::size_t b = 0; b < resamples && !ee[i].empty(); ++b) {
      for (auto& e : sample) e = ee[i][static_cast<std::size_t>(rng() % ee[i].size())];
      const EffectStats q = effect_stats(sample);
      b_mu.push_back(q.mu);
      b_star.push_back(q.mu_star);
      b_sigma.push_back(q.sigma);
    }
    auto interval = [&](double est, const std::vector<double>& boot) -> Interval {
      if (boot.empty() || !std::isfinite(est)) return {est, est, est};
      return {est, percentile(boot, lo), percentile(boot, hi)};
    };
    m.mu_ci.push_back(interval(st.mu, b_mu));
    m.mu_star_ci.push_back(interval(st.mu_star, b_star));
    m.sigma_ci.push_back(ee[i].size() > 1 ? interval(st.sigma, b_sigma) : Interval{st.sigma, st.sigma, st.sigma});
    double sm = 0.0, s2 = 0.0;
    for (double x : b_star) sm += x;
    sm = b_star.empty() ? 0.0 : sm / static_cast<double>(b_star.size());
    for (double x : b_star) s2 += (x - sm) * (x - sm);
    m.mu_star_conf.push_back(b_star.size() > 1 ? z * std::sqrt(s2 / static_cast<double>(b_star.size() - 1)) : 0.0);
  }
  return m;
}

}  // namespace ver::sens
