#pragma once
// Running a case: the step loop with outputs (time-series CSV, JSON summary, VTK snapshots), probes,
// stop criteria, progress on a terminal, and blow-up detection (NaN or runaway energy stops the run
// with a message, keeping what was written).
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "dem/cases/case_file.hpp"

namespace dem {

struct RunOptions {
  std::filesystem::path out_dir;  // empty: write nothing (studies that only need probes)
  bool progress = false;          // show progress (only when stderr is a terminal)
};

struct RunResult {
  std::string status;   // "completed", "settled", "past peak" ([stop] after_peak), "blow-up"
  std::string message;  // what happened, for a blow-up
  std::int64_t steps = 0;
  double time = 0.0;                 // simulated [s]
  double wall_seconds = 0.0;
  double element_steps_per_second = 0.0;
  double stability_limit = 0.0;      // [s]
  std::map<std::string, std::optional<double>> probes;
  nlohmann::json summary;            // what summary.json holds
};

/// The code version, build type and the like, recorded in every result file.
nlohmann::json provenance();

RunResult run_case(const Case& c, const RunOptions& opt);

}  // namespace dem
