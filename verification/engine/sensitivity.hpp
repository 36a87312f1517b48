#pragma once
// Parameter sensitivity studies (`dem2d sweep STUDY`): a base case (or a test function with known
// indices), uncertain parameters (any `--set` path; uniform, log-uniform, normal, truncated normal,
// triangular, log-normal or discrete levels), outputs (probes of the case's summary) and methods:
// one-at-a-time sweeps, Morris elementary effects (bootstrap intervals of μ*, μ, σ), Sobol' first-order,
// total and optionally second-order indices (Saltelli sampling on an Owen-scrambled Sobol' sequence,
// Saltelli 2010, Janon 2014, Jansen and Saltelli 2002 estimators, bootstrap intervals). Runs go in parallel through the DEM core with a run cache
// in <out>/cache (resumable like `dem2d study`); failed runs (blow-up, refused by the time-step
// guard, no value of an output) are recorded, not fatal. Writes runs.csv, indices.csv and result.json (RESULT_FORMAT.md).
// The file format is documented in verification/README.md ("Sensitivity studies").
#include <filesystem>

#include "engine/study.hpp"

namespace ver {

/// Runs one sensitivity study. Throws std::runtime_error for a malformed file (file:line: key: what)
/// and StudyInterrupted for SIGINT / SIGTERM.
StudyResult run_sensitivity(const std::filesystem::path& study_file, const StudyOptions& opt);

/// `dem2d sweep STUDY --design-only`: writes <out>/design.csv (run, method, each parameter's value in SI
/// with its ASCII name and unit in the header) and runs nothing (sensitivity_design_io.cpp).
void write_sensitivity_design(const std::filesystem::path& study_file, const StudyOptions& opt);

/// `dem2d analyse STUDY --outputs OUTPUTS.csv`: the outputs of the design's runs computed anywhere (a
/// `run` column and one column per output, named as in the study; blank = a failed run), analysed as
/// `dem2d sweep` would: the same indices.csv, runs.csv and result.json in <out>.
StudyResult analyse_sensitivity(const std::filesystem::path& study_file, const std::filesystem::path& outputs_csv, const StudyOptions& opt);

/// Reads and checks a sensitivity file (its keys and the parameters' ranges against the base case)
/// without running anything: what `dem2d sweep` refuses before it starts (the fuzz target's path).
void check_sensitivity_file(const std::filesystem::path& study_file);

}  // namespace ver
