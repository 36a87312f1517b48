#pragma once
// Parameter sensitivity studies (`dem2d sweep STUDY`): a base case (or a test function with known
// indices), uncertain parameters with ranges (any `--set` path; uniform or log-uniform), outputs
// (probes of the case's summary) and methods: one-at-a-time sweeps, Morris elementary effects,
// Sobol' first-order and total indices (Saltelli sampling on a Sobol' sequence, Saltelli 2010 and
// Jansen estimators, bootstrap intervals). Runs go in parallel through the DEM core with a run cache
// in <out>/cache (resumable like `dem2d study`); failed runs (blow-up, refused by the time-step
// guard) are recorded, not fatal. Writes runs.csv, indices.csv and result.json (RESULT_FORMAT.md).
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

}  // namespace ver
