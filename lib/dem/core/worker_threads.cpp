#include "dem/core/worker_threads.hpp"

#include <pthread.h>
#include <time.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace dem {

namespace {

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// Spin iterations before sleeping: a few microseconds, about the imbalance of a balanced step; a partner
// that takes longer is probably descheduled, and the core is better given back.
constexpr int kSpins = 2000;

/// Waits until a != old: a short spin, then sleeps.
void await_change(const std::atomic<std::uint32_t>& a, std::uint32_t old) {
  for (int k = 0; k < kSpins; ++k) {
    if (a.load(std::memory_order_acquire) != old) return;
    cpu_relax();
  }
  while (a.load(std::memory_order_acquire) == old) a.wait(old, std::memory_order_acquire);
}

}  // namespace

WorkerThreads::WorkerThreads(int threads) : threads_(threads < 1 ? 1 : threads), done_(static_cast<std::size_t>(threads_)) {
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

void WorkerThreads::work(int t) {
  std::uint32_t seen = 0;
  for (;;) {
    await_change(generation_, seen);
    seen = generation_.load(std::memory_order_acquire);
    if (stop_) return;
    job_(context_, t);
    if (busy_.fetch_sub(1, std::memory_order_acq_rel) == 1) busy_.notify_all();
  }
}

void WorkerThreads::run_job(void (*job)(void*, int), void* context) {
  if (threads_ == 1) {
    job(context, 0);
    return;
  }
  job_ = job;
  context_ = context;
  ++job_number_;  // published to the workers with the generation below
  busy_.store(static_cast<std::uint32_t>(threads_ - 1), std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  job(context, 0);
  for (std::uint32_t left; (left = busy_.load(std::memory_order_acquire)) != 0;) await_change(busy_, left);
}

void WorkerThreads::signal_done(int t) {
  if (threads_ == 1) return;
  Done& d = done_[static_cast<std::size_t>(t)];
  d.job.store(job_number_, std::memory_order_release);
  d.job.notify_all();
}
void WorkerThreads::wait_earlier(int t) {
  for (int s = 0; s < t; ++s) {
    const std::atomic<std::uint32_t>& job = done_[static_cast<std::size_t>(s)].job;
    for (std::uint32_t seen; (seen = job.load(std::memory_order_acquire)) != job_number_;) await_change(job, seen);
  }
}
void WorkerThreads::barrier() {
  if (threads_ == 1) return;
  const std::uint32_t pass = passed_.load(std::memory_order_acquire);
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == static_cast<std::uint32_t>(threads_)) {
    arrived_.store(0, std::memory_order_relaxed);
    passed_.fetch_add(1, std::memory_order_release);
    passed_.notify_all();
  } else {
    await_change(passed_, pass);
  }
}

}  // namespace dem
