#pragma once
// How many of a run's threads a step uses (Simulation::set_threads): all of them, unless the machine is
// busy with other work. No result depends on it (thread_shares.hpp: every element sums its contacts in
// the one-thread order on any number of threads). On a machine whose cores other processes also use, a
// thread waits for partners that lost their core at every barrier, and two threads ran four to five times
// slower than one (bench/journal.md, "Oversubscribed"). The governor measures and steps down:
// - steps are grouped in windows of kWindow steps, each read as its median step time (a rebuild inside
//   a window does not move it);
// - while the threads waited for more than kWaitShare of their time in the window's jobs, a probe: one
//   window of kProbe steps on half the threads, kept if its median is lower than the last window's;
// - from fewer threads than asked for, a probe up to twice as many now and then;
// - a probe that loses makes the hold before the next one in its direction four times longer (from
//   kStartHold up to kMaxHold windows): on a quiet machine, or on a busy one, the probes cost little.
#include <cstdint>
#include <vector>

namespace dem {

class ThreadGovernor {
 public:
  static constexpr int kWindow = 16, kProbe = 8;
  static constexpr double kWaitShare = 0.5;
  static constexpr int kStartHold = 4, kMaxHold = 1024;
  /// The threads asked for (at most the usable cores); 1: the governor does nothing.
  void start(int most);
  int most() const { return most_; }
  /// From now on `threads` (1 … most) and no probes (tests: the thread count changing between steps).
  void hold_at(int threads);
  /// The threads of the next step.
  int threads() const { return current_; }
  /// After a step on threads() threads: its wall time [s]; true when a window is complete (window_done next).
  bool add_step(double wall_seconds);
  /// At a window's end: the share of the threads' time in its jobs spent waiting (0 … 1; −1: unknown).
  void window_done(double wait_share);
  /// Probes made, and the steps made on fewer threads than asked for (statistics for summary.json).
  std::int64_t probes() const { return probes_; }
  std::int64_t steps_below_most() const { return steps_below_most_; }

 private:
  int most_ = 1, base_ = 1, current_ = 1;
  bool probing_ = false, probing_down_ = false, held_ = false;
  double base_median_ = 0.0;
  int hold_down_ = 0, hold_up_ = 0, grow_down_ = kStartHold, grow_up_ = kStartHold;
  std::vector<double> walls_;
  std::int64_t probes_ = 0, steps_below_most_ = 0;
};

}  // namespace dem
