#pragma once
// The threads of a step (Simulation::set_threads): a small pool that stays alive between steps, with a
// barrier. Waiting threads spin briefly, then sleep (C++20 atomic wait: a futex): on a machine shared
// with other work a thread that waits for a descheduled partner must not burn a core (OpenMP's default
// spinning made two threads four times as expensive in CPU time as one there; bench/README.md).
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

  /// Runs body(t) for t = 0 … size() − 1, t = 0 on the caller's thread; returns when every call returned.
  template <class Body>
  void run(Body& body) {
    run_job([](void* b, int t) { (*static_cast<Body*>(b))(t); }, &body);
  }
  /// Inside body: returns once every thread has called it.
  void barrier();

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
};

}  // namespace dem
