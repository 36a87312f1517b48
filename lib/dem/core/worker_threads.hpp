#pragma once
// The threads of a step (Simulation::set_threads): a small pool that stays alive between steps, with a
// barrier. Waiting threads spin briefly, then sleep (C++20 atomic wait: a futex): on a machine shared
// with other work a thread that waits for a descheduled partner must not burn a core (OpenMP's default
// spinning made two threads four times as expensive in CPU time as one there; bench/journal.md, "Threads
// inside a run").
// Memory: everything a thread wrote before barrier() or before the end of run() is visible to every
// thread after it (release/acquire on the counters).
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace dem {

class WorkerThreads {
 public:
  explicit WorkerThreads(int threads);  // threads − 1 workers; the caller is thread 0
  ~WorkerThreads();
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;

  int size() const { return threads_; }
  /// CPU time that the workers (not the caller) have used since they started [s].
  double cpu_seconds() const;

  /// Runs body(t) for t = 0 … size() − 1, t = 0 on the caller's thread; returns when every call returned.
  template <class Body>
  void run(Body& body) {
    run_job([](void* b, int t) { (*static_cast<Body*>(b))(t); }, &body);
  }
  /// Inside body: returns once every thread has called it.
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

  int threads_;
  std::vector<std::thread> workers_;
  void (*job_)(void*, int) = nullptr;
  void* context_ = nullptr;
  bool stop_ = false;
  std::atomic<std::uint32_t> generation_{0};  // bumped for every job (and to stop)
  std::atomic<std::uint32_t> busy_{0};        // workers still running the job
  std::atomic<std::uint32_t> arrived_{0};     // threads at the barrier
  std::atomic<std::uint32_t> passed_{0};      // barriers passed
  struct alignas(64) Done {                   // per thread, on a cache line of its own
    std::atomic<std::uint32_t> job{0};        // the job in which the thread last called signal_done
  };
  std::vector<Done> done_;
  std::uint32_t job_number_ = 0;              // of the running job (written before it starts); a stale
                                              // flag equals it only after 2^32 jobs without a signal
};

}  // namespace dem
