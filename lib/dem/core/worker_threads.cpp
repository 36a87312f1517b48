#include "dem/core/worker_threads.hpp"

#include <pthread.h>
#include <time.h>

#include <cstdlib>

#include "dem/core/step_timings.hpp"
#include "dem/core/usable_cores.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace dem {

namespace {

thread_local int pool_thread = 0;  // the calling thread's index in its pool (0: the caller of run)

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// How long a wait spins before it sleeps: longer than the spread of the threads' ends in a step and the
// serial gap between two jobs, so that no thread sleeps on a quiet machine (a sleeping thread's wake-up
// costs 5 to 50 µs, paid by the whole step: 1 ms against 50 µs was 13-15 % faster at 16 threads; journal,
// "Sixteen cores"). By the clock, not by a count of pause instructions (a pause takes 10 to 140 cycles, by
// processor). On a busy machine the governor takes threads out of the jobs (thread_governor.hpp), and a
// pool of more threads than usable cores does not spin at all. DEM2D_SPIN_US overrides it (benchmarks).
double default_spin_seconds() {
  if (const char* us = std::getenv("DEM2D_SPIN_US")) {
    char* end = nullptr;
    const double v = std::strtod(us, &end);
    if (end != us && v >= 0.0) return 1e-6 * v;
  }
  return 1e-3;
}

}  // namespace

void WorkerThreads::await_change(const std::atomic<std::uint32_t>& a, std::uint32_t old, int t) {
  if (a.load(std::memory_order_acquire) != old) return;
  const double start = spin_seconds_ > 0.0 || timing_ ? phase_clock() : 0.0;
  bool changed = false;
  for (int k = 1; spin_seconds_ > 0.0; ++k) {
    if (a.load(std::memory_order_acquire) != old) {
      changed = true;
      break;
    }
    cpu_relax();
    if (k % 32 == 0 && phase_clock() - start > spin_seconds_) break;
  }
  if (!changed) {
    if (timing_) ++done_[static_cast<std::size_t>(t)].times.sleeps;
    while (a.load(std::memory_order_acquire) == old) a.wait(old, std::memory_order_acquire);
  }
  if (timing_) done_[static_cast<std::size_t>(t)].times.wait += phase_clock() - start;
}

WorkerThreads::WorkerThreads(int threads)
    : threads_(threads < 1 ? 1 : threads),
      active_(threads_),
      spin_seconds_(threads_ > usable_cores() ? 0.0 : default_spin_seconds()),
      done_(static_cast<std::size_t>(threads_)) {
  workers_.reserve(static_cast<std::size_t>(threads_ - 1));
  for (int t = 1; t < threads_; ++t) workers_.emplace_back([this, t] { work(t); });
}

WorkerThreads::~WorkerThreads() {
  stop_ = true;
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  for (std::thread& w : workers_) w.join();
}

double WorkerThreads::cpu_seconds() const {
  double sum = 0.0;
  for (const std::thread& w : workers_) {
    clockid_t clock{};
    timespec ts{};
    if (pthread_getcpuclockid(const_cast<std::thread&>(w).native_handle(), &clock) == 0 && clock_gettime(clock, &ts) == 0)
      sum += static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
  return sum;
}

std::vector<PoolThreadTimes> WorkerThreads::times() const {
  std::vector<PoolThreadTimes> out;
  for (const Done& d : done_) out.push_back(d.times);
  return out;
}

double WorkerThreads::wait_seconds() const {
  double sum = 0.0;
  for (const Done& d : done_) sum += d.times.wait + d.times.wake;
  return sum;
}

void WorkerThreads::work(int t) {
  pool_thread = t;
  std::uint32_t seen = 0;
  for (;;) {
    // between jobs: waiting for the next one is not a wait inside a job (timing: the wake-up is)
    if (generation_.load(std::memory_order_acquire) == seen) {
      const double start = phase_clock();
      for (int k = 1; spin_seconds_ > 0.0 && generation_.load(std::memory_order_acquire) == seen; ++k) {
        cpu_relax();
        if (k % 32 == 0 && phase_clock() - start > spin_seconds_) break;
      }
      while (generation_.load(std::memory_order_acquire) == seen) generation_.wait(seen, std::memory_order_acquire);
    }
    seen = generation_.load(std::memory_order_acquire);
    if (stop_) return;
    if (t < job_active_) {  // in this job (the others only say that they saw it)
      if (timing_) done_[static_cast<std::size_t>(t)].times.wake += phase_clock() - job_start_;
      job_(context_, t);
    }
    if (busy_.fetch_sub(1, std::memory_order_acq_rel) == 1) busy_.notify_all();
  }
}

void WorkerThreads::run_job(void (*job)(void*, int), void* context) {
  const double start = timing_ ? phase_clock() : 0.0;
  job_active_ = active_;  // no worker reads it now: each one said it saw the last job
  if (active_ == 1) {
    job(context, 0);
  } else {
    job_ = job;
    context_ = context;
    job_start_ = start;
    ++job_number_;  // published to the workers with the generation below
    // every worker, also one not in the job, says it saw it: no worker reads the job's fields after it
    busy_.store(static_cast<std::uint32_t>(threads_ - 1), std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
    generation_.notify_all();
    job(context, 0);
    for (std::uint32_t left; (left = busy_.load(std::memory_order_acquire)) != 0;) await_change(busy_, left, 0);
  }
  if (timing_) {
    job_seconds_ += phase_clock() - start;
    ++jobs_;
  }
}

void WorkerThreads::signal_done(int t) {
  if (job_active_ == 1) return;
  Done& d = done_[static_cast<std::size_t>(t)];
  d.job.store(job_number_, std::memory_order_release);
  d.job.notify_all();
}
void WorkerThreads::wait_earlier(int t) {
  for (int s = 0; s < t; ++s) {
    const std::atomic<std::uint32_t>& job = done_[static_cast<std::size_t>(s)].job;
    for (std::uint32_t seen; (seen = job.load(std::memory_order_acquire)) != job_number_;) await_change(job, seen, t);
  }
}
void WorkerThreads::barrier() {
  if (job_active_ == 1) return;
  const std::uint32_t pass = passed_.load(std::memory_order_acquire);
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == static_cast<std::uint32_t>(job_active_)) {
    arrived_.store(0, std::memory_order_relaxed);
    passed_.fetch_add(1, std::memory_order_release);
    passed_.notify_all();
  } else {
    await_change(passed_, pass, pool_thread);
  }
}

}  // namespace dem
