#pragma once
// The threads of a step (Simulation::set_threads): a small pool that stays alive between steps, with a
// barrier. Waiting threads spin for up to a millisecond by the clock, then sleep (C++20 atomic wait:
// a futex): on a machine shared with other work a thread that waits for a descheduled partner must not
// burn a core (OpenMP's default spinning made two threads four times as expensive in CPU time as one
// there; bench/journal.md, "Threads inside a run"). A pool of more threads than the cores this process
// may use (usable_cores.hpp) does not spin at all.
// A job may run on the first `active` threads only (Simulation's thread governor: fewer threads when the
// machine is busy); the others sleep through it.
// Memory: everything a thread wrote before barrier() or before the end of run() is visible to every
// thread after it (release/acquire on the counters).
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace dem {

/// Where the pool's time went (WorkerThreads::set_timing; `dem2d run --timings`), per thread [s].
struct PoolThreadTimes {
  double wait = 0.0;  // inside a job: at barrier(), wait_earlier() and (thread 0) for the job's end
  double wake = 0.0;  // from the job's start on thread 0 to the worker starting it (0 for thread 0)
  std::int64_t sleeps = 0;  // waits that outlasted the spin and slept (futex)
};

class WorkerThreads {
 public:
  explicit WorkerThreads(int threads);  // threads − 1 workers; the caller is thread 0
  ~WorkerThreads();
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;

  int size() const { return threads_; }
  /// The threads the next jobs run on (1 … size()); set between jobs only.
  void set_active(int active) { active_ = active < 1 ? 1 : (active > threads_ ? threads_ : active); }
  int active() const { return active_; }
  /// CPU time that the workers (not the caller) have used since they started [s].
  double cpu_seconds() const;
  /// Measure waits and wake-ups from now on (a clock read per wait; off by default).
  void set_timing(bool on) { timing_ = on; }
  /// Per thread, since set_timing(true); thread 0's entry also has the jobs' wall time in job_seconds().
  std::vector<PoolThreadTimes> times() const;
  /// The waits and wake-ups of every thread, summed [s] (the governor reads it every window).
  double wait_seconds() const;
  double job_seconds() const { return job_seconds_; }
  std::int64_t jobs() const { return jobs_; }
  bool spins() const { return spin_seconds_ > 0.0; }

  /// Runs body(t) for t = 0 … active() − 1, t = 0 on the caller's thread; returns when every call returned.
  template <class Body>
  void run(Body& body) {
    run_job([](void* b, int t) { (*static_cast<Body*>(b))(t); }, &body);
  }
  /// Inside body: returns once every active thread has called it.
  void barrier();
  /// Inside body: thread t says that its part of the job before this call is done (for wait_earlier).
  void signal_done(int t);
  /// Inside body: returns once every thread s < t has called signal_done(s) in this job. Thread 0 does not
  /// wait. Weaker than a barrier: a thread that needs only what the threads before it wrote does not wait
  /// for the threads after it.
  void wait_earlier(int t);

 private:
  void run_job(void (*job)(void*, int), void* context);
  void work(int t);
  // Waits until a != old: spins for spin_seconds_, then sleeps; with timing on, adds the wait to thread t.
  void await_change(const std::atomic<std::uint32_t>& a, std::uint32_t old, int t);

  int threads_;
  int active_;
  double spin_seconds_;  // how long a wait spins before it sleeps (0: the pool has more threads than cores)
  std::vector<std::thread> workers_;
  void (*job_)(void*, int) = nullptr;
  void* context_ = nullptr;
  int job_active_ = 1;  // active_ of the running job (written before it starts)
  bool stop_ = false;
  std::atomic<std::uint32_t> generation_{0};  // bumped for every job (and to stop)
  std::atomic<std::uint32_t> busy_{0};        // workers still running the job
  std::atomic<std::uint32_t> arrived_{0};     // threads at the barrier
  std::atomic<std::uint32_t> passed_{0};      // barriers passed
  struct alignas(64) Done {                   // per thread, on a cache line of its own
    std::atomic<std::uint32_t> job{0};        // the job in which the thread last called signal_done
    PoolThreadTimes times;                    // written by this thread only
  };
  std::vector<Done> done_;
  std::uint32_t job_number_ = 0;              // of the running job (written before it starts); a stale
                                              // flag equals it only after 2^32 jobs without a signal
  bool timing_ = false;
  double job_start_ = 0.0;                    // steady clock at the job's start (timing only)
  double job_seconds_ = 0.0;
  std::int64_t jobs_ = 0;
};

}  // namespace dem
