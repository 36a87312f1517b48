// Sobol' indices of a sensitivity study: first-order (Saltelli 2010, Janon 2014) and total (Jansen)
// indices with bootstrap intervals from Saltelli's runs, of each output and of each declared transform
// of it — indices.csv rows, a table per transform, a bar figure per output, and for test functions
// the checks against the exact indices (sensitivity_sobol_checks.cpp: interval widths, error rate).
#include <cmath>
#include <optional>
#include <tuple>

#include <fmt/format.h>

#include "engine/sensitivity_study.hpp"

namespace ver::sens {

namespace {

/// The estimators' inputs for output o: its values in the runs of A, B and each AB_i.
DesignOutputs outputs_of_runs(const Plan& plan, std::size_t o, std::size_t n, std::size_t d) {
  DesignOutputs y{std::vector<double>(n), std::vector<double>(n), std::vector<std::vector<double>>(d, std::vector<double>(n)), {}};
  const bool second = plan.runs.size() >= plan.sobol_begin + (2 * d + 2) * n;
  if (second) y.fba.assign(d, std::vector<double>(n));
  for (std::size_t j = 0; j < n; ++j) {
    y.fa[j] = plan.runs[plan.sobol_begin + j].outputs[o];
    y.fb[j] = plan.runs[plan.sobol_begin + n + j].outputs[o];
    for (std::size_t i = 0; i < d; ++i) y.fab[i][j] = plan.runs[plan.sobol_begin + (2 + i) * n + j].outputs[o];
    if (second)
      for (std::size_t i = 0; i < d; ++i) y.fba[i][j] = plan.runs[plan.sobol_begin + (2 + d + i) * n + j].outputs[o];
  }
  return y;
}

/// A failing check when an index of this output could not be computed: a non-finite variance (outputs near
/// ±1.7e308 overflow it) or fewer than two complete rows. Without it such indices read as 0 or "—" and a
/// sweep passed saying that nothing matters.
void check_computable(const SobolIndices& si, const std::string& yname, const std::string& tsuffix, Analysis& an) {
  std::size_t missing = 0;
  for (const auto* v : {&si.first, &si.total, &si.first_janon})
    for (const Interval& x : *v) missing += !std::isfinite(x.estimate);
  if (missing == 0) return;
  const std::string why = si.rows_used < 2 ? fmt::format("{} complete rows (at least 2 needed)", si.rows_used)
                                           : fmt::format("the variance of the output is {} (overflow or not finite)", si.variance);
  an.add_check(fmt::format("Sobol' indices of {} computable{}", yname, tsuffix), 0.0, static_cast<double>(missing),
               static_cast<double>(missing), 0.0, "an index that cannot be computed is no answer", false,
               fmt::format("{} of {} indices not computable: {}", missing, 3 * si.first.size(), why));
}

/// The table's rows and indices.csv's of one output's indices, each checked against its exact value
/// where known (the bootstrap interval must contain it).
void index_rows(const SobolIndices& si, const ExactIndices& exact_sobol, const std::string& yname, const std::string& tsuffix,
                nlohmann::json& rows, Analysis& an) {
  const Sens& s = an.s;
  for (std::size_t i = 0; i < s.params.size(); ++i) {
    rows.push_back({yname, s.params[i].label, num(si.first[i].estimate),
                    fmt::format("[{}, {}]", num(si.first[i].low), num(si.first[i].high)), num(si.total[i].estimate),
                    fmt::format("[{}, {}]", num(si.total[i].low), num(si.total[i].high)),
                    exact_sobol.first.empty() ? "" : num(exact_sobol.first[i]), exact_sobol.total.empty() ? "" : num(exact_sobol.total[i]),
                    num(si.first_janon[i].estimate), fmt::format("[{}, {}]", num(si.first_janon[i].low), num(si.first_janon[i].high))});
    for (const auto& [kind, iv, ex] : {std::tuple{"S", si.first[i], exact_sobol.first}, std::tuple{"ST", si.total[i], exact_sobol.total},
                                       std::tuple{"S_janon", si.first_janon[i], exact_sobol.first}}) {
      an.idx_csv << "sobol," << yname << ",\"" << s.params[i].label << "\"," << kind << ","
                 << fmt::format("{:.17g},{:.17g},{:.17g},", iv.estimate, iv.low, iv.high)
                 << (ex.empty() ? std::string() : fmt::format("{:.17g}", ex[i])) << "\n";
      if (!ex.empty()) {
        const double e = std::abs(iv.estimate - ex[i]);
        const double tol = ex[i] < iv.estimate ? iv.estimate - iv.low : iv.high - iv.estimate;
        an.add_check(fmt::format("{}_{} of {} ({}, N = {}{})", kind, i + 1, s.params[i].label, s.function->name, s.samples, tsuffix), ex[i],
                     iv.estimate, e, tol,
                     fmt::format("the {:.0f} % bootstrap interval ({} resamples of the N rows) must contain the exact value",
                                 100.0 * s.confidence, s.resamples),
                     ex[i] >= iv.low && ex[i] <= iv.high, fmt::format("interval [{}, {}]", num(iv.low), num(iv.high)));
        if (s.index_tolerance && tsuffix.empty())
          an.add_check(fmt::format("{}_{} of {} within ±{} ({}, N = {})", kind, i + 1, s.params[i].label, num(*s.index_tolerance),
                                   s.function->name, s.samples),
                       ex[i], iv.estimate, e, *s.index_tolerance, s.index_tolerance_reason, e <= *s.index_tolerance, "");
      }
    }
  }
}

/// The noise floor, at no cost: Janon's first order of an inert dummy input, whose AB_dummy is A
/// itself (Y = f(B), Y^dummy = f(A): independent points, exact index 0). Saltelli's S and Jansen's S_T
/// of such an input are exactly 0 (f(AB) − f(A) = 0 row by row), so only Janon's carries noise; an
/// index whose interval does not clear the dummy's is not resolved at this N.
void dummy_row(const DesignOutputs& y, const MeanNoise* nz, const std::string& yname, const std::string& tsuffix, nlohmann::json& rows,
               Analysis& an) {
  const Sens& s = an.s;
  std::optional<MeanNoise> dz;
  if (nz) dz = MeanNoise{nz->a, nz->b, {nz->a}};
  const SobolIndices sd = sobol_indices(y.fa, y.fb, {y.fa}, s.resamples, s.confidence, 12345, dz ? &*dz : nullptr);
  const Interval& j = sd.first_janon[0];
  rows.push_back({yname, "dummy (inert: noise floor)", "0", "[0, 0]", "0", "[0, 0]", s.function ? "0" : "", s.function ? "0" : "",
                  num(j.estimate), fmt::format("[{}, {}]", num(j.low), num(j.high))});
  an.idx_csv << "sobol," << yname << ",\"dummy\",S_janon," << fmt::format("{:.17g},{:.17g},{:.17g},0", j.estimate, j.low, j.high) << "\n";
  if (s.function)
    an.add_check(fmt::format("S_janon of the inert dummy ({}, N = {}{})", s.function->name, s.samples, tsuffix), 0.0, j.estimate,
                 std::abs(j.estimate), j.estimate > 0.0 ? j.estimate - j.low : j.high - j.estimate,
                 fmt::format("the {:.0f} % bootstrap interval must contain 0, the exact index of an input without effect", 100.0 * s.confidence),
                 j.low <= 0.0 && j.high >= 0.0, fmt::format("interval [{}, {}]", num(j.low), num(j.high)));
}

nlohmann::json jv(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(jnum(x));
  return a;
}

/// Bars: S and S_T side by side per parameter, each with its bootstrap interval.
nlohmann::json index_figure(const Sens& s, const SobolIndices& si, const ExactIndices& exact_sobol, const std::string& yname,
                            Transform transform, std::size_t o) {
  const std::size_t d = s.params.size();
  nlohmann::json curves = nlohmann::json::array();
  std::vector<double> xi, xt, ys, yt;
  std::vector<double> s_lo, s_hi, t_lo, t_hi;
  nlohmann::json xticks = nlohmann::json::array();
  for (std::size_t i = 0; i < d; ++i) {
    const double x = static_cast<double>(i + 1);
    xi.push_back(x - 0.11);
    xt.push_back(x + 0.11);
    ys.push_back(si.first[i].estimate);
    yt.push_back(si.total[i].estimate);
    s_lo.push_back(si.first[i].low);
    s_hi.push_back(si.first[i].high);
    t_lo.push_back(si.total[i].low);
    t_hi.push_back(si.total[i].high);
    xticks.push_back({static_cast<double>(i + 1), s.params[i].label});
  }
  curves.push_back({{"label", "first order S (Saltelli 2010)"}, {"x", xi}, {"y", jv(ys)}, {"style", "boxes"}, {"width", 0.2}});
  {  // Janon's first order as points with their interval between the bars
    std::vector<double> xj, yj, jlo, jhi;
    for (std::size_t i = 0; i < d; ++i) {
      xj.push_back(static_cast<double>(i + 1));
      yj.push_back(si.first_janon[i].estimate);
      jlo.push_back(si.first_janon[i].low);
      jhi.push_back(si.first_janon[i].high);
    }
    curves.push_back({{"label", fmt::format("first order S (Janon 2014), {:.0f} % bootstrap interval", 100.0 * s.confidence)},
                      {"x", xj}, {"y", jv(yj)}, {"ylow", jv(jlo)}, {"yhigh", jv(jhi)}, {"style", "errorbars"}, {"colour", "#b03000"}});
  }
  curves.push_back({{"label", "total S_T (Jansen)"}, {"x", xt}, {"y", jv(yt)}, {"style", "boxes"}, {"width", 0.2}});
  curves.push_back({{"label", fmt::format("S, {:.0f} % bootstrap interval", 100.0 * s.confidence)}, {"x", xi}, {"y", jv(ys)},
                    {"ylow", jv(s_lo)}, {"yhigh", jv(s_hi)}, {"style", "errorbars"}, {"colour", "#000000"}});
  curves.push_back({{"label", fmt::format("S_T, {:.0f} % bootstrap interval", 100.0 * s.confidence)}, {"x", xt}, {"y", jv(yt)},
                    {"ylow", jv(t_lo)}, {"yhigh", jv(t_hi)}, {"style", "errorbars"}, {"colour", "#555555"}});
  if (!exact_sobol.first.empty()) {
    std::vector<double> xe, ye;
    for (std::size_t i = 0; i < d; ++i) {
      xe.insert(xe.end(), {xi[i], xt[i]});
      ye.insert(ye.end(), {exact_sobol.first[i], exact_sobol.total[i]});
    }
    curves.push_back({{"label", "exact"}, {"x", xe}, {"y", ye}, {"style", "points"}});
  }
  return {{"id", transform == Transform::none ? fmt::format("sobol_{}", o) : fmt::format("sobol_{}_{}", transform_name(transform), o)},
          {"title", fmt::format("Sobol' indices of {} (N = {}, {} rows used)", yname, s.samples, si.rows_used)},
          {"xlabel", "parameter"}, {"ylabel", "index"}, {"logx", false}, {"logy", false}, {"curves", curves},
          {"xticks", xticks}, {"xrange", {0.5, static_cast<double>(d) + 0.5}}};
}

/// The indices of every output under one transform ("none": the output itself): rows, checks,
/// figures, the table and for function studies the error rate.
void analyse_transform(const Plan& plan, const ExactIndices& exact, Transform transform, Analysis& an) {
  const Sens& s = an.s;
  const std::size_t d = s.params.size(), n = s.samples;
  // The exact values of the indices of the (transformed) output, where known.
  ExactIndices exact_sobol = exact;
  if (s.function && transform == Transform::log) exact_sobol = exact_indices_of_log(*s.function);
  if (s.function && transform == Transform::rank) exact_sobol = {};
  // What names a check, figure or table of a transform: "" for the output itself.
  const std::string tsuffix = transform == Transform::none ? "" : ", " + transformed_label(transform, "y");
  nlohmann::json rows = nlohmann::json::array(), rows2 = nlohmann::json::array();
  for (std::size_t o = 0; o < s.outputs.size(); ++o) {
    DesignOutputs y = outputs_of_runs(plan, o, n, d);
    apply_transform(transform, y.fa, y.fb, y.fab, y.fba);
    const std::string yname = transformed_label(transform, s.outputs[o]);
    // Replicates: the indices of the means' expectation E[y | x], the noise left in the means taken out
    // (sensitivity_noise.hpp); of the output itself only (a transform's noise is not the output's).
    const std::optional<MeanNoise> nz = transform == Transform::none ? mean_noise_of_runs(plan, o, n, d) : std::nullopt;
    const SobolIndices si = sobol_indices(y.fa, y.fb, y.fab, s.resamples, s.confidence, 12345, nz ? &*nz : nullptr);
    check_computable(si, yname, tsuffix, an);
    if (s.function && s.resamples >= 100 && !nz) check_interval_widths(si, transform, tsuffix, an);
    index_rows(si, exact_sobol, yname, tsuffix, rows, an);
    dummy_row(y, nz ? &*nz : nullptr, yname, tsuffix, rows, an);
    an.figures.push_back(index_figure(s, si, exact_sobol, yname, transform, o));
    if (s.second_order) second_order_rows(y, exact_sobol, yname, tsuffix, rows2, an);
    if (!s.function)
      sobol_subsets(y, nz, yname, transform == Transform::none ? std::to_string(o) : fmt::format("{}_{}", transform_name(transform), o), an);
  }
  const bool corrected = !s.replicates.empty() && transform == Transform::none;
  an.tables.push_back({{"title", fmt::format("Sobol' indices (Saltelli sampling, N = {}, {} runs; {} % bootstrap intervals){}{}", n, n * (d + 2),
                                             100.0 * s.confidence,
                                             corrected ? fmt::format(" of the mean of {} replicates, the noise left in the means taken out "
                                                                     "(indices of E[y | x]; the noise fraction: table \"Run-to-run noise\")",
                                                                     s.replicates.size())
                                                       : std::string(),
                                             transform == Transform::none ? "" : fmt::format(
                                                 ": indices of the TRANSFORMED output {} (declared transforms = [\"{}\"]), not of the output itself",
                                                 transformed_label(transform, "y"), transform_name(transform)))},
                       {"columns", {"output", "parameter", "S", "interval", "S_T", "interval", "exact S", "exact S_T", "S (Janon)", "interval"}},
                       {"rows", rows}});
  if (s.second_order)
    an.tables.push_back({{"title", fmt::format("Second-order Sobol' indices S_ij (Saltelli 2002: A, B, AB_i and BA_i, N = {}, {} runs; {} % bootstrap intervals){}",
                                               n, n * (2 * d + 2), 100.0 * s.confidence, tsuffix)},
                         {"columns", {"output", "parameters", "S_ij", "interval", "exact S_ij"}}, {"rows", rows2}});
  if (s.function && !s.convergence.empty() && !exact_sobol.first.empty()) sobol_convergence(exact_sobol, transform, tsuffix, an);
}

}  // namespace

void analyse_sobol(const Plan& plan, const ExactIndices& exact, Analysis& an) {
  std::vector<Transform> sobol_transforms = {Transform::none};
  sobol_transforms.insert(sobol_transforms.end(), an.s.transforms.begin(), an.s.transforms.end());
  for (const Transform transform : sobol_transforms) analyse_transform(plan, exact, transform, an);
}

}  // namespace ver::sens
