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

/// Reads and checks a sensitivity file (its keys and the parameters' ranges against the base case)
/// without running anything: what `dem2d sweep` refuses before it starts (the fuzz target's path).
void check_sensitivity_file(const std::filesystem::path& study_file);

}  // namespace ver
