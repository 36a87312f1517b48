#include "engine/study_run.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "engine/progress.hpp"
#include "engine/run_cache.hpp"
#include "engine/run_dispatch.hpp"
#include "ref/registry.hpp"

namespace fs = std::filesystem;

namespace ver {

std::vector<RunOut> StudyRun::run_many(const std::vector<Planned>& plan, int jobs) {
  std::vector<RunOut> outs(plan.size());
  std::vector<RunRequest> reqs;
  std::vector<std::size_t> slot;
  std::vector<fs::path> entries;
  std::vector<std::string> case_paths;
  const fs::path case_file = fs::absolute(s.case_file);
  for (std::size_t k = 0; k < plan.size(); ++k) {
    const dem::Case c = dem::read_case(s.case_file, plan[k].sets);
    fs::path entry;
    if (!cache_dir.empty()) {
      entry = cache_entry(cache_dir, c.resolved, plan[k].sets, plan[k].out);
      const fs::path& run_out = plan[k].out;
      const bool wall_contacts = std::any_of(plan[k].sets.begin(), plan[k].sets.end(),
                                             [](const std::string& x) { return x.rfind("output.wall_contacts=", 0) == 0; });
      const bool files_ok = run_out.empty() || (fs::exists(run_out / "series.csv") && fs::exists(run_out / "summary.json") &&
                                                (!wall_contacts || fs::exists(run_out / "wall_contacts.csv")));
      if (files_ok)
        if (const auto cached = read_cached(entry)) {
          ++reused;
          note_reused(*cached, run_cost(c));
          outs[k] = {cached->probes, cached->status, cached->message, cached->eps, cached->seconds_per_step};
          continue;
        }
    }
    reqs.push_back({case_file, plan[k].sets, plan[k].out, run_cost(c)});
    slot.push_back(k);
    entries.push_back(entry);
    case_paths.push_back(c.path.string());
  }
  if (Progress* p = current_progress(); p && reqs.size() < plan.size()) p->reused(plan.size() - reqs.size());
  run_all(reqs, jobs, [&](std::size_t i, RunReply& r) {
    const std::size_t k = slot[i];
    const bool finished = r.status != "interrupted" && r.status != "case-error" && r.status != "error";
    if (finished && !entries[i].empty()) {  // at once: a killed study keeps every finished run
      CachedRun entry{r.status, r.message, r.eps, r.probes};
      entry.seconds_per_step = r.seconds_per_step;
      write_cached(entries[i], entry, case_paths[i], plan[k].sets);
      ++ran;
    }
    outs[k] = {std::move(r.probes), r.status, r.message, r.eps, r.seconds_per_step};
  });
  for (const RunOut& r : outs) {  // the first failure in plan order, whatever finished first
    if (r.status == "interrupted") throw StudyInterrupted(fmt::format("study {}: {}", s.name, r.message));
    if (r.status == "case-error") throw dem::CaseError(r.message);
    if (r.status == "error") throw std::runtime_error(r.message);
  }
  return outs;
}

void StudyRun::note_reused(const CachedRun& cached, double cost) {
  std::lock_guard<std::mutex> lock(reused_mutex);
  if (cached.eps > 0.0) reused_seconds += cost / cached.eps;
  if (cached.date >= reused_date) {
    reused_date = cached.date;
    reused_code_version = cached.code_version;
  }
}

RunOut StudyRun::run_one(const std::vector<std::string>& sets, const fs::path& run_out) {
  return run_many({Planned{sets, run_out}}, 1).front();
}

std::optional<double> StudyRun::reference_of(const Check& c, const Variant& v, double param,
                                             const RefinementLevel* level) const {
  if (c.value) return c.value;
  if (!c.against_variant.empty()) {  // kind = single: the other variant's value of the same probe
    for (std::size_t vi = 0; vi < s.variants.size() && vi < finest_runs.size(); ++vi)
      if (s.variants[vi].label == c.against_variant) return probe_of(finest_runs[vi], c.probe);
    return std::nullopt;
  }
  if (c.solver.empty()) return std::nullopt;
  std::map<std::string, double> args = v.args;
  if (level)
    for (const auto& [k, x] : level->args) args[k] = x;
  for (const auto& [k, x] : c.args) args[k] = x;
  // Only the arguments the solver takes: variant args may serve several solvers.
  std::map<std::string, double> use;
  for (const auto& info : ref::solvers())
    if (info.name == c.solver)
      for (const auto& a : info.arguments) {
        if (a.name == "param") use[a.name] = param;
        else if (args.count(a.name)) use[a.name] = args[a.name];
      }
  return c.offset + c.scale * ref::evaluate(c.solver, use);
}

void StudyRun::add_check(const std::string& quantity, std::optional<double> reference, std::optional<double> dem,
                         const Check& c, std::optional<double> order, const std::string& note) {
  std::optional<double> err;
  bool ok = dem.has_value();
  if (dem && reference) {
    const double e = std::abs(*dem - *reference);
    err = c.relative ? e / std::abs(*reference) : e;
    // above / below: beyond the reference by the margin (relative: a fraction of |reference|)
    const double margin = c.relative ? c.tolerance * std::abs(*reference) : c.tolerance;
    if (c.expect == Expect::within) ok = *err <= c.tolerance;
    else if (c.expect == Expect::above) ok = *dem > *reference + margin;
    else ok = *dem < *reference - margin;
  }
  bool order_ok = true;
  if (c.expected_order) order_ok = order && std::abs(*order - *c.expected_order) <= c.order_band;
  ok = ok && order_ok;
  passed = passed && ok;
  auto j = [](std::optional<double> x) { return x ? nlohmann::json(*x) : nlohmann::json(nullptr); };
  checks.push_back({{"quantity", quantity}, {"reference", j(reference)}, {"dem", j(dem)}, {"error", j(err)},
                    {"error_kind", c.relative ? "rel" : "abs"}, {"tolerance", c.tolerance},
                    {"tolerance_reason", c.reason}, {"observed_order", j(order)},
                    {"expected_order", j(c.expected_order)},
                    {"order_band", c.expected_order ? nlohmann::json(c.order_band) : nlohmann::json(nullptr)},
                    {"expect", c.expect == Expect::within ? "within" : c.expect == Expect::above ? "above" : "below"},
                    {"passed", ok}, {"note", note}});
}

void StudyRun::add_ensemble_check(const std::string& quantity, std::optional<double> reference, const EnsembleStat& st,
                                  const Check& c, const std::string& note) {
  add_check(quantity, reference, st.mean, c, std::nullopt, note);  // the row, judged on the mean
  nlohmann::json& row = checks.back();
  const std::optional<double> lo = st.low(), hi = st.high();
  bool ok = lo && hi && reference && interval_passes(c, *reference, *lo, *hi);  // fewer than two values: no verdict
  if (!row["passed"].get<bool>() && ok) ok = false;  // the mean alone already fails
  row["passed"] = ok;
  row["ci_low"] = lo ? nlohmann::json(*lo) : nlohmann::json(nullptr);
  row["ci_high"] = hi ? nlohmann::json(*hi) : nlohmann::json(nullptr);
  row["members"] = st.n;
  // add_check folded the mean's verdict into `passed`; fold the interval's as well
  if (!ok) passed = false;
}

bool interval_passes(const Check& c, double reference, double lo, double hi) {
  const double margin = c.relative ? c.tolerance * std::abs(reference) : c.tolerance;
  if (c.expect == Expect::within) return lo >= reference - margin && hi <= reference + margin;
  if (c.expect == Expect::above) return lo > reference + margin;
  return hi < reference - margin;
}

std::string check_label(const Check& c, const Variant& v) {
  return v.label.empty() ? c.label : fmt::format("{}, {}", c.label, v.label);
}

std::string fmt_value(std::optional<double> v) { return v ? fmt::format("{:.6g}", *v) : std::string("—"); }

std::optional<double> probe_of(const RunOut& r, const std::string& probe) {
  if (probe == "element_steps_per_second") return r.eps > 0.0 ? std::optional<double>(r.eps) : std::nullopt;
  if (probe == "seconds_per_step") return r.seconds_per_step > 0.0 ? std::optional<double>(r.seconds_per_step) : std::nullopt;
  return r.probes.count(probe) ? r.probes.at(probe) : std::nullopt;
}

double evaluate_solver(const std::string& solver, const std::map<std::string, double>& args) {
  std::map<std::string, double> use;
  for (const auto& info : ref::solvers())
    if (info.name == solver)
      for (const auto& a : info.arguments)
        if (args.count(a.name)) use[a.name] = args.at(a.name);
  return ref::evaluate(solver, use);
}

void fail(const Study& s, const std::string& key, const std::string& what) {
  throw std::runtime_error(fmt::format("{}: {}: {}", s.file.string(), key, what));
}

}  // namespace ver
