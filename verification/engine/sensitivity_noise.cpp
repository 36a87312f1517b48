// Run-to-run noise against parameter effect (sensitivity_noise.hpp): the split of each output's
// variance over the samples of a study with replicates, its table, indices.csv rows and, for a test
// function with added noise of known variance, the checks against the exact noise fraction.
#include "engine/sensitivity_noise.hpp"
#include "engine/sensitivity_estimators.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <fmt/format.h>

#include "engine/sensitivity_study.hpp"

namespace ver::sens {

namespace {

struct Split {
  double noise_var, effect_var, fraction;
};

Split split_of(const std::vector<double>& means, const std::vector<double>& within, const std::vector<std::size_t>& rows, double r) {
  const double n = static_cast<double>(rows.size());
  double m = 0.0, noise = 0.0;
  for (std::size_t k : rows) {
    m += means[k];
    noise += within[k];
  }
  m /= n;
  noise /= n;
  double var = 0.0;
  for (std::size_t k : rows) var += (means[k] - m) * (means[k] - m);
  var /= n - 1.0;
  const double effect = var - noise / r;  // the noise left in the means: σ²_noise / R
  const double total = effect + noise;
  return {noise, effect, total > 0.0 ? noise / total : std::nan("")};
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

double standard_normal_draw(std::uint64_t seed, std::uint64_t k) {
  const std::uint64_t h1 = splitmix64(splitmix64(seed) ^ splitmix64(2 * k)), h2 = splitmix64(h1 ^ splitmix64(2 * k + 1));
  const double u1 = (static_cast<double>(h1 >> 11) + 0.5) * 0x1.0p-53, u2 = static_cast<double>(h2 >> 11) * 0x1.0p-53;  // u1 in (0, 1)
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

NoiseSplit noise_split(const std::vector<double>& means, const std::vector<double>& within_var, std::size_t replicates,
                       std::size_t resamples, double confidence, std::uint64_t seed) {
  NoiseSplit out;
  out.replicates = replicates;
  std::vector<std::size_t> rows;
  for (std::size_t k = 0; k < means.size() && k < within_var.size(); ++k)
    if (std::isfinite(means[k]) && std::isfinite(within_var[k])) rows.push_back(k);
  out.samples = rows.size();
  if (rows.size() < 3 || replicates < 2) {
    out.noise_var = out.effect_var = std::nan("");
    out.fraction = out.noise_sd = {std::nan(""), std::nan(""), std::nan("")};
    return out;
  }
  const double r = static_cast<double>(replicates);
  const Split p = split_of(means, within_var, rows, r);
  out.noise_var = p.noise_var;
  out.effect_var = p.effect_var;
  std::mt19937_64 rng(seed);
  std::vector<double> bf, bs;
  std::vector<std::size_t> sample(rows.size());
  for (std::size_t b = 0; b < resamples; ++b) {
    for (auto& k : sample) k = rows[static_cast<std::size_t>(rng() % rows.size())];
    const Split q = split_of(means, within_var, sample, r);
    if (std::isfinite(q.fraction)) bf.push_back(q.fraction);
    bs.push_back(std::sqrt(q.noise_var));
  }
  const double lo = 0.5 * (1.0 - confidence), hi = 1.0 - lo;
  out.fraction = {p.fraction, bf.empty() ? p.fraction : percentile(bf, lo), bf.empty() ? p.fraction : percentile(bf, hi)};
  const double sd = std::sqrt(p.noise_var);
  out.noise_sd = {sd, bs.empty() ? sd : percentile(bs, lo), bs.empty() ? sd : percentile(bs, hi)};
  return out;
}

std::optional<MeanNoise> mean_noise_of_runs(const Plan& plan, std::size_t o, std::size_t n, std::size_t d) {
  const Run& first = plan.runs[plan.sobol_begin];
  if (first.noise_var.empty()) return std::nullopt;
  MeanNoise m{std::vector<double>(n), std::vector<double>(n), std::vector<std::vector<double>>(d, std::vector<double>(n))};
  auto left = [&](std::size_t k) {  // the variance of run k's mean: s² / R
    const Run& r = plan.runs[plan.sobol_begin + k];
    return r.noise_var[o] / static_cast<double>(r.replicates);
  };
  for (std::size_t j = 0; j < n; ++j) {
    m.a[j] = left(j);
    m.b[j] = left(n + j);
    for (std::size_t i = 0; i < d; ++i) m.ab[i][j] = left((2 + i) * n + j);
  }
  return m;
}

namespace {

/// The split of one output over runs [begin, end) of the plan: a table row, indices.csv's and, for a
/// noisy test function, the checks against φ = σ² / (V_f + σ²).
void noise_row(const Plan& plan, const ExactIndices& exact, const std::string& method, std::size_t begin, std::size_t end, std::size_t o,
               nlohmann::json& rows, Analysis& an) {
  const Sens& s = an.s;
  std::vector<double> means, within;
  for (std::size_t k = begin; k < end; ++k) {
    means.push_back(plan.runs[k].outputs[o]);
    within.push_back(plan.runs[k].noise_var.empty() ? std::nan("") : plan.runs[k].noise_var[o]);
  }
  const std::size_t resamples = method == "sobol" ? s.resamples : s.morris_resamples;
  const double confidence = method == "sobol" ? s.confidence : s.morris_confidence;
  const NoiseSplit ns = noise_split(means, within, s.replicates.size(), resamples, confidence);
  // Exact only over the inputs' distribution (Sobol'): Morris points sit on a grid whose variance differs.
  const double exact_fraction = method == "sobol" && s.function && s.noise_sd > 0.0 && std::isfinite(exact.variance)
                                    ? s.noise_sd * s.noise_sd / (exact.variance + s.noise_sd * s.noise_sd)
                                    : std::nan("");
  // Morris: the μ* that the noise alone gives, E|ε − ε'| / Δ with ε, ε' ~ N(0, σ²/R): 2σ / (Δ √(π R)).
  const double mu_star_floor = method == "morris" ? 2.0 * std::sqrt(ns.noise_var) /
                                                         (morris_delta(s.levels) * std::sqrt(std::numbers::pi * static_cast<double>(ns.replicates)))
                                                  : std::nan("");
  rows.push_back({s.outputs[o], method == "sobol" ? "Sobol' A and B" : "Morris points", std::to_string(ns.samples), std::to_string(ns.replicates),
                  num(ns.noise_sd.estimate), fmt::format("[{}, {}]", num(ns.noise_sd.low), num(ns.noise_sd.high)),
                  num(std::sqrt(std::max(0.0, ns.effect_var))), num(ns.fraction.estimate),
                  fmt::format("[{}, {}]", num(ns.fraction.low), num(ns.fraction.high)), num(exact_fraction), num(mu_star_floor)});
  const std::string ex = std::isfinite(exact_fraction) ? fmt::format("{:.17g}", exact_fraction) : std::string();
  an.idx_csv << method << "," << s.outputs[o] << ",\"run-to-run noise\",noise_fraction,"
             << fmt::format("{:.17g},{:.17g},{:.17g},", ns.fraction.estimate, ns.fraction.low, ns.fraction.high) << ex << "\n";
  an.idx_csv << method << "," << s.outputs[o] << ",\"run-to-run noise\",noise_sd,"
             << fmt::format("{:.17g},{:.17g},{:.17g},", ns.noise_sd.estimate, ns.noise_sd.low, ns.noise_sd.high)
             << (s.function && s.noise_sd > 0.0 ? fmt::format("{:.17g}", s.noise_sd) : std::string()) << "\n";
  if (!std::isfinite(exact_fraction)) return;
  const Interval& f = ns.fraction;
  an.add_check(fmt::format("noise fraction of {} ({} + noise σ = {}, {} samples × {} replicates, {})", s.outputs[o], s.function->name,
                           num(s.noise_sd), ns.samples, ns.replicates, method),
               exact_fraction, f.estimate, std::abs(f.estimate - exact_fraction),
               exact_fraction < f.estimate ? f.estimate - f.low : f.high - f.estimate,
               fmt::format("the {:.0f} % bootstrap interval must contain the exact σ²/(V_f + σ²)", 100.0 * confidence),
               exact_fraction >= f.low && exact_fraction <= f.high, fmt::format("interval [{}, {}]", num(f.low), num(f.high)));
  if (s.index_tolerance)
    an.add_check(fmt::format("noise fraction of {} within ±{} ({})", s.outputs[o], num(*s.index_tolerance), method), exact_fraction,
                 f.estimate, std::abs(f.estimate - exact_fraction), *s.index_tolerance, s.index_tolerance_reason,
                 std::abs(f.estimate - exact_fraction) <= *s.index_tolerance, "");
}

}  // namespace

void analyse_noise(const Plan& plan, const ExactIndices& exact, Analysis& an) {
  const Sens& s = an.s;
  if (s.replicates.empty()) return;
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t o = 0; o < s.outputs.size(); ++o) {
    if (s.sobol) noise_row(plan, exact, "sobol", plan.sobol_begin, plan.sobol_begin + 2 * s.samples, o, rows, an);
    if (s.morris) noise_row(plan, exact, "morris", plan.morris_begin, plan.sobol_begin, o, rows, an);
  }
  if (rows.empty()) return;
  an.tables.push_back(
      {{"title", fmt::format("Run-to-run noise against parameter effect ({} replicates per sample): σ_noise² = mean within-sample variance, "
                             "V_effect = Var(means) − σ_noise²/R, noise fraction = σ_noise² / (V_effect + σ_noise²) of a single run; "
                             "Sobol' over the independent rows of A and B, Morris over the trajectories' grid points (not the inputs' "
                             "distribution); bootstrap intervals over the samples",
                             s.replicates.size())},
       {"columns", {"output", "samples", "n", "R", "σ_noise", "interval", "√V_effect", "noise fraction", "interval", "exact", "noise μ* (Morris)"}},
       {"rows", rows}});
}

}  // namespace ver::sens
