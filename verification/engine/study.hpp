#pragma once
// The study runner: a study file (verification/<name>/study.toml, documented in verification/README.md)
// names a base case, the overrides of its variants, the parameter to refine or bisect and the checks:
// a probe of the case against a reference solver from reference/ (or a fixed value, or Richardson),
// with a tolerance and an expected order. It runs every case in parallel, analyses each
// convergence series (convergence.hpp), prints a table and writes result.json (RESULT_FORMAT.md).
#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace ver {

struct StudyOptions {
  std::filesystem::path out_dir;   // default: build/studies/<name>
  int jobs = 1;                    // runs in parallel
  bool print = true;               // print the table
  bool use_cache = true;           // reuse finished runs from <out>/cache (false: --fresh, clears it first)
  bool verbose = false;            // a line per finished run on stderr (progress.hpp)
};

/// Thrown when SIGINT / SIGTERM stopped a run: the study stops without writing result.json (finished
/// runs stay in the cache).
struct StudyInterrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct StudyResult {
  bool passed = false;
  nlohmann::json json;             // what result.json holds
};

/// Runs one study. Throws std::runtime_error for a malformed study file (file:line: key: what), and
/// StudyInterrupted for SIGINT / SIGTERM.
StudyResult run_study(const std::filesystem::path& study_file, const StudyOptions& opt);

}  // namespace ver
