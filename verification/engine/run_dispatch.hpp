#pragma once
// Where the runs of a study go: threads of this process (parallel_for, run_cache.hpp) or, when the
// MPI front end installed a distributor (engine/mpi/mpi_runs.hpp, built with -DDEM2D_MPI=ON), the
// ranks of an MPI job. The study runner and the sensitivity engine plan their runs first (a request
// per run that the cache does not hold), hand them to run_all, and store each reply in the slot of its
// request: the order in which runs finish never shows in the results.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dem {
struct Case;
}

namespace ver {

/// One run to do: the case file with overrides and, for runs that feed a figure, the run folder.
struct RunRequest {
  std::filesystem::path case_file;   // absolute
  std::vector<std::string> sets;
  std::filesystem::path out;         // run folder (series.csv, summary.json); empty: no files
  double cost = 0.0;                 // estimated work, steps × elements: the longest runs go first
};

/// What came back. status as dem::RunResult, or "case-error" (the case or the time-step guard refused
/// the run; message = what) or "error" (another failure on a remote rank; message = what).
struct RunReply {
  std::string status, message;
  double eps = 0.0;  // element-steps per second
  std::map<std::string, std::optional<double>> probes;
  double seconds_per_step = 0.0;  // the time loop's wall clock over its steps (a timing, not a result)
};

using RunDone = std::function<void(std::size_t, RunReply&)>;

/// The work of a run: steps × elements (at least 1).
double run_cost(const dem::Case& c);

/// Runs one request in this process, its files (if any) in `out_dir`. An interrupt (SIGINT/SIGTERM)
/// received before it starts gives status "interrupted" without running.
RunReply run_here(const RunRequest& req, const std::filesystem::path& out_dir);

/// Runs requests somewhere else (the MPI front end installs one on rank 0).
struct RunDistributor {
  virtual ~RunDistributor() = default;
  /// Runs every request once and calls done(i, reply) once per request as it finishes (from any
  /// thread, never two at once for the same i); returns when all have finished. Thread-safe: several
  /// callers (the bisections of a stability study) may run batches at the same time.
  virtual void run(const std::vector<RunRequest>& reqs, const RunDone& done) = 0;
};

/// Installs (or with nullptr removes) the distributor run_all uses.
void set_run_distributor(RunDistributor* d);
RunDistributor* run_distributor();

/// Runs the requests, longest first: on `jobs` threads here, or through the installed distributor.
/// done(i, reply) as each finishes (rank 0 only; it writes the cache entry).
void run_all(const std::vector<RunRequest>& reqs, int jobs, const RunDone& done);

}  // namespace ver
