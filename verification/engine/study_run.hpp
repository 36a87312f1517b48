#pragma once
// One study being run (engine/study.cpp): its runs, reused from the run cache or handed to the run
// pool, and what it has produced so far — checks, convergence series, tables, the finest run of each
// variant. Each kind of study fills it in a file of its own (study_levels.cpp: single and refinement,
// study_mode_map.cpp, study_stability.cpp); study_figures.cpp draws the declared figures and tables
// from it; study.cpp writes result.json.
#include <atomic>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/run_cache.hpp"
#include "engine/study.hpp"
#include "engine/study_file.hpp"

namespace ver {

/// A finished run: its probes (empty on a blow-up), status and speed.
struct RunOut {
  std::map<std::string, std::optional<double>> probes;
  std::string status, message;
  double eps = 0.0;
  double seconds_per_step = 0.0;  // wall clock per step (the cost of Fig. 10(c)); 0: unknown
};

/// A run to do: the overrides of the base case and its run folder (empty: no files).
struct Planned {
  std::vector<std::string> sets;
  std::filesystem::path out;
};

struct StudyRun {
  const Study& s;
  std::filesystem::path out;
  const StudyOptions& opt;
  std::filesystem::path cache_dir;   // finished runs, one small JSON file each (run_cache.hpp)
  std::atomic<int> reused{0}, ran{0};
  // The runs the cache served: their original run time (work / speed) and where they came from.
  double reused_seconds = 0.0;
  std::string reused_code_version, reused_date;  // of the newest reused run
  std::mutex reused_mutex;

  nlohmann::json checks = nlohmann::json::array(), series = nlohmann::json::array();
  nlohmann::json tables = nlohmann::json::array(), setup_extra = nlohmann::json::object();
  nlohmann::json mode_chart;          // mode_map: the coloured chart (the first figure)
  bool passed = true;
  std::vector<RunOut> finest_runs;    // the finest run of each variant (stability: probe "limit"); of an
                                      // ensemble: the members' means
  std::vector<std::map<std::string, EnsembleStat>> ensemble_stats;  // per variant and probe (ensembles only)
  double speed_sum = 0.0;
  std::size_t speed_n = 0;

  /// Runs a batch of the base case with overrides: reuses cached runs, hands the others to run_all
  /// (threads here, or the ranks of an MPI job: run_dispatch.hpp), caches each as it finishes. The
  /// k-th result belongs to the k-th plan, whatever order the runs finish in.
  std::vector<RunOut> run_many(const std::vector<Planned>& plan, int jobs);
  RunOut run_one(const std::vector<std::string>& sets, const std::filesystem::path& run_out = {});  // jobs = 1

  /// Counts a run the cache served into reused_seconds and the newest reused code version and date.
  void note_reused(const CachedRun& cached, double cost);

  /// The reference of a check for a variant: the solver at the variant's arguments, over them a
  /// refinement level's (if given), over those the check's own.
  std::optional<double> reference_of(const Check& c, const Variant& v, double param,
                                     const RefinementLevel* level = nullptr) const;
  /// Appends a check row to result.json's checks (and folds its verdict into `passed`).
  void add_check(const std::string& quantity, std::optional<double> reference, std::optional<double> dem,
                 const Check& c, std::optional<double> order, const std::string& note);
  /// The same for the mean of an ensemble: it passes only if the whole confidence interval of the mean
  /// satisfies the check (within: inside reference ± tolerance; above / below: beyond the margin).
  void add_ensemble_check(const std::string& quantity, std::optional<double> reference, const EnsembleStat& st,
                          const Check& c, const std::string& note);
};

/// The verdict of a check on an ensemble's interval [lo, hi] of the mean: within — inside reference ±
/// tolerance; above / below — beyond reference ± the margin (relative: tolerance × |reference|).
bool interval_passes(const Check& c, double reference, double lo, double hi);

/// "label, variant" (the label alone for the unnamed variant).
std::string check_label(const Check& c, const Variant& v);
std::string fmt_value(std::optional<double> v);
/// A probe of a run; "element_steps_per_second" is the run's speed.
std::optional<double> probe_of(const RunOut& r, const std::string& probe);
/// A registry solver with only the arguments it takes (variant arguments may serve several solvers).
double evaluate_solver(const std::string& solver, const std::map<std::string, double>& args);
[[noreturn]] void fail(const Study& s, const std::string& key, const std::string& what);

void run_levels(StudyRun& run);      // kind single or refinement (study_levels.cpp)
/// An ensemble study's plan: each planned run once per member (member 1 keeps the run folder that
/// feeds the figures); and the members' runs folded into one per variant (means; run.ensemble_stats),
/// with members.csv and a table of every checked probe's interval (study_ensemble_run.cpp).
std::vector<Planned> member_plan(const StudyRun& run, const std::vector<Planned>& per_variant);
std::vector<RunOut> fold_members(StudyRun& run, const std::vector<RunOut>& runs);
void run_mode_map(StudyRun& run);    // study_mode_map.cpp
/// One grid point of the mode map: Sagaseta's mode (ref), Goodman & Bray's (gb), the DEM's (−1: the run failed).
struct ModePoint {
  std::size_t block, phi, alpha;
  int ref = 0, gb = 0, dem = -1;
  bool near_boundary = false;
  double slide = 0.0, rotation = 0.0;
};
/// The map as a coloured chart: rows = block and φ (equal margins above and below), x = α; ring = Sagaseta, dot = the DEM.
nlohmann::json mode_chart(const Study& s, const std::vector<ModePoint>& pts);
void run_stability(StudyRun& run);   // study_stability.cpp
/// The declared figures (after the mode map's chart) and tables (appended to run.tables).
nlohmann::json draw_figures(const StudyRun& run);
void fill_tables(StudyRun& run);

}  // namespace ver
