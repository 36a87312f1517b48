#pragma once
// Where the time of a run's steps goes, per thread and phase (`dem2d run --timings` writes it to
// summary.json; bench/scaling.py reads it): what an Amdahl estimate of a step on more cores needs, and
// where a thread waits. The phases of a step on several threads (parallel_step.cpp): the rebuild test and
// a rebuild made inside the step's job, the sweeps (contact laws), the integration, the sums of the
// shared elements; the pool adds the waits and the wake-ups (worker_threads.hpp). Thread 0's work outside
// the jobs is the serial part of a step.
#include <chrono>
#include <cstdint>
#include <vector>

namespace dem {

/// The wall clock of the timings [s] (steady; a vDSO call of some 20 ns).
inline double phase_clock() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Adds the time from its construction to its end to *seconds (nothing if seconds is null).
class PhaseTimer {
 public:
  explicit PhaseTimer(double* seconds) : seconds_(seconds), start_(seconds ? phase_clock() : 0.0) {}
  ~PhaseTimer() {
    if (seconds_) *seconds_ += phase_clock() - start_;
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  double* seconds_;
  double start_;
};

struct alignas(64) PhaseTimes {  // one thread's [s], on a cache line of its own
  double rebuild = 0.0, sweep = 0.0, integrate = 0.0, gather = 0.0;
};

struct StepTimings {
  bool on = false;
  std::vector<PhaseTimes> threads;  // per thread of the pool
  double step_wall = 0.0;           // the wall time inside Simulation::step()
  double step_jobs = 0.0;           // of it, inside the pool's jobs (thread 0's wall time)
  double rebuild_serial = 0.0;      // of it, the rebuild's serial part on thread 0 (the cells)
  std::int64_t steps = 0, rebuilds = 0;
};

}  // namespace dem
