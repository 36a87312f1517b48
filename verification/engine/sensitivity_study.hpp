#pragma once
// What the pieces of a sensitivity study (sensitivity.hpp, `dem2d sweep`) share: the study as read
// (Sens), its runs (Run; the design in sensitivity_plan.cpp, the Runner in sensitivity_runs.cpp) and
// the analysis state each method adds to (checks, tables, figures, series, indices.csv, passed;
// sensitivity_oat.cpp, sensitivity_morris.cpp, sensitivity_sobol*.cpp). Internal to the engine.
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/sensitivity_estimators.hpp"
#include "engine/sensitivity_functions.hpp"
#include "engine/sensitivity_sampling.hpp"
#include "engine/sensitivity_transform.hpp"

namespace ver::sens {

struct Sens {
  std::filesystem::path file, case_file;  // case_file: the base case, resolved relative to the sensitivity file's folder
  std::string name, title, requirement, case_path;
  std::optional<TestFunction> function;
  std::vector<std::string> set, outputs;
  std::vector<Parameter> params;
  bool oat = false, morris = false, sobol = false;
  std::size_t oat_points = 5;
  std::size_t trajectories = 10;
  int levels = 4;
  std::size_t morris_resamples = 1000;  // [morris] bootstrap: resamples of the elementary effects
  double morris_confidence = 0.95;     // [morris] confidence of the μ*, μ, σ intervals
  std::uint64_t seed = 1;
  std::size_t samples = 256, resamples = 1000;
  double confidence = 0.95;
  std::uint64_t sobol_seed = 1;   // [sobol] seed: the Owen scrambling of the Sobol' sequence
  bool second_order = false;      // [sobol] second_order: also BA_i, the S_ij (sensitivity_second_order.hpp)
  std::optional<double> second_order_tolerance;  // function studies: |S_ij − exact| allowed, with its reason
  std::string second_order_reason;
  bool delta = false;                 // [sobol] delta: also Borgonovo's δ from the rows of A and B (sensitivity_delta.hpp)
  std::size_t delta_resamples = 100;  // [sobol] delta_bootstrap
  std::optional<double> delta_tolerance;  // Ishigami: |δ − reference| allowed, with its reason
  std::string delta_reason;
  std::optional<double> index_tolerance;  // [sobol] tolerance, function studies: |S − exact| allowed for S, S_T, noise fraction
  std::string index_tolerance_reason;
  std::vector<std::size_t> convergence;     // function studies: Sobol' sample sizes for the error rate
  std::optional<double> expected_order;
  double order_band = 0.3;
  // [sobol] transforms: the indices of each listed monotone transform of the output, IN ADDITION to
  // those of the output itself (sensitivity_transform.hpp).
  std::vector<Transform> transforms;
  int max_failed = 0;
  // Δt tied to the time-step guard: each run's Δt = dt_fraction × the guard's limit for that run's
  // parameters (stiffness, mass, damping move the limit). dt_fraction_base: the fraction is the base
  // case's own Δt / limit (so the base run keeps the case's Δt).
  std::optional<double> dt_fraction;
  bool dt_fraction_base = false;
  // Replicates: every sample runs once per entry (that entry's overrides after the sample's) and its
  // outputs are the mean over the entries — for outputs with run-to-run noise (a silo's discharge rate
  // set by which arches form): the noise of the mean falls as 1/√(entries).
  std::vector<std::vector<std::string>> replicates;
  // A test function with run-to-run noise (the check of the noise split, sensitivity_noise.hpp): each
  // evaluation adds noise_sd × a standard normal draw, run k's draw from a generator seeded by
  // (noise_seed, k); `replicates = R` (a count for a function) evaluates every sample R times.
  double noise_sd = 0.0;
  std::uint64_t noise_seed = 1;
  nlohmann::json setup = nlohmann::json::object();
};

// ---- runs: the study engine's cache and pool (engine/run_cache.hpp) ----

struct Run {
  std::vector<double> u;                      // unit coordinates (OAT: NaN for parameters left at base)
  std::vector<std::string> sets;
  std::string method, status, message;
  std::vector<double> outputs;                // NaN: missing
  double dt = std::nan("");                   // dt_fraction: the Δt this run used
  // Replicates: the unbiased variance of each output over the sample's replicates (run-to-run noise;
  // empty without replicates, NaN where an output is missing) and how many there were.
  std::vector<double> noise_var;
  std::size_t replicates = 1;
};

bool run_ok(const Run& r);

std::string num(double x);        // 6 significant digits, "—" for a missing value
nlohmann::json jnum(double x);     // null for a missing value

// ---- the design (sensitivity_plan.cpp) ----

/// The overrides that put parameter p at value v: its path and every path that follows it.
void push_sets(std::vector<std::string>& sets, const Parameter& p, double v);

/// A run of the design at unit coordinates u (NaN: the parameter stays at the base case's value).
Run make_run(const Sens& s, const std::string& method, const std::vector<double>& u);

/// Every path and value is checked before anything runs: each parameter at both ends of its range.
void check_ranges(const Sens& s);

/// Every run of the study in order: one-at-a-time, then Morris, then Saltelli's A, B and AB_i; where
/// each method's runs begin.
struct Plan {
  std::vector<Run> runs;
  std::vector<double> grid;                   // one-at-a-time: the unit coordinates of each sweep
  std::size_t oat_begin = 0, morris_begin = 0, sobol_begin = 0;  // Sobol': A, B, AB_1 … AB_d, then BA_1 … BA_d (second order)
  std::vector<MorrisTrajectory> traj;
};
Plan plan_runs(const Sens& s);

// ---- running them (sensitivity_runs.cpp) ----

/// The time-step guard's limit for a case with these overrides (the guard's refusal off while it is asked).
double guard_limit(const std::filesystem::path& case_file, std::vector<std::string> sets);

struct Runner {
  const Sens& s;
  std::filesystem::path cache_dir;
  double dt_fraction = 0.0;  // > 0: Δt = dt_fraction × the guard's limit of each run
  std::atomic<int> reused{0}, ran{0};
  int duplicates = 0;  // runs with the same overrides as an earlier run of the study: run once, result shared

  void run_function(Run& r) const;
  void set_outputs(Run& r, const std::map<std::string, std::optional<double>>& probes) const;
  void run_all_runs(std::vector<Run>& runs, int jobs);
  /// Every sample, once or (replicates) once per replicate and then the mean per sample.
  void run_samples(std::vector<Run>& runs, int jobs);
};

/// The Δt fraction of the study's runs (0: each run keeps its case's Δt).
double dt_fraction_of(const Sens& s);

// ---- sample and analyse apart (sensitivity_design_io.cpp) ----

/// design.csv: run, method, then each parameter's value (17 digits, SI; blank = the base case's), the
/// header naming each by its ASCII name and unit ("dt [s]").
void write_design_csv(const Sens& s, const std::vector<Run>& runs, const std::filesystem::path& file);

/// Reads an outputs file (CSV: a `run` column 0 … n−1, one column per output of the study; other
/// columns ignored; blank, "nan" or a missing row = a failed run) into the runs' outputs and status.
/// Throws dem::CaseError (file:line: what) for anything else.
void read_outputs_csv(const Sens& s, const std::filesystem::path& file, std::vector<Run>& runs);

/// The table of every run (runs.csv, and its rows for result.json) and how many failed.
struct RunTable {
  nlohmann::json rows = nlohmann::json::array();
  int failed = 0;
};
RunTable write_runs_csv(const Sens& s, const std::vector<Run>& runs, bool derived_dt, const std::filesystem::path& file);

// ---- the analysis (sensitivity_oat.cpp, sensitivity_morris.cpp, sensitivity_sobol*.cpp) ----

struct Analysis {
  const Sens& s;
  nlohmann::json checks = nlohmann::json::array(), tables = nlohmann::json::array(), figures = nlohmann::json::array(),
                 series = nlohmann::json::array();
  std::ostringstream idx_csv;  // indices.csv
  bool passed = true;

  explicit Analysis(const Sens& study) : s(study) {}
  void add_check(const std::string& q, double ref, double val, double err, double tol, const std::string& reason,
                 bool ok, const std::string& note, std::optional<double> order = std::nullopt);
};

/// The failed-runs check and the table of all runs.
void report_runs(const RunTable& table, bool derived_dt, Analysis& an);

void analyse_oat(const Plan& plan, Analysis& an);
/// Run-to-run noise against effect for studies with replicates (sensitivity_noise.cpp).
void analyse_noise(const Plan& plan, const ExactIndices& exact, Analysis& an);
/// The noise each Sobol' row's mean carries (its replicates' variance / R), none without replicates.
std::optional<MeanNoise> mean_noise_of_runs(const Plan& plan, std::size_t o, std::size_t n, std::size_t d);
void analyse_morris(const Plan& plan, const ExactIndices& exact, Analysis& an);
void analyse_sobol(const Plan& plan, const ExactIndices& exact, Analysis& an);
void analyse_delta(const Plan& plan, Analysis& an);  // sensitivity_sobol_delta.cpp
/// Ranks (1 = largest) of the values, ties by order; Spearman's ρ of two rankings without ties (sensitivity_sobol_subsets.cpp).
std::vector<double> descending_ranks(const std::vector<double>& v);
double spearman(const std::vector<double>& ra, const std::vector<double>& rb);

struct DesignOutputs;
/// Convergence against sample size for a study of a case (sensitivity_sobol_subsets.cpp): the indices on
/// the nested first N/8, N/4, N/2, N rows, a table, a figure and the ranking's stability.
/// yname: the (transformed) output's label; id: what makes the figure's id unique.
void sobol_subsets(const DesignOutputs& y, const std::optional<MeanNoise>& nz, const std::string& yname, const std::string& id, Analysis& an);

/// Second-order indices of one output (sensitivity_sobol_second.cpp): table rows, indices.csv rows
/// ("i:j", S2) and, for test functions, the checks against the exact S_ij.
void second_order_rows(const DesignOutputs& y, const ExactIndices& exact, const std::string& yname, const std::string& tsuffix,
                       nlohmann::json& rows, Analysis& an);

// ---- Sobol' against a test function (sensitivity_sobol_checks.cpp) ----

/// The Sobol' estimators' inputs for a test function on Saltelli's design of n rows, transformed.
struct DesignOutputs {
  std::vector<double> fa, fb;
  std::vector<std::vector<double>> fab, fba;  // fba: second order only
};
/// scramble: the Owen scrambling's seed (0: the study's own).
DesignOutputs function_on_design(const Sens& s, std::size_t n, Transform transform, std::uint64_t scramble = 0);

/// Test functions: the bootstrap interval's width against the central limit theorem.
void check_interval_widths(const SobolIndices& si, Transform transform, const std::string& tsuffix, Analysis& an);

/// Function studies: the error over doubling sample sizes, at the quasi-random rate.
void sobol_convergence(const ExactIndices& exact_sobol, Transform transform, const std::string& tsuffix, Analysis& an);

}  // namespace ver::sens
