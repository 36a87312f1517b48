#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "dem/run/output_files.hpp"
#include "engine/convergence.hpp"
#include "engine/study_run.hpp"

// kind = "single" and kind = "refinement": every variant at every level (one level for single), each
// check against its reference at the finest level, by Richardson, at every level, or as a trend.

namespace fs = std::filesystem;

namespace ver {

namespace {

/// [[level]] form: a check compared at the finest level (or by Richardson) needs ONE reference for
/// the whole sequence; a reference that moves with the level's arguments is refused before anything
/// runs (compare = "each" checks every level against its own).
void refuse_moving_reference(const StudyRun& run) {
  const Study& s = run.s;
  const std::vector<RefinementLevel>& levels = s.refinement.levels;
  if (s.kind != Kind::refinement || !s.refinement.declared_levels) return;
  for (const Check& c : s.checks) {
    if (c.compare_each || c.solver.empty()) continue;
    for (const Variant& v : s.variants) {
      if (!applies(c, v)) continue;
      const std::optional<double> finest = run.reference_of(c, v, levels.back().value, &levels.back());
      for (const RefinementLevel& l : levels) {
        const std::optional<double> r = run.reference_of(c, v, l.value, &l);
        if (r && finest && std::abs(*r - *finest) > 1e-12 * std::max(1.0, std::abs(*finest)))
          throw std::runtime_error(fmt::format("{}:{}: check.compare: {}", s.file.string(), c.line,
               fmt::format("check \"{}\": the reference {} is {:.10g} at level \"{}\" but {:.10g} at the finest level: "
                           "a convergence series needs one reference (compare = \"each\" checks every level "
                           "against its own)", c.label, c.solver, *r, l.label, *finest)));
      }
    }
  }
}

/// Every variant × level: the study's overrides, the variant's, the level's; the finest level of a
/// variant that a figure draws writes its series (only the quantities drawn).
std::vector<Planned> plan_levels(const StudyRun& run, std::size_t nl) {
  const Study& s = run.s;
  const std::vector<RefinementLevel>& levels = s.refinement.levels;
  std::vector<Planned> plan(s.variants.size() * nl);
  for (std::size_t k = 0; k < plan.size(); ++k) {
    const Variant& v = s.variants[k / nl];
    std::vector<std::string> sets = s.set;
    sets.insert(sets.end(), v.set.begin(), v.set.end());
    if (s.kind == Kind::refinement) sets.insert(sets.end(), levels[k % nl].set.begin(), levels[k % nl].set.end());
    fs::path run_dir;
    if (k % nl == nl - 1) {  // the finest level feeds the figures
      std::vector<std::string> q, walls;
      std::int64_t every = 0;
      for (const Figure& f : s.figures)
        if (f.probe.empty() && (f.variants.empty() || std::find(f.variants.begin(), f.variants.end(), v.label) != f.variants.end())) {
          if (!f.walls.empty()) {  // a wall-contact profile: wall_contacts.csv at the end (and the time, every f.every)
            for (const auto& w : f.walls)
              if (std::find(walls.begin(), walls.end(), w) == walls.end()) walls.push_back(w);
            q.push_back("t");
          } else {
            q.push_back(f.x);
            q.push_back(f.y);
          }
          every = every ? std::min(every, f.every) : f.every;
        }
      if (!walls.empty()) {
        std::string list;
        for (const auto& name : walls) list += (list.empty() ? "" : ", ") + fmt::format("\"{}\"", name);
        sets.push_back(fmt::format("output.wall_contacts=[{}]", list));
      }
      if (!q.empty()) {
        run_dir = run.out / "runs" / fmt::format("variant{}", k / nl);
        std::string list;
        for (const auto& name : q) list += (list.empty() ? "" : ", ") + fmt::format("\"{}\"", name);
        sets.push_back(fmt::format("output.series=[{}]", list));
        sets.push_back(fmt::format("output.every={}", every));
        sets.push_back("output.vtk=false");
      }
    }
    plan[k] = {sets, run_dir};
  }
  return plan;
}

/// levels.csv: every run's status and checked probes.
void write_levels_csv(const StudyRun& run, const std::vector<RunOut>& runs, std::size_t nl) {
  const Study& s = run.s;
  const std::vector<RefinementLevel>& levels = s.refinement.levels;
  std::ostringstream csv;
  csv << "variant,level,parameter,status";
  for (const auto& c : s.checks) csv << "," << c.probe;
  csv << "\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    csv << '"' << s.variants[k / nl].label << "\"," << k % nl << ","
        << (s.kind == Kind::refinement ? fmt::format("{:.17g}", levels[k % nl].value) : "") << "," << runs[k].status;
    for (const auto& c : s.checks) csv << "," << fmt_value(runs[k].probes.count(c.probe) ? runs[k].probes.at(c.probe) : std::nullopt);
    csv << "\n";
  }
  dem::write_file_atomic(run.out / "levels.csv", csv.str(), false);
}

/// The variants of a trend check in the order its `variants` list names them (default: file order).
std::vector<std::size_t> trend_order(const Study& s, const Check& c) {
  std::vector<std::size_t> order;
  if (c.only.empty()) {
    for (std::size_t vi = 0; vi < s.variants.size(); ++vi) order.push_back(vi);
    return order;
  }
  for (const std::string& label : c.only)
    for (std::size_t vi = 0; vi < s.variants.size(); ++vi)
      if (s.variants[vi].label == label) order.push_back(vi);
  return order;
}

/// A trend across the variants, in the order the check lists them: every step moves the asserted way by more than the
/// tolerance. The error column holds the smallest step (negative: a wrong step).
void trend_check(StudyRun& run, const Check& c) {
  const Study& s = run.s;
  const std::vector<RefinementLevel>& levels = s.refinement.levels;
  std::vector<std::string> shown;
  std::optional<double> smallest, last, last_ref;
  bool complete = true;
  std::optional<double> prev_value, prev_dist;
  for (const std::size_t vi : trend_order(s, c)) {
    const Variant& v = s.variants[vi];
    if (!run.finest_runs[vi].probes.count(c.probe)) fail(s, "check.probe", fmt::format("the case has no probe \"{}\"", c.probe));
    const std::optional<double> x = run.finest_runs[vi].probes.at(c.probe);
    shown.push_back(s.ensemble ? fmt::format("{}: {}", v.label, stat_words(run.ensemble_stats[vi].at(c.probe), s.ensemble->confidence))
                               : fmt::format("{}: {}", v.label, fmt_value(x)));
    if (!x) {
      complete = false;
      continue;
    }
    std::optional<double> dist;
    if (c.trend == Trend::toward_reference) {
      last_ref = s.kind == Kind::refinement ? run.reference_of(c, v, levels.back().value, &levels.back()) : run.reference_of(c, v, 0.0);
      if (!last_ref) fail(s, "check.reference", fmt::format("check \"{}\": toward_reference needs a reference", c.label));
      dist = std::abs(*x - *last_ref);
      if (c.relative) *dist /= std::abs(*last_ref);
    }
    if (prev_value) {
      const double step = c.trend == Trend::decreasing ? *prev_value - *x
                          : c.trend == Trend::increasing ? *x - *prev_value
                                                         : *prev_dist - *dist;
      smallest = smallest ? std::min(*smallest, step) : step;
    }
    prev_value = x;
    prev_dist = dist;
    last = x;
  }
  std::string values;
  for (const auto& t : shown) values += (values.empty() ? "" : " → ") + t;
  const bool ok = complete && smallest && *smallest > c.tolerance;
  run.passed = run.passed && ok;
  auto j = [](std::optional<double> x) { return x ? nlohmann::json(*x) : nlohmann::json(nullptr); };
  const char* word = c.trend == Trend::decreasing ? "decreasing" : c.trend == Trend::increasing ? "increasing" : "toward_reference";
  run.checks.push_back({{"quantity", c.label}, {"reference", j(last_ref)}, {"dem", j(last)}, {"error", j(smallest)},
                        {"error_kind", c.relative ? "rel" : "abs"}, {"tolerance", c.tolerance},
                        {"tolerance_reason", c.reason}, {"observed_order", nullptr}, {"expected_order", nullptr},
                        {"order_band", nullptr}, {"expect", word}, {"passed", ok},
                        {"note", (complete ? "" : "a variant gave no value; ") + std::string("values: ") + values}});
}

/// A check of every variant it applies to: single, finest level, Richardson, or every level.
void level_checks(StudyRun& run, const Check& c, const std::vector<RunOut>& runs, std::size_t nl) {
  const Study& s = run.s;
  const std::vector<RefinementLevel>& levels = s.refinement.levels;
  for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
    const Variant& v = s.variants[vi];
    if (!applies(c, v)) continue;
    const RunOut& finest = runs[vi * nl + nl - 1];
    if (!finest.probes.count(c.probe))
      fail(s, "check.probe", fmt::format("the case has no probe \"{}\"", c.probe));
    const std::optional<double> ref =
        s.kind == Kind::refinement ? run.reference_of(c, v, levels.back().value, &levels.back()) : run.reference_of(c, v, 0.0);
    std::string note = finest.status == "blow-up" ? "blow-up: " + finest.message : "";
    if (s.kind == Kind::single && s.ensemble) {  // the mean of the members, judged on its interval
      const EnsembleStat& st = run.ensemble_stats[vi].at(c.probe);
      run.add_ensemble_check(check_label(c, v), ref, st, c, (note.empty() ? "" : note + "; ") + "ensemble: " + stat_words(st, s.ensemble->confidence));
      continue;
    }
    if (s.kind == Kind::single) {
      run.add_check(check_label(c, v), ref, finest.probes.at(c.probe), c, std::nullopt, note);
      continue;
    }
    if (c.compare_each) {  // every level against its own reference (the level's arguments)
      for (std::size_t l = 0; l < nl; ++l) {
        const RunOut& at = runs[vi * nl + l];
        const std::string where = levels[l].label.empty() ? fmt::format("level {}", l) : levels[l].label;
        run.add_check(fmt::format("{} [{}]", check_label(c, v), where), run.reference_of(c, v, levels[l].value, &levels[l]),
                      at.probes.at(c.probe), c, std::nullopt, at.status == "blow-up" ? "blow-up: " + at.message : "");
      }
      continue;
    }
    std::vector<std::optional<double>> q;
    for (std::size_t l = 0; l < nl; ++l) q.push_back(runs[vi * nl + l].probes.at(c.probe));
    const std::size_t given = static_cast<std::size_t>(std::count_if(q.begin(), q.end(), [](const auto& x) { return x.has_value(); }));
    std::optional<double> order;
    if (given >= 2) {
      ConvergenceOptions co;
      if (!c.compare_richardson) co.reference = ref;
      co.expected_order = c.expected_order;
      co.assumed_order = c.assumed_order;
      co.fit_levels = c.fit_levels;
      std::vector<std::string> level_labels;
      Series ser = analyse_levels(s.refinement, q, co, check_label(c, v), &level_labels);
      order = c.compare_richardson && given >= 3 ? ser.three_level_order : ser.fitted_order;
      nlohmann::json sj = to_json(ser);
      if (s.refinement.declared_levels) sj["level_labels"] = level_labels;  // the report names the levels
      run.series.push_back(sj);
      if (c.compare_richardson) {
        note += fmt::format(" Richardson extrapolation compared (GCI of the finest level {})", fmt_value(ser.gci_fine));
        if (c.assumed_order) note += fmt::format(" with the assumed order {:g}", *c.assumed_order);
        run.add_check(check_label(c, v) + " (Richardson)", ref, ser.richardson, c, order, note);
        continue;
      }
      if (given < nl) note += fmt::format(" {} of {} levels gave no value", nl - given, nl);
    } else {
      note += " fewer than two levels gave a value";
    }
    run.add_check(check_label(c, v), ref, finest.probes.at(c.probe), c, order, note);
  }
}

}  // namespace

void run_levels(StudyRun& run) {
  const Study& s = run.s;
  refuse_moving_reference(run);
  const std::size_t nl = s.kind == Kind::single ? 1 : s.refinement.levels.size();
  std::vector<RunOut> runs = s.ensemble ? run.run_many(member_plan(run, plan_levels(run, nl)), run.opt.jobs)
                                        : run.run_many(plan_levels(run, nl), run.opt.jobs);
  for (const auto& r : runs) {
    run.speed_sum += r.eps;
    ++run.speed_n;
  }
  if (s.ensemble) runs = fold_members(run, runs);  // one run per variant: the members' means
  write_levels_csv(run, runs, nl);
  for (std::size_t vi = 0; vi < s.variants.size(); ++vi) run.finest_runs.push_back(runs[vi * nl + nl - 1]);
  for (const Check& c : s.checks) {
    if (c.trend != Trend::none) trend_check(run, c);
    else level_checks(run, c, runs, nl);
  }
}

}  // namespace ver
