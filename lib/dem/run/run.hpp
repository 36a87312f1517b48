#pragma once
// Running a case: the step loop with outputs (time-series CSV, JSON summary, VTK snapshots), probes,
// stop criteria, progress on a terminal, and blow-up detection (NaN or runaway energy stops the run
// with a message, keeping what was written). Outputs are crash-safe (output_files.hpp), interruptible
// (interrupt.hpp) and restartable bit for bit (checkpoint.hpp).
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "dem/cases/case_file.hpp"

namespace dem {

struct RunOptions {
  std::filesystem::path out_dir;  // empty: write nothing (studies that only need probes); cleared first
  bool progress = false;          // show progress (only when stderr is a terminal)
  // Checkpoints (checkpoint.hpp), written to <out_dir>/checkpoint.bin (replaced each time): every this
  // many steps (0: never), at the end, and always when the run is interrupted (SIGINT / SIGTERM).
  std::int64_t checkpoint_every = 0;
  bool checkpoint_at_end = false;
  std::filesystem::path restart;     // continue from this checkpoint (of the same case, unless:)
  bool restart_other_case = false;   //   the checkpoint is the start of this (other) case
  bool restart_any_version = false;  // accept a checkpoint another code version wrote (refused otherwise)
  std::int64_t interrupt_at_step = 0;  // tests: behave as if SIGTERM arrived after this step (0: no)
  int threads = 1;  // threads inside the run (Simulation::set_threads); results are the same for any number
  std::size_t min_per_thread = 1024;  // elements per thread at least (tests: 1)
  int threads_asked = 0;  // what the user asked for, if more than `threads` (summary.json "threads"; 0: = threads)
  bool governed = true;   // fewer threads while the machine is busy (core/thread_governor.hpp); false: exactly `threads`
  bool timings = false;   // summary.json "timings": per thread and phase (core/step_timings.hpp)
};

struct RunResult {
  std::string status;   // "completed", "settled", "past peak" ([stop] after_peak), "blow-up", "interrupted", "refused" (G7)
  std::string message;  // what happened, for a blow-up or a settle stop
  std::int64_t steps = 0;
  double time = 0.0;                 // simulated [s]
  double wall_seconds = 0.0;          // the time loop, by the clock on the wall
  double cpu_seconds = 0.0;           // the time loop's CPU time: the stepping thread and the run's workers
  double element_steps_per_second = 0.0;
  double stability_limit = 0.0;      // [s]
  std::map<std::string, std::optional<double>> probes;
  nlohmann::json summary;            // what summary.json holds
};

/// The code version, build type and the like, recorded in every result file.
nlohmann::json provenance();

/// Checks the quantity names of output.series and of the probes against the model; throws CaseError
/// with the file:line of the name (`dem2d check` and run_case call it before anything runs).
void check_outputs(const Case& c);

/// Runs a case. Throws CaseError for a wrong case or a checkpoint that does not fit it, OutputError
/// (output_files.hpp) when a result file cannot be written.
/// The case is taken by value and its model is moved into the run's Simulation: a caller that no
/// longer needs the case passes `std::move(c)`, and the model's elements exist once during the run
/// instead of twice (bench/journal.md, "Where the time and the bytes go"); a caller that keeps its case
/// passes it as it is and the run works on a copy. Either way the results are the same.
RunResult run_case(Case c, const RunOptions& opt);

}  // namespace dem
