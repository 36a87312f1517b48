// Simulation on several threads (simulation.hpp, thread_shares.hpp): the pool, the shares and their
// balance, the sums of the shared elements in the contact index's fixed
// order (gather_forces), and the step's job on the threads (step_on_threads).
#include "dem/core/simulation.hpp"

#include <algorithm>

#include <time.h>

#include "dem/core/step_loops.hpp"

namespace dem {

using step_detail::any_displaced;
using step_detail::take_worse;

namespace {

/// CPU time of the calling thread [s] (not the wall clock: a thread descheduled by other work on a shared
/// machine must not look slow).
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

// The pool has the threads asked for; a job runs on `threads` of them (fewer while the governor says so).
WorkerThreads& Simulation::workers(int threads) const {
  const int size = std::max(threads, threads_asked());
  if (!workers_.pool || workers_.pool->size() != size) {
    workers_.pool = std::make_unique<WorkerThreads>(size);
    workers_.pool->set_timing(true);  // the waits, for the governor and the timings (a clock read per wait)
  }
  if (timings_.on && timings_.threads.size() < static_cast<std::size_t>(size))
    timings_.threads.resize(static_cast<std::size_t>(size));
  workers_.pool->set_active(threads);
  return *workers_.pool;
}

// After a step on several threads: the step's wall time to the governor; at a window's end, the share of
// the threads' time in the window's jobs that they waited (the pool's waits and wake-ups).
void Simulation::govern(double step_wall) {
  if (!governor_.add_step(step_wall)) return;
  double share = -1.0;
  if (workers_.pool) {
    const double waits = workers_.pool->wait_seconds();
    const double jobs = workers_.pool->job_seconds();
    const double threads = static_cast<double>(workers_.pool->active());
    if (jobs > governor_job0_) share = (waits - governor_wait0_) / (threads * (jobs - governor_job0_));
    governor_wait0_ = waits;
    governor_job0_ = jobs;
  }
  governor_.window_done(share);
}

StepTimings Simulation::step_timings() const { return timings_; }

void Simulation::share_work(int threads) {
  shares_.build(threads, m_.elements.size(), linear_pairs_.pair, face_pairs_, linear_walls_, face_walls_);
  busy_.assign(static_cast<std::size_t>(threads), ThreadClock{});
  balance_steps_ = 0;
}

void Simulation::balance_threads(const std::vector<double>& seconds) {
  const int nt = threads_used();
  if (nt < 2) return;
  if (shares_.threads != nt) share_work(nt);
  shares_.balance(seconds, linear_pairs_.pair, face_pairs_, linear_walls_, face_walls_);
  busy_.assign(static_cast<std::size_t>(nt), ThreadClock{});
  balance_steps_ = 0;
  ++balances_;
}

void Simulation::balance_if_uneven() {
  if (++balance_steps_ < kBalanceSteps) return;
  busy_seconds_.resize(busy_.size());
  double most = 0.0, sum = 0.0;
  for (std::size_t t = 0; t < busy_.size(); ++t) {
    busy_seconds_[t] = busy_[t].seconds;
    most = std::max(most, busy_[t].seconds);
    sum += busy_[t].seconds;
  }
  const double mean = sum / static_cast<double>(busy_.size());
  // A balance runs between two steps on one thread (a pass over the elements): it is made when it pays. The
  // busiest thread held the others up by about (most − mean) over the kBalanceSteps / kClockEvery measured
  // steps, i.e. by kClockEvery (most − mean) over the next kBalanceSteps; a damped balance wins back half.
  const double gain = 0.5 * kClockEvery * (most - mean);
  if (most > (1.0 + kBalanceTolerance) * mean && gain > balance_seconds_) {
    const double start = phase_clock();
    balance_threads(busy_seconds_);
    balance_seconds_ = phase_clock() - start;
  } else {
    busy_.assign(busy_.size(), ThreadClock{});
    balance_steps_ = 0;
  }
}

void Simulation::gather_shared(std::size_t k, bool from_weight) {
  const std::uint32_t b = shares_.shared_start[k], end = shares_.shared_start[k + 1];
  gather_forces(shares_.shared_items.data() + b, end - b, from_weight);
}

// Each element sums what its slots computed, in the fixed order of the contact index, with the very
// operations the one-thread sweeps performed (f_i += f, f_j −= f; K15, M12): the same sums bit for bit.
// A slot that added nothing this step is skipped by adding −0 (x + (−0) = x) or subtracting +0 (x − 0 = x)
// for every x, also x = −0, without a branch.
void Simulation::gather_forces(const std::uint32_t* items, std::size_t count, bool from_weight) {
  Elements& e = m_.elements;
  const double* const mass = e.mass.data();
  const double* const radius = e.radius.data();
  double* const fx_e = e.fx.data();
  double* const fy_e = e.fy.data();
  double* const moment = e.moment.data();
  const std::uint8_t* const lp_touching = linear_pairs_.touching.data();
  const LinearContactResultant* const lp = linear_pairs_.resultant.data();
  const LinearSlot* const lw = linear_walls_.data();
  const ElementPush* const fp = face_push_.data();
  const ElementPush* const fw = face_wall_push_.data();
  const std::uint32_t* const ls = index_.linear_start.data();
  const std::uint32_t* const li = index_.linear_items.data();
  const std::uint32_t* const os = index_.other_start.data();
  const std::uint32_t* const oi = index_.other_items.data();
  const Vec2 g = m_.gravity;
  const bool rolling = linear_pairs_.with_rolling;
  const RollingState* const lr = linear_pairs_.rolling.data();
  const std::int32_t* const lp_law = linear_pairs_.law.data();
  const PairLaw* const laws = m_.laws.data();
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint32_t k = items[c];
    double fx = from_weight ? mass[k] * g.x : fx_e[k];  // (K15): gravity, m g
    double fy = from_weight ? mass[k] * g.y : fy_e[k];
    double mom = from_weight ? 0.0 : moment[k];
    const double r = radius[k];
    for (std::uint32_t n = ls[k]; n < ls[k + 1]; ++n) {
      const std::uint32_t entry = li[n];
      const std::uint32_t slot = ContactIndex::linear_slot(entry);
      const LinearContactResultant& s = lp[slot];
      const bool on = lp_touching[slot] != 0;
      // (K15): force on i is −f_n n − f_s t, t = (−sin α, cos α); on j the opposite.
      const double sfx = -s.fn * s.nx + s.fs * s.ny, sfy = -s.fn * s.ny - s.fs * s.nx;
      if (ContactIndex::is_j(entry)) {
        fx -= on ? sfx : 0.0;
        fy -= on ? sfy : 0.0;
      } else {
        fx += on ? sfx : -0.0;
        fy += on ? sfy : -0.0;
      }
      mom -= on ? r * s.fs : 0.0;
      if (rolling) {  // (R6): +m on i, −m on j, added after the shear's moment as the sweep does
        const bool rolls = on && laws[static_cast<std::size_t>(lp_law[slot])].rolling.enabled;
        if (ContactIndex::is_j(entry)) mom -= rolls ? lr[slot].m : 0.0;
        else mom += rolls ? lr[slot].m : -0.0;
      }
    }
    for (std::uint32_t n = os[k]; n < os[k + 1]; ++n) {
      const std::uint32_t entry = oi[n];
      const std::uint32_t slot = ContactIndex::other_slot(entry);
      switch (ContactIndex::other_kind(entry)) {
        case SlotKind::face_pair: {
          const ElementPush& p = fp[slot];
          const bool on = p.applied != 0;
          if (ContactIndex::is_j(entry)) {
            fx -= on ? p.fx : 0.0;
            fy -= on ? p.fy : 0.0;
            mom += on ? p.mj : -0.0;
          } else {
            fx += on ? p.fx : -0.0;
            fy += on ? p.fy : -0.0;
            mom += on ? p.mi : -0.0;
          }
          break;
        }
        case SlotKind::linear_wall: {
          const LinearSlot& s = lw[slot];
          const bool on = s.touching != 0;
          fx += on ? -s.f.fn * s.nx + s.f.fs * s.ny : -0.0;
          fy += on ? -s.f.fn * s.ny - s.f.fs * s.nx : -0.0;
          mom -= on ? r * s.f.fs : 0.0;
          mom += on && laws[static_cast<std::size_t>(s.law)].rolling.enabled ? s.rolling.m : -0.0;  // (R6)
          break;
        }
        case SlotKind::face_wall: {
          const ElementPush& p = fw[slot];
          const bool on = p.applied != 0;
          fx += on ? p.fx : -0.0;
          fy += on ? p.fy : -0.0;
          mom += on ? p.mi : -0.0;
          break;
        }
      }
    }
    fx_e[k] = fx;
    fy_e[k] = fy;
    moment[k] = mom;
  }
}

// The part of step() that runs on several threads: the rebuild test (and rebuild) split over the threads,
// each thread's share of the sweeps and of the integration, the shared elements' sums.
void Simulation::step_on_threads(int nt, bool tested, double inv_dt, double dt_v, double limit2_step,
                                 double limit2_next, bool plate) {
  if (shares_.threads != nt) share_work(nt);
  WorkerThreads& pool = workers(nt);
  const double limit2 = step_ > 0 && !tested ? rebuild_limit2() : 0.0;
  const bool test = step_ > 0 && !tested && limit2 >= 0.0;  // the rebuild test, each thread over its elements
  if (step_ > 0 && !tested && !test) rebuild();
  displaced_.assign(static_cast<std::size_t>(nt), 0);
  displaced_now_.assign(static_cast<std::size_t>(nt), 0);
  range_tests_.assign(static_cast<std::size_t>(nt), RangeTests{});
  oversteps_.assign(static_cast<std::size_t>(nt), Overstep{});
  bool index_failed = false;
  const bool timed = balance_steps_ % kClockEvery == 0;  // this step's work measured (balance_if_uneven)
  auto body = [&](int t) {  // thread t takes share t
    const std::size_t k = static_cast<std::size_t>(t);
    PhaseTimes* const phase = phases(t);
    if (test) {  // needs_rebuild() split over the threads (an OR of the same per-element tests)
      const Elements& e = m_.elements;
      const std::size_t b = shares_.first[k], end = shares_.first[k + 1];
      displaced_now_[k] = any_displaced(e.x.data() + b, e.y.data() + b, x_ref_.data() + b, y_ref_.data() + b,
                                        limit2, end - b);
      pool.barrier();
      std::uint8_t any = 0;  // the same on every thread: displaced_now_ is not written again in this job
      for (std::uint8_t d : displaced_now_) any |= d;
      if (any && !rebuild_on(Team{&pool, t, nt})) {  // new slot lists and shares, for every thread after it
        if (t == 0) index_failed = true;  // too many slots: thrown after the job
        return;
      }
    }
    const double c0 = timed ? thread_seconds() : 0.0;  // the thread's work on its share, without the waits
    const double w0 = phase ? phase_clock() : 0.0;
    sweep_share(inv_dt, k, true);  // every contact law (K5–K14, M3–M12); (K15) on private elements
    pool.signal_done(t);
    const double w1 = phase ? phase_clock() : 0.0;
    // (K17–K19) and the next step's rebuild test: the elements [mid, end) at once (private: their forces
    // are complete, and no other thread reads them), the rest after the shared ones are summed. The shared
    // elements of thread t are touched only by slots of the threads before it (slots are computed by
    // the owner of their i, and j > i): t waits for those threads' sweeps, not for every thread (a
    // barrier would make each wait for the slowest of both phases).
    const std::size_t b = shares_.first[k], end = shares_.first[k + 1];
    const std::size_t mid = plate ? end : std::max<std::size_t>(b, shares_.private_from[k]);
    Overstep late;
    RangeTests tests_late;
    if (mid < end) late = integrate_range(mid, end, dt_v, freedom(mid, end), limit2_step, limit2_next, tests_late);
    const double c1 = timed ? thread_seconds() : 0.0;
    const double w2 = phase ? phase_clock() : 0.0;
    pool.wait_earlier(t);  // their sweeps no longer read the shared elements, and their slots are complete
    const double c2 = timed ? thread_seconds() : 0.0;
    const double w3 = phase ? phase_clock() : 0.0;
    gather_shared(k, true);  // (K15): m g plus the contacts of the shared elements, in the fixed order
    const double w4 = phase ? phase_clock() : 0.0;
    if (!plate) {
      Overstep first;  // over the shares in element order (overstep())
      RangeTests tests_first;
      if (b < mid) first = integrate_range(b, mid, dt_v, freedom(b, mid), limit2_step, limit2_next, tests_first);
      take_worse(first, late);
      oversteps_[k] = first;
      displaced_[k] = tests_first.displaced | tests_late.displaced;
      range_tests_[k] = {0, static_cast<std::uint8_t>(tests_first.skipped + tests_late.skipped),
                         std::max(tests_first.max_d2, tests_late.max_d2)};
    }
    // the walls' forces from the wall slots (in slot order, as on one thread), by the last thread: it has
    // waited for every other thread's sweep, and it usually finishes before thread 0
    if (t == nt - 1) sum_wall_forces();
    if (timed) busy_[k].seconds += (c1 - c0) + (thread_seconds() - c2);
    if (phase) {
      phase->sweep += w1 - w0;
      phase->gather += w4 - w3;
      phase->integrate += (w2 - w1) + (phase_clock() - w4);
    }
  };
  pool.run(body);
  if (index_failed)
    ContactIndex::check(linear_pairs_.size(), face_pairs_.size() + linear_walls_.size() + face_walls_.size());
  balance_if_uneven();  // the next step's shares (results do not depend on them)
}

}  // namespace dem
