#include "engine/study.hpp"

#include <chrono>
#include <cstdio>

#include <unistd.h>

#include <fmt/format.h>

#include "dem/cases/text.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"
#include "dem/run/owned_files.hpp"
#include "engine/progress.hpp"
#include "engine/run_cache.hpp"
#include "engine/study_file.hpp"
#include "engine/study_run.hpp"

namespace fs = std::filesystem;

namespace ver {

namespace {

/// What result.json's "setup" shows: the study file's, the kind's own (mode map counts), the number
/// of variants, the levels, the mean speed.
nlohmann::json setup_of(const StudyRun& run) {
  const Study& s = run.s;
  const std::vector<RefinementLevel>& levels = s.refinement.levels;
  nlohmann::json setup = s.setup;
  for (const auto& [k, v] : run.setup_extra.items()) setup[k] = v;
  setup["variants"] = s.variants.size();
  if (s.kind == Kind::refinement) {
    if (!s.refinement.declared_levels) {
      std::vector<double> values;
      for (const RefinementLevel& l : levels) values.push_back(l.value);
      setup["levels"] = values;
    } else {
      std::vector<std::string> words;  // "1x3 (h = 0.0125)"
      for (const RefinementLevel& l : levels) words.push_back(fmt::format("{} ({} = {:g})", l.label, s.refinement.inverse ? "n" : "h", l.value));
      setup["levels"] = words;
    }
  }
  if (run.speed_n) setup["mean element-steps per second"] = run.speed_sum / static_cast<double>(run.speed_n);
  return setup;
}

/// The table printed at the end of `dem2d study`.
void print_checks(const Study& s, const nlohmann::json& checks, bool passed, const fs::path& out) {
  fmt::print("study {}: {}\n", s.name, s.title);
  fmt::print("  {:<40} {:>13} {:>13} {:>10} {:>9} {:>15} {}\n", "quantity", "reference", "DEM", "error", "tol", "order (exp)", "");
  for (const auto& c : checks) {
    auto num = [](const nlohmann::json& x) { return x.is_null() ? std::string("—") : fmt::format("{:.6g}", x.get<double>()); };
    const std::string order = c["observed_order"].is_null() && c["expected_order"].is_null()
                                  ? ""
                                  : fmt::format("{} ({}±{})", num(c["observed_order"]), num(c["expected_order"]), num(c["order_band"]));
    fmt::print("  {:<40} {:>13} {:>13} {:>10} {:>9} {:>15} {}{}\n", c["quantity"].get<std::string>(), num(c["reference"]),
               num(c["dem"]), num(c["error"]), num(c["tolerance"]), order, c["passed"].get<bool>() ? "pass" : "FAIL",
               c["note"].get<std::string>().empty() ? "" : "  [" + c["note"].get<std::string>() + "]");
  }
  fmt::print("  => {}  ({})\n", passed ? "PASSED" : "FAILED", (out / "result.json").string());
}

/// The study after its file was read and running.json written: run it, draw, write result.json.
StudyResult run_marked(const Study& s, const fs::path& file, const fs::path& out, const StudyOptions& opt,
                       std::chrono::steady_clock::time_point started) {
  Progress progress("study " + s.name, stderr, opt.print && ::isatty(::fileno(stderr)), opt.verbose);
  const ProgressScope shown(&progress);
  StudyRun run{s, out, opt, out / "cache"};
  // --fresh: forget earlier runs, record the new ones (only cache entries: anything else refuses)
  if (!opt.use_cache) dem::remove_owned_folder(run.cache_dir, dem::OwnedFolder::study_cache, "--fresh");
  fs::create_directories(run.cache_dir);

  if (s.kind == Kind::single || s.kind == Kind::refinement) run_levels(run);
  else if (s.kind == Kind::mode_map) run_mode_map(run);
  else run_stability(run);
  const nlohmann::json snapshots = take_snapshots(run);  // the pictures, after the study's runs
  progress.close();
  const nlohmann::json figures = draw_figures(run);
  fill_tables(run);

  nlohmann::json prov = dem::provenance();
  prov["overrides"] = s.set;
  nlohmann::json result = {
      {"study", s.name}, {"title", s.title}, {"requirement", s.requirement},
      {"kind", kind_word(s.kind)},
      {"case", s.case_path}, {"parameter", s.parameter}, {"reference", s.reference_text}, {"setup", setup_of(run)},
      {"provenance", prov}, {"passed", run.passed}, {"checks", run.checks}, {"series", run.series},
      {"figures", figures}, {"tables", run.tables}};
  if (s.ensemble) result["ensemble"] = ensemble_json(*s.ensemble);
  if (!snapshots.empty()) result["snapshots"] = snapshots;
  result["provenance"]["wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  result["provenance"]["command"] = fmt::format("dem2d study {} --out {} --jobs {}{}", file.string(), out.string(),
                                                opt.jobs, opt.use_cache ? "" : " --fresh");
  // The study's README (purpose, findings, known limits) travels with the result: the report shows it.
  if (const fs::path readme = fs::absolute(file).parent_path() / "README.md"; fs::exists(readme))
    result["readme"] = dem::read_file(readme);
  result["provenance"]["runs_reused"] = run.reused.load();
  result["provenance"]["runs_run"] = run.ran.load();
  if (run.reused.load() > 0) {  // what the cache served: the report says so beside the wall time
    result["provenance"]["reused_run_seconds"] = run.reused_seconds;
    result["provenance"]["reused_code_version"] = run.reused_code_version;
    result["provenance"]["reused_date"] = run.reused_date;
  }
  dem::write_file_atomic(out / "result.json", result.dump(2) + "\n");
  fs::remove(out / "running.json");
  if (opt.print) print_checks(s, run.checks, run.passed, out);
  return {run.passed, result};
}

}  // namespace

StudyResult run_study(const fs::path& file, const StudyOptions& opt) {
  const auto started = std::chrono::steady_clock::now();
  const Study s = read_study(file);
  // running.json marks a study under way (or killed) until the new result.json is renamed into place,
  // and says how it ended if it failed.
  const fs::path out = open_study_folder(s.name, opt);
  return marking_failure(out, s.name, [&] { return run_marked(s, file, out, opt, started); });
}

}  // namespace ver
