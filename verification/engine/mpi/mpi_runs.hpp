#pragma once
// Studies over MPI (built with -DDEM2D_MPI=ON; docs/cluster.md). `mpirun -n P dem2d study STUDY` (or
// `sweep`): rank 0 reads the study, plans the runs and writes every file, exactly as the serial
// command does; it hands the runs out dynamically, the longest (steps × elements) first, to its own
// `--jobs` threads and to `--jobs` threads on each other rank. The other ranks only run cases and send
// back the probes (and, for a run that feeds a figure, the files of its run folder, which they write
// in a private temporary folder and delete): they write nothing shared. Rank 0 writes each finished
// run's cache entry at once (atomically), so a killed job keeps every finished run and the rerun
// continues. The order in which runs finish never shows: each result goes to its request's slot.
#include "engine/run_dispatch.hpp"

#include <memory>

namespace ver::mpi {

/// MPI for the lifetime of the object (MPI_Init_thread with MPI_THREAD_SERIALIZED, MPI_Finalize).
class Session {
 public:
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

/// Rank 0 of a job with more than one rank: installs itself as the run distributor (run_dispatch.hpp)
/// for its lifetime; its destructor tells the other ranks to stop.
class Distributor final : public RunDistributor {
 public:
  explicit Distributor(int jobs);
  ~Distributor() override;
  void run(const std::vector<RunRequest>& reqs, const RunDone& done) override;

  struct State;

 private:
  std::unique_ptr<State> st_;
};

/// Ranks > 0: runs what rank 0 sends, `jobs` at a time, until rank 0 says stop. Returns the exit code.
int serve(int jobs);

}  // namespace ver::mpi
