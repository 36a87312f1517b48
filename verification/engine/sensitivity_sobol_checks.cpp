// Sobol' estimators against a test function, evaluated here on Saltelli designs of its own: the
// bootstrap intervals' width against the central limit theorem, and the index error over doubling
// sample sizes at the quasi-random rate (convergence.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include <fmt/format.h>

#include "engine/convergence.hpp"
#include "engine/sensitivity_study.hpp"

namespace ver::sens {

DesignOutputs function_on_design(const Sens& s, std::size_t n, Transform transform, std::uint64_t scramble) {
  const std::size_t d = s.params.size();
  const SaltelliDesign des = saltelli_design(n, d, scramble ? scramble : s.sobol_seed);
  auto f = [&](const std::vector<double>& u) {
    std::vector<double> x;
    for (std::size_t i = 0; i < d; ++i) x.push_back(value_at(s.params[i], u[i]));
    return evaluate(*s.function, x);
  };
  DesignOutputs y{std::vector<double>(n), std::vector<double>(n), std::vector<std::vector<double>>(d, std::vector<double>(n)), {}};
  for (std::size_t j = 0; j < n; ++j) {
    y.fa[j] = f(des.a[j]);
    y.fb[j] = f(des.b[j]);
    for (std::size_t i = 0; i < d; ++i) y.fab[i][j] = f(des.ab[i][j]);
  }
  apply_transform(transform, y.fa, y.fb, y.fab);
  return y;
}

// Test functions: the bootstrap interval's width against the central limit theorem for N rows,
// 2 z σ_∞ / √N, σ_∞ from 2^16 rows of the exact function (sensitivity_estimators.hpp).
void check_interval_widths(const SobolIndices& si, Transform transform, const std::string& tsuffix, Analysis& an) {
  const Sens& s = an.s;
  const DesignOutputs g = function_on_design(s, std::size_t{1} << 16, transform);
  const SobolAsymptoticSd sd = sobol_asymptotic_sd(g.fa, g.fb, g.fab);
  const double z = normal_quantile(0.5 * (1.0 + s.confidence));
  // The bootstrap's own noise: a percentile of B resamples has standard error √(p(1−p)/B)/φ(z) in
  // units of the spread (p = (1 − c)/2), so the width 2 z σ has relative error √2 × that / (2 z);
  // 3 of those, plus 10 % for what the CLT leaves out at finite N (the ratio estimator's skew).
  const double p_end = 0.5 * (1.0 - s.confidence);
  const double phi_z = std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi);
  const double quantile_noise = std::sqrt(2.0) * std::sqrt(p_end * (1.0 - p_end) / static_cast<double>(s.resamples)) / phi_z / (2.0 * z);
  const double band = 3.0 * quantile_noise + 0.1;
  for (std::size_t i = 0; i < s.params.size(); ++i)
    for (const auto& [kind, iv, sig] : {std::tuple{"S", si.first[i], sd.first[i]}, std::tuple{"ST", si.total[i], sd.total[i]},
                                        std::tuple{"S(Janon)", si.first_janon[i], sd.first_janon[i]}}) {
      if (!(sig > 0.0)) continue;  // an exact estimator (σ_∞ = 0): no width to compare
      const double clt = 2.0 * z * sig / std::sqrt(static_cast<double>(si.rows_used));
      const double w = iv.high - iv.low;
      an.add_check(fmt::format("width of the {}_{} interval of {} ({}, N = {}{})", kind, i + 1, s.params[i].label, s.function->name, s.samples, tsuffix),
                   clt, w, std::abs(w - clt) / clt, band,
                   fmt::format("CLT: a {:.0f} % interval over N i.i.d. rows is 2 z σ_∞/√N wide (z = {:.4f}, σ_∞ from 2^16 rows); the "
                               "bootstrap width within 3 × {:.1f} % (its {} resamples' quantile noise) + 10 % (finite-N skew) of it",
                               100.0 * s.confidence, z, 100.0 * quantile_noise, s.resamples),
                   std::abs(w - clt) <= band * clt, fmt::format("σ_∞ = {}, relative difference", num(sig)));
      an.checks.back()["error_kind"] = "rel";
    }
}

void sobol_convergence(const ExactIndices& exact_sobol, Transform transform, const std::string& tsuffix, Analysis& an) {
  const Sens& s = an.s;
  const std::size_t d = s.params.size();
  std::vector<double> h, err, err_janon;
  nlohmann::json crow = nlohmann::json::array();
  // Owen-scrambled points: the error at one N is random; its root mean square over kScramblings
  // scramblings (seeds seed, seed + 1, …) is what falls at the quasi-random rate.
  constexpr std::uint64_t kScramblings = 32;
  for (std::size_t nn : s.convergence) {
    double e2 = 0.0, ej2 = 0.0;
    for (std::uint64_t k = 0; k < kScramblings; ++k) {
      const DesignOutputs y = function_on_design(s, nn, transform, s.sobol_seed + k);
      const SobolIndices si = sobol_indices(y.fa, y.fb, y.fab, 0);
      double e1 = 0.0, ej1 = 0.0;
      for (std::size_t i = 0; i < d; ++i) {
        e1 = std::max({e1, std::abs(si.first[i].estimate - exact_sobol.first[i]), std::abs(si.total[i].estimate - exact_sobol.total[i])});
        ej1 = std::max(ej1, std::abs(si.first_janon[i].estimate - exact_sobol.first[i]));
      }
      e2 += e1 * e1 / static_cast<double>(kScramblings);
      ej2 += ej1 * ej1 / static_cast<double>(kScramblings);
    }
    const double e = std::sqrt(e2), ej = std::sqrt(ej2);
    h.push_back(1.0 / static_cast<double>(nn));
    err.push_back(e);
    err_janon.push_back(ej);
    crow.push_back({std::to_string(nn), num(e), num(ej)});
  }
  ConvergenceOptions co;
  co.reference = 0.0;
  co.expected_order = s.expected_order;
  // The least-squares order of one error series, checked one-sided against the expected order.
  auto rate = [&](const std::vector<double>& errors, const std::string& series_label, const std::string& check_of) {
    const Series ser = analyse_convergence(h, errors, co, fmt::format("{} ({}{}, RMS over scramblings)", series_label, s.function->name, tsuffix), "1/N");
    an.series.push_back(to_json(ser));
    const double p = ser.fitted_order.value_or(std::nan(""));
    if (s.expected_order)
      an.add_check(fmt::format("order of the {} in N ({}, N = {} … {}{})", check_of, s.function->name, s.convergence.front(), s.convergence.back(), tsuffix),
                   0.0, errors.back(), errors.back(), NAN,
                   fmt::format("Sobol' points: error ~ N^-1 up to log factors (Monte Carlo: N^-1/2); least-squares order must be at least {} − {}",
                               *s.expected_order, s.order_band),
                   std::isfinite(p) && p >= *s.expected_order - s.order_band, "one-sided: faster than promised passes", p);
  };
  rate(err, "max |index − exact|", "index error");
  rate(err_janon, "max |S (Janon) − exact|", "Janon first-order error");
  an.tables.push_back({{"title", fmt::format("Largest index error over doubling sample sizes (root mean square over {} Owen scramblings){}",
                                             kScramblings, tsuffix)},
                       {"columns", {"N", "max |S − exact|, |S_T − exact|", "max |S (Janon) − exact|"}}, {"rows", crow}});
}

}  // namespace ver::sens
