// The runs of a sensitivity study: test functions evaluated here, DEM runs from the run cache or
// through run_all (engine/run_dispatch.hpp), Δt tied to the time-step guard, replicates' means, and
// the table of every run (runs.csv).
#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/run/output_files.hpp"
#include "engine/progress.hpp"
#include "engine/run_cache.hpp"
#include "engine/run_dispatch.hpp"
#include "engine/sensitivity_noise.hpp"
#include "engine/sensitivity_study.hpp"
#include "engine/study.hpp"

namespace fs = std::filesystem;

namespace ver::sens {

double guard_limit(const fs::path& case_file, std::vector<std::string> sets) {
  sets.push_back("numerics.allow_unstable=true");
  return dem::check_case(dem::read_case(case_file, sets));
}

double dt_fraction_of(const Sens& s) {
  double dt_fraction = 0.0;
  if (s.dt_fraction) dt_fraction = *s.dt_fraction;
  if (s.dt_fraction_base) {
    const dem::Case base = dem::read_case(s.case_file, s.set);
    dt_fraction = base.model.numerics.dt / guard_limit(s.case_file, s.set);
  }
  return dt_fraction;
}

void Runner::run_function(Run& r) const {
  std::vector<double> x;
  for (std::size_t i = 0; i < s.params.size(); ++i)  // the base point of a function: mid-range
    x.push_back(value_at(s.params[i], std::isfinite(r.u[i]) ? r.u[i] : 0.5));
  r.outputs = {evaluate(*s.function, x)};
  r.status = std::isfinite(r.outputs[0]) ? "completed" : "non-finite";
}

void Runner::set_outputs(Run& r, const std::map<std::string, std::optional<double>>& probes) const {
  for (const auto& o : s.outputs) {
    if (r.status != "refused" && r.status != "blow-up" && !probes.count(o))
      throw std::runtime_error(fmt::format("{}: sensitivity.outputs: the case has no probe \"{}\"", s.file.string(), o));
    const auto it = probes.find(o);
    r.outputs.push_back(it != probes.end() && it->second && r.status != "blow-up" ? *it->second : std::nan(""));
    // A run that ended without a value of an output (a probe time after the end of the run, a crossing
    // that never came) is a failed run, counted by max_failed_runs, not a good run with a hole.
    if (run_ok(r) && !std::isfinite(r.outputs.back())) {
      r.status = "no-output";
      r.message = fmt::format("output \"{}\": the run gave no value (null probe: a time after the end of the run, "
                              "or an event that did not happen)", o);
    }
  }
}

/// Every run: a test function here; DEM runs from the cache, the others through run_all (threads
/// here or the ranks of an MPI job, run_dispatch.hpp), each cached as it finishes. Results go to
/// the run's own slot, whatever order the runs finish in.
void Runner::run_all_runs(std::vector<Run>& runs, int jobs) {
  if (s.function) {
    for (std::size_t k = 0; k < runs.size(); ++k) {
      run_function(runs[k]);
      if (s.noise_sd > 0.0) runs[k].outputs[0] += s.noise_sd * standard_normal_draw(s.noise_seed, k);
    }
    return;
  }
  std::vector<std::map<std::string, std::optional<double>>> probes(runs.size());
  std::vector<RunRequest> reqs;
  std::vector<std::size_t> slot;
  std::vector<fs::path> entries;
  std::vector<std::string> case_paths;
  const fs::path case_file = fs::absolute(s.case_file);
  // Δt tied to the guard: each run's limit first (in parallel; a refusal is the run's result).
  std::vector<char> settled(runs.size(), 0);
  // A design may hold the same point more than once (Saltelli's row 0 is the origin in A, B and
  // every AB_i; integer parameters repeat values): the same overrides are the same cache entry, so
  // each is run once and its reply goes to every run that shares the entry.
  std::map<fs::path, std::size_t> request_of;        // cache entry → index into reqs
  std::vector<std::vector<std::size_t>> shared_by;   // per request: the further runs that use its reply
  if (dt_fraction > 0.0)
    parallel_for(runs.size(), jobs, [&](std::size_t k) {
      Run& r = runs[k];
      try {
        r.dt = dt_fraction * guard_limit(s.case_file, r.sets);
        r.sets.push_back(fmt::format("numerics.dt={:.17g}", r.dt));
      } catch (const dem::CaseError& e) {
        r.status = "refused";
        r.message = e.what();
        r.outputs.assign(s.outputs.size(), std::nan(""));
        settled[k] = 1;
      }
    });
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (settled[k]) continue;
    Run& r = runs[k];
    const dem::Case c = dem::read_case(s.case_file, r.sets);  // a bad path or value: the study fails
    const fs::path entry = cache_entry(cache_dir, c.resolved, r.sets);
    if (const auto cached = read_cached(entry)) {
      r.status = cached->status;
      r.message = cached->message;
      probes[k] = cached->probes;
      ++reused;
      if (Progress* p = current_progress()) p->reused(1);
      continue;
    }
    if (const auto it = request_of.find(entry); it != request_of.end()) {
      shared_by[it->second].push_back(k);
      ++duplicates;
      continue;
    }
    request_of.emplace(entry, reqs.size());
    shared_by.emplace_back();
    reqs.push_back({case_file, r.sets, {}, run_cost(c)});
    slot.push_back(k);
    entries.push_back(entry);
    case_paths.push_back(c.path.string());
  }
  run_all(reqs, jobs, [&](std::size_t i, RunReply& rep) {
    Run& r = runs[slot[i]];
    r.status = rep.status;
    r.message = rep.message;
    if (rep.status == "interrupted" || rep.status == "error") return;
    if (rep.status == "case-error") {  // the time-step guard (or another check before the run) refused it
      r.status = "refused";
      rep.probes.clear();
    }
    probes[slot[i]] = rep.probes;
    write_cached(entries[i], {r.status, r.message, 0.0, rep.probes}, case_paths[i], r.sets);  // at once
    ++ran;
  });
  for (std::size_t i = 0; i < reqs.size(); ++i)
    for (std::size_t k : shared_by[i]) {
      runs[k].status = runs[slot[i]].status;
      runs[k].message = runs[slot[i]].message;
      probes[k] = probes[slot[i]];
    }
  for (std::size_t k = 0; k < runs.size(); ++k) {  // the first failure in run order
    if (runs[k].status == "interrupted") throw StudyInterrupted(fmt::format("sensitivity {}: {}", s.name, runs[k].message));
    if (runs[k].status == "error") throw std::runtime_error(runs[k].message);
  }
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (!settled[k]) set_outputs(runs[k], probes[k]);
}

bool run_ok(const Run& r) {  // missing, failed: no output in the outputs file of `dem2d analyse`
  return r.status != "refused" && r.status != "blow-up" && r.status != "non-finite" && r.status != "missing" && r.status != "failed" &&
         r.status != "no-output";
}

namespace {

/// One sample from its replicates: the mean of every output (missing if any replicate's is), the status
/// and message of the first replicate that failed (else the first's), the mean Δt.
Run replicate_mean(const Run* reps, std::size_t count) {
  Run r = reps[0];
  for (std::size_t j = 1; j < count; ++j) {
    const Run& x = reps[j];
    if (run_ok(r) && !run_ok(x)) {
      r.status = x.status;
      r.message = fmt::format("replicate {}: {}", j + 1, x.message);
    }
    for (std::size_t o = 0; o < r.outputs.size(); ++o) r.outputs[o] += x.outputs[o];  // NaN stays NaN
    r.dt += x.dt;
  }
  for (double& y : r.outputs) y /= static_cast<double>(count);
  r.dt /= static_cast<double>(count);
  r.replicates = count;
  r.noise_var.assign(r.outputs.size(), 0.0);  // unbiased: Σ (y_j − ȳ)² / (R − 1)
  for (std::size_t o = 0; o < r.outputs.size(); ++o) {
    for (std::size_t j = 0; j < count; ++j) r.noise_var[o] += (reps[j].outputs[o] - r.outputs[o]) * (reps[j].outputs[o] - r.outputs[o]);
    r.noise_var[o] /= static_cast<double>(count - 1);
  }
  return r;
}

}  // namespace

void Runner::run_samples(std::vector<Run>& runs, int jobs) {
  if (s.replicates.empty()) {
    run_all_runs(runs, jobs);
  } else {  // every sample once per replicate, then the mean per sample
    const std::size_t nr = s.replicates.size();
    std::vector<Run> reps;
    reps.reserve(runs.size() * nr);
    for (const Run& r : runs)
      for (const auto& extra : s.replicates) {
        Run x = r;
        x.sets.insert(x.sets.end(), extra.begin(), extra.end());
        reps.push_back(std::move(x));
      }
    run_all_runs(reps, jobs);
    for (std::size_t k = 0; k < runs.size(); ++k) runs[k] = replicate_mean(&reps[k * nr], nr);
  }
}

// The table of every run: inputs (values; blank = the base case's), outputs, status.
RunTable write_runs_csv(const Sens& s, const std::vector<Run>& runs, bool derived_dt, const fs::path& file) {
  std::ostringstream csv;
  csv << "run,method";
  for (const auto& p : s.params) csv << "," << p.name << " [" << p.unit << "]";  // ASCII name and SI unit (sensitivity_names.hpp)
  if (derived_dt) csv << ",dt";
  for (const auto& o : s.outputs) csv << "," << o;
  csv << ",status,message\n";
  RunTable table;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Run& r = runs[k];
    const bool ok = run_ok(r);
    table.failed += !ok;
    csv << k << "," << r.method;
    nlohmann::json row = {std::to_string(k), r.method};
    for (std::size_t i = 0; i < s.params.size(); ++i) {
      const std::string v = std::isfinite(r.u[i]) ? fmt::format("{:.6g}", value_at(s.params[i], r.u[i])) : std::string("base");
      csv << "," << (std::isfinite(r.u[i]) ? fmt::format("{:.17g}", value_at(s.params[i], r.u[i])) : std::string());
      row.push_back(v);
    }
    if (derived_dt) {
      csv << "," << (std::isfinite(r.dt) ? fmt::format("{:.17g}", r.dt) : std::string());
      row.push_back(num(r.dt));
    }
    for (double y : r.outputs) {
      csv << "," << (std::isfinite(y) ? fmt::format("{:.17g}", y) : std::string());
      row.push_back(num(y));
    }
    std::string msg = r.message;
    std::replace(msg.begin(), msg.end(), '"', '\'');
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    csv << "," << r.status << ",\"" << msg << "\"\n";
    row.push_back(r.status);
    table.rows.push_back(row);
  }
  dem::write_file_atomic(file, csv.str(), false);
  return table;
}

void report_runs(const RunTable& table, bool derived_dt, Analysis& an) {
  const Sens& s = an.s;
  const int failed = table.failed;
  if (failed > s.max_failed) an.passed = false;
  an.checks.push_back({{"quantity", "failed runs (blow-up, refused by the guard, no output)"}, {"reference", 0}, {"dem", failed},
                       {"error", failed}, {"error_kind", "abs"}, {"tolerance", s.max_failed},
                       {"tolerance_reason", "the ranges are meant to stay inside the stable, accepted region (max_failed_runs)"},
                       {"observed_order", nullptr}, {"expected_order", nullptr}, {"order_band", nullptr},
                       {"passed", failed <= s.max_failed}, {"note", ""}});
  if (table.rows.size() <= 300) {
    nlohmann::json cols = {"run", "method"};
    for (const auto& p : s.params) cols.push_back(p.label);
    if (derived_dt) cols.push_back("Δt (guard × fraction)");
    for (const auto& o : s.outputs) cols.push_back(o);
    cols.push_back("status");
    an.tables.push_back({{"title", "All runs (runs.csv)"}, {"columns", cols}, {"rows", table.rows}});
  } else {
    an.tables.push_back({{"title", "All runs"}, {"preformatted", fmt::format("{} runs, {} failed: see runs.csv", table.rows.size(), failed)}});
  }
}

}  // namespace ver::sens
