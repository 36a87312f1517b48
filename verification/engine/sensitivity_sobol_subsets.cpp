// Convergence of the Sobol' indices against sample size (Sarrazin, Pianosi & Wagener 2016) for a study
// of a case: the indices and their bootstrap intervals recomputed on the nested first N/8, N/4, N/2 and
// N rows of A, B and AB_i (the prefixes of a scrambled Sobol' sequence are themselves nets: no new run),
// a table, a figure of S_T against N with its intervals, and the ranking by S_T at each size with its
// Spearman correlation to the full sample's ranking (screening and ranking stability).
#include <algorithm>
#include <iterator>
#include <cmath>
#include <numeric>
#include <optional>

#include <fmt/format.h>

#include "engine/sensitivity_study.hpp"

namespace ver::sens {

/// Ranks (1 = largest) of the values, ties by order.
std::vector<double> descending_ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] > v[b]; });
  std::vector<double> rank(v.size());
  for (std::size_t k = 0; k < order.size(); ++k) rank[order[k]] = static_cast<double>(k + 1);
  return rank;
}

/// Spearman's rank correlation of two rankings without ties: 1 − 6 Σ d² / (d (d² − 1)).
double spearman(const std::vector<double>& ra, const std::vector<double>& rb) {
  const double d = static_cast<double>(ra.size());
  if (ra.size() < 2) return 1.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < ra.size(); ++i) sum += (ra[i] - rb[i]) * (ra[i] - rb[i]);
  return 1.0 - 6.0 * sum / (d * (d * d - 1.0));
}

namespace {

/// The first m rows of each of A, B, AB_i (and their noise) of a design of n rows.
DesignOutputs prefix(const DesignOutputs& y, std::size_t m) {
  DesignOutputs p{{y.fa.begin(), y.fa.begin() + static_cast<std::ptrdiff_t>(m)}, {y.fb.begin(), y.fb.begin() + static_cast<std::ptrdiff_t>(m)}, {}, {}};
  for (const auto& c : y.fab) p.fab.emplace_back(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(m));
  return p;
}
std::optional<MeanNoise> prefix(const std::optional<MeanNoise>& nz, std::size_t m) {
  if (!nz) return std::nullopt;
  MeanNoise p{{nz->a.begin(), nz->a.begin() + static_cast<std::ptrdiff_t>(m)}, {nz->b.begin(), nz->b.begin() + static_cast<std::ptrdiff_t>(m)}, {}};
  for (const auto& c : nz->ab) p.ab.emplace_back(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(m));
  return p;
}

std::string cell(const Interval& iv) { return fmt::format("{} [{}, {}]", num(iv.estimate), num(iv.low), num(iv.high)); }

}  // namespace

void sobol_subsets(const DesignOutputs& y, const std::optional<MeanNoise>& nz, const std::string& yname, const std::string& id, Analysis& an) {
  const Sens& s = an.s;
  const std::size_t n = s.samples, d = s.params.size();
  if (n < 32) return;  // N/8 >= 4 rows
  const std::vector<std::size_t> sizes = {n / 8, n / 4, n / 2, n};
  std::vector<SobolIndices> at;
  for (std::size_t m : sizes) {
    const DesignOutputs p = prefix(y, m);
    const std::optional<MeanNoise> pz = prefix(nz, m);
    at.push_back(sobol_indices(p.fa, p.fb, p.fab, s.resamples, s.confidence, 12345, pz ? &*pz : nullptr));
  }
  nlohmann::json cols = {"output", "index", "parameter"};
  for (std::size_t m : sizes) cols.push_back(fmt::format("N = {}", m));
  nlohmann::json rows = nlohmann::json::array();
  for (const char* kind : {"S_T", "S"})
    for (std::size_t i = 0; i < d; ++i) {
      nlohmann::json r = {yname, kind, s.params[i].label};
      for (const auto& si : at) r.push_back(cell(std::string(kind) == "S_T" ? si.total[i] : si.first[i]));
      rows.push_back(r);
    }
  // The ranking by S_T at each size against the full sample's; the widest S_T interval.
  std::vector<double> full_total;
  for (std::size_t i = 0; i < d; ++i) full_total.push_back(at.back().total[i].estimate);
  const std::vector<double> full_rank = descending_ranks(full_total);
  nlohmann::json rank_row = {yname, "ranking by S_T", ""}, rho_row = {yname, "Spearman ρ with N's ranking", ""},
                 width_row = {yname, "widest S_T interval", ""};
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    std::vector<double> total;
    double widest = 0.0;
    for (std::size_t i = 0; i < d; ++i) {
      total.push_back(at[k].total[i].estimate);
      widest = std::max(widest, at[k].total[i].high - at[k].total[i].low);
    }
    const std::vector<double> rank = descending_ranks(total);
    std::vector<std::size_t> order(d);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
    std::string text;
    for (std::size_t i : order) text += (text.empty() ? "" : " > ") + s.params[i].label;
    rank_row.push_back(text);
    rho_row.push_back(num(spearman(rank, full_rank)));
    width_row.push_back(num(widest));
    an.idx_csv << "sobol_subset," << yname << ",\"ranking\",spearman_N" << sizes[k] << ","
               << fmt::format("{:.17g},{:.17g},{:.17g},", spearman(rank, full_rank), spearman(rank, full_rank), spearman(rank, full_rank)) << "\n";
  }
  rows.push_back(rank_row);
  rows.push_back(rho_row);
  rows.push_back(width_row);
  an.tables.push_back({{"title", fmt::format("Convergence of the Sobol' indices of {} against sample size (Sarrazin et al. 2016): the nested "
                                             "first N/8 … N rows of the same design, {:.0f} % bootstrap intervals; the ranking by S_T at each size",
                                             yname, 100.0 * s.confidence)},
                       {"columns", cols}, {"rows", rows}});
  nlohmann::json curves = nlohmann::json::array();
  for (std::size_t i = 0; i < d; ++i) {
    nlohmann::json x = nlohmann::json::array(), yv = nlohmann::json::array(), lo = nlohmann::json::array(), hi = nlohmann::json::array();
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      x.push_back(static_cast<double>(sizes[k]) * std::pow(1.06, static_cast<double>(i) - 0.5 * static_cast<double>(d - 1)));  // side by side
      yv.push_back(jnum(at[k].total[i].estimate));
      lo.push_back(jnum(at[k].total[i].low));
      hi.push_back(jnum(at[k].total[i].high));
    }
    static constexpr const char* kColours[] = {"#1f77b4", "#2ca02c", "#9467bd", "#d62728", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};
    const char* colour = kColours[i % std::size(kColours)];  // the bars and the line joining them alike
    curves.push_back({{"label", fmt::format("S_T of {}", s.params[i].label)}, {"x", x}, {"y", yv}, {"ylow", lo}, {"yhigh", hi},
                      {"style", "errorbars"}, {"colour", colour}});
    curves.push_back({{"label", ""}, {"x", x}, {"y", yv}, {"style", "lines"}, {"colour", colour}});
  }
  an.figures.push_back({{"id", "sobol_subsets_" + id},
                        {"title", fmt::format("S_T of {} on the first N/8, N/4, N/2, N rows ({:.0f} % bootstrap intervals)", yname, 100.0 * s.confidence)},
                        {"xlabel", "N (rows of A, B and each AB_i)"}, {"ylabel", "total index S_T"}, {"logx", true}, {"logy", false},
                        {"curves", curves}});
}

}  // namespace ver::sens
