#include "dem/core/simulation.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <time.h>

#include <fmt/format.h>

#include "dem/core/stability.hpp"

namespace dem {

namespace {

inline std::uint64_t key(std::uint32_t i, std::uint32_t j) { return (std::uint64_t{i} << 32) | j; }

/// A slot list as merge() sees it: a vector of slots, or the columns of the linear pairs.
template <class Slot>
struct SlotVector {
  using Item = Slot;
  std::vector<Slot>& v;
  std::size_t size() const { return v.size(); }
  std::size_t capacity() const { return v.capacity(); }
  void reserve(std::size_t n) { v.reserve(n); }
  void resize(std::size_t n) { v.resize(n); }
  std::uint64_t key_at(std::size_t k) const { return key(v[k].i, v[k].j); }
  bool must_keep_at(std::size_t k) const { return must_keep(v[k]); }
  void move(std::size_t to, std::size_t from) { v[to] = v[from]; }
  void put(std::size_t to, const Slot& f) { v[to] = f; }
  using Full = Slot;  // a whole slot, held aside by merge_on
  Full load(std::size_t k) const { return v[k]; }
  void store(std::size_t k, const Full& s) { v[k] = s; }
};
struct PairSeed {  // a fresh linear pair slot
  std::uint32_t i = 0, j = 0;
  std::int32_t law = -1;
};
struct PairColumns {
  using Item = PairSeed;
  LinearPairSlots& v;
  std::size_t size() const { return v.size(); }
  std::size_t capacity() const { return v.capacity(); }
  void reserve(std::size_t n) { v.reserve(n); }
  void resize(std::size_t n) { v.resize(n); }
  std::uint64_t key_at(std::size_t k) const { return key(v.pair[k].i, v.pair[k].j); }
  bool must_keep_at(std::size_t) const { return false; }  // a linear history ends with its candidate
  void move(std::size_t to, std::size_t from) { v.move(to, from); }
  void put(std::size_t to, const PairSeed& f) { v.put_fresh(to, f.i, f.j, f.law); }
  using Full = FullPairSlot;
  Full load(std::size_t k) const { return {v.pair[k], v.touching[k], v.law[k], v.state[k]}; }
  void store(std::size_t k, const Full& s) {
    v.pair[k] = s.pair, v.touching[k] = s.touching, v.law[k] = s.law, v.state[k] = s.state;
  }
};

/// Merges fresh candidates into the old slots (both sorted by (i, j)) in place, without a second list:
/// make(fresh[k], slot) turns a candidate into a fresh slot, or skips it (false). The result is the
/// list a merge into a new vector gives: every candidate in (i, j) order, with its old history if it had
/// one, and the old slots without candidate that must outlive the rebuild. First the old slots that stay
/// are compacted towards the front (a write never passes the read), then the candidates without an old
/// slot are inserted from the back (the write stays ahead of the read by the inserts still to come).
/// A list that grows gets 1/8 headroom, not the vector's doubling (bench/journal.md, "Where the time and the
/// bytes go").
template <class List, class Fresh, class Make>
void merge(List slots, const std::vector<Fresh>& fresh, Make&& make) {
  const std::size_t n = fresh.size();
  typename List::Item f;
  std::size_t kept = 0, inserts = 0, c = 0;
  for (std::size_t o = 0; o < slots.size(); ++o) {
    const std::uint64_t ko = slots.key_at(o);
    for (; c < n && key(fresh[c].i, fresh[c].j) < ko; ++c) inserts += make(fresh[c], f) ? 1 : 0;
    bool candidate = false;
    if (c < n && key(fresh[c].i, fresh[c].j) == ko) candidate = make(fresh[c++], f);
    if (candidate || slots.must_keep_at(o)) {
      if (kept != o) slots.move(kept, o);
      ++kept;
    }
  }
  for (; c < n; ++c) inserts += make(fresh[c], f) ? 1 : 0;
  const std::size_t total = kept + inserts;
  if (total > slots.capacity()) slots.reserve(total + total / 8);
  slots.resize(total);
  std::size_t w = total, o = kept;
  for (c = n; c-- > 0 && w > o;) {
    if (!make(fresh[c], f)) continue;
    const std::uint64_t kc = key(f.i, f.j);
    while (o > 0 && slots.key_at(o - 1) > kc) --w, --o, slots.move(w, o);
    if (o > 0 && slots.key_at(o - 1) == kc) --w, --o, slots.move(w, o);  // its old history
    else slots.put(--w, f);
  }
}

/// merge() on the threads of a team, each taking the old slots and candidates of its element range
/// [first[t], first[t+1]) (every thread calls it with the same arguments; `aside` is the thread's own): the
/// same list, slot for slot. Each old slot's new place and each inserted candidate's is counted per range
/// first; then the old slots move straight to their places without a second list: all that move towards the
/// front, each thread in ascending order over its range, then all that move towards the back, in descending
/// order. A slot never lands on one that still has to move (the places keep the order of the slots), except a
/// slot whose place lies in another thread's range: those few are held aside before and written after the
/// moves, with the fresh slots.
template <class List, class Fresh, class Make, class Team>
void merge_on(const Team& team, List slots, const std::vector<Fresh>& fresh, Make&& make,
              const std::vector<std::uint32_t>& first, MergePlan& plan,
              std::vector<std::pair<std::size_t, typename List::Full>>& aside) {
  constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  const auto t = static_cast<std::size_t>(team.t), nt = static_cast<std::size_t>(team.nt);
  const std::size_t old_size = slots.size(), n = fresh.size();
  // This thread's old slots [ob, oe) and candidates [cb, ce): those whose i lies in its range.
  auto old_bound = [&](std::uint32_t i) {
    std::size_t lo = 0, hi = old_size;
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (slots.key_at(mid) < key(i, 0)) lo = mid + 1; else hi = mid;
    }
    return lo;
  };
  auto fresh_bound = [&](std::uint32_t i) {
    return static_cast<std::size_t>(std::lower_bound(fresh.begin(), fresh.end(), key(i, 0),
                                                     [](const Fresh& f, std::uint64_t k) { return key(f.i, f.j) < k; }) -
                                    fresh.begin());
  };
  const std::size_t ob = t == 0 ? 0 : old_bound(first[t]), oe = t + 1 == nt ? old_size : old_bound(first[t + 1]);
  const std::size_t cb = t == 0 ? 0 : fresh_bound(first[t]), ce = t + 1 == nt ? n : fresh_bound(first[t + 1]);
  if (t == 0) {
    plan.dest.resize(old_size);
    plan.place.resize(n);
    plan.at.resize(nt + 1);
  }
  team.sync();
  // Places relative to the range's start, as merge() makes them.
  typename List::Item f;
  std::uint32_t count = 0;
  std::size_t c = cb;
  for (std::size_t o = ob; o < oe; ++o) {
    const std::uint64_t ko = slots.key_at(o);
    for (; c < ce && key(fresh[c].i, fresh[c].j) < ko; ++c) plan.place[c] = make(fresh[c], f) ? count++ : none;
    bool candidate = false;
    if (c < ce && key(fresh[c].i, fresh[c].j) == ko) plan.place[c] = none, candidate = make(fresh[c++], f);
    plan.dest[o] = candidate || slots.must_keep_at(o) ? count++ : none;
  }
  for (; c < ce; ++c) plan.place[c] = make(fresh[c], f) ? count++ : none;
  plan.at[t + 1] = count;
  team.sync();
  if (t == 0) {
    plan.at[0] = 0;
    for (std::size_t q = 0; q < nt; ++q) plan.at[q + 1] += plan.at[q];
    const std::size_t total = plan.at[nt];
    if (total > slots.capacity()) slots.reserve(total + total / 8);
    if (total > old_size) slots.resize(total);
  }
  team.sync();
  const std::size_t at = plan.at[t];
  const bool last = t + 1 == nt;
  aside.clear();
  for (std::size_t o = ob; o < oe; ++o) {  // the slots that land in another range
    if (plan.dest[o] == none) continue;
    const std::size_t d = at + plan.dest[o];
    if (d < ob || (!last && d >= oe)) aside.emplace_back(d, slots.load(o));
  }
  team.sync();
  for (std::size_t o = ob; o < oe; ++o) {  // towards the front, ascending
    if (plan.dest[o] == none) continue;
    const std::size_t d = at + plan.dest[o];
    if (d < o && d >= ob) slots.move(d, o);
  }
  team.sync();
  for (std::size_t o = oe; o-- > ob;) {  // towards the back, descending
    if (plan.dest[o] == none) continue;
    const std::size_t d = at + plan.dest[o];
    if (d > o && (last || d < oe)) slots.move(d, o);
  }
  team.sync();
  for (const auto& [d, full] : aside) slots.store(d, full);
  for (std::size_t k = cb; k < ce; ++k) {
    if (plan.place[k] == none) continue;
    make(fresh[k], f);
    slots.put(at + plan.place[k], f);
  }
  team.sync();
  if (t == 0 && plan.at[nt] < old_size) slots.resize(plan.at[nt]);
  team.sync();
}

/// Ends a contact: the slot stays (it is a candidate pair) but forgets its history.
template <class Slot>
void reset_slot(Slot& s) {
  Slot fresh;
  fresh.i = s.i;
  fresh.j = s.j;
  fresh.law = s.law;
  s = fresh;
}

inline double reduced_mass(double a, double b) { return a * b / (a + b); }

// Element loops of the hot path as functions of restrict-qualified parameters, so that the compiler
// vectorises them (it does not trust restrict on local pointers). Every lane performs the scalar code's
// operations in the same order, and nothing is contracted into FMAs: results are bit-identical. The free
// integration also has an AVX2 clone (DEM2D_CLONES_AVX2: 4 lanes instead of 2, AVX2 has no FMA).

/// One degree of freedom of free elements: v += (h f) w (K17, w = 1/m or 1/I), then the increment
/// d = v Δt (K18) or d = (d + v Δt)/2 (K19), then x += d.
template <bool K19>
inline double advance_dof(double& v, double f, double w, double& d, double& x, double h, double dt) {
  v += h * f * w;
  d = K19 ? 0.5 * (d + v * dt) : v * dt;
  x += d;
  return d;
}
/// The blow-up prefilter of one element (may_overstep): bits whose sign bit is clear if (|Δx|/r)² may exceed
/// the limit, and bits with a set exponent if it is not finite. limit2r = limit2 (1 − 1e-12), so that no
/// division is needed: (dx² + dy²)/r² > limit2 implies dx² + dy² > limit2r · r² after rounding.
/// Also the largest squared increment |Δx|² so far, as its bit pattern (max_bits: the travel bound,
/// Simulation::travel_): for doubles ≥ 0 the patterns, read as integers, order as the values do, and an
/// integer maximum vectorises where a floating-point one does not. (A NaN d2 is caught by not_finite.)
inline void overstep_bits(double ddx, double ddy, double r, double limit2r, std::uint64_t& all_below,
                          std::uint64_t& not_finite, std::int64_t& max_bits) {
  const double d2 = ddx * ddx + ddy * ddy;
  all_below &= std::bit_cast<std::uint64_t>(d2 - limit2r * (r * r));
  not_finite |= std::bit_cast<std::uint64_t>(d2 * 0.0);
  const std::int64_t bits = std::bit_cast<std::int64_t>(d2);
  max_bits = bits > max_bits ? bits : max_bits;
}
inline bool may_overstep(std::uint64_t all_below, std::uint64_t not_finite) {
  return (all_below >> 63) == 0 || (not_finite & 0x7fffffffffffffffULL) != 0;
}
/// Free elements (K17–K19), the three degrees of freedom in one pass, with the blow-up prefilter on the
/// increments just computed (the bytes pass the core once). The same operations per element as one
/// degree of freedom at a time: bit-identical.
/// With `active` (Masked): elements removed from the run (a silo's outlet) keep their state, as the
/// element-by-element loop leaves them; the others advance with the same operations (a select per value).
template <bool K19, bool Masked = false>
DEM2D_CLONES_AVX2 bool integrate_free(double* __restrict vx, double* __restrict vy, double* __restrict om,
                                      const double* __restrict fx, const double* __restrict fy,
                                      const double* __restrict mom, const double* __restrict wm,
                                      const double* __restrict wi, double* __restrict dx, double* __restrict dy,
                                      double* __restrict dphi, double* __restrict x, double* __restrict y,
                                      double* __restrict phi, const double* __restrict r, double h, double dt,
                                      double limit2r, std::size_t n,
                                      const std::uint8_t* __restrict active, double& max_d2) {
  std::uint64_t all_below = ~std::uint64_t{0}, not_finite = 0;
  std::int64_t md = 0;  // the bits of +0.0
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (!Masked) {
      const double ddx = advance_dof<K19>(vx[i], fx[i], wm[i], dx[i], x[i], h, dt);
      const double ddy = advance_dof<K19>(vy[i], fy[i], wm[i], dy[i], y[i], h, dt);
      advance_dof<K19>(om[i], mom[i], wi[i], dphi[i], phi[i], h, dt);
      overstep_bits(ddx, ddy, r[i], limit2r, all_below, not_finite, md);
    } else {
      const bool on = active[i] != 0;
      double v[3] = {vx[i], vy[i], om[i]}, d[3] = {dx[i], dy[i], dphi[i]}, q[3] = {x[i], y[i], phi[i]};
      advance_dof<K19>(v[0], fx[i], wm[i], d[0], q[0], h, dt);
      advance_dof<K19>(v[1], fy[i], wm[i], d[1], q[1], h, dt);
      advance_dof<K19>(v[2], mom[i], wi[i], d[2], q[2], h, dt);
      vx[i] = on ? v[0] : vx[i], vy[i] = on ? v[1] : vy[i], om[i] = on ? v[2] : om[i];
      dx[i] = on ? d[0] : dx[i], dy[i] = on ? d[1] : dy[i], dphi[i] = on ? d[2] : dphi[i];
      x[i] = on ? q[0] : x[i], y[i] = on ? q[1] : y[i], phi[i] = on ? q[2] : phi[i];
      // (the increments of removed elements are old: they move no more, and count in no maximum)
      overstep_bits(on ? dx[i] : 0.0, on ? dy[i] : 0.0, r[i], limit2r, all_below, not_finite, md);
    }
  }
  max_d2 = std::bit_cast<double>(md);
  return may_overstep(all_below, not_finite);
}
/// Whether an element moved by at least √limit2 from its reference position: d² − limit2 ≥ 0 has a clear
/// sign bit (an AND of the bit patterns, which the compiler vectorises; a comparison it does not).
bool any_displaced(const double* __restrict x, const double* __restrict y, const double* __restrict xr,
                   const double* __restrict yr, double limit2, std::size_t n) {
  std::uint64_t all_negative = ~std::uint64_t{0};
  for (std::size_t i = 0; i < n; ++i) {
    const double ddx = x[i] - xr[i], ddy = y[i] - yr[i];
    all_negative &= std::bit_cast<std::uint64_t>(ddx * ddx + ddy * ddy - limit2);
  }
  return (all_negative >> 63) == 0;
}
/// Whether (|Δx|/r)² may exceed limit2 for some element of [0, n): overstep_bits over the increments,
/// without branches or comparisons, which the compiler vectorises.
bool may_overstep(const double* __restrict dx, const double* __restrict dy, const double* __restrict r,
                  double limit2r, std::size_t n, double& max_d2) {
  std::uint64_t all_below = ~std::uint64_t{0}, not_finite = 0;
  std::int64_t md = 0;  // the bits of +0.0
  for (std::size_t i = 0; i < n; ++i) overstep_bits(dx[i], dy[i], r[i], limit2r, all_below, not_finite, md);
  max_d2 = std::bit_cast<double>(md);
  return may_overstep(all_below, not_finite);
}
/// The first NaN, else the first largest (the order in which oversteps of successive ranges combine).
void take_worse(Simulation::Overstep& worst, const Simulation::Overstep& o) {
  if (o.index == Simulation::Overstep::npos) return;
  if (worst.index == Simulation::Overstep::npos || (!std::isnan(worst.fraction2) && !(o.fraction2 <= worst.fraction2))) worst = o;
}
/// The kinematic blow-up test over elements [b, end) (Simulation::overstep()), exact, element by element.
Simulation::Overstep find_overstep(const Elements& e, std::size_t b, std::size_t end, double limit2) {
  Simulation::Overstep worst;
  for (std::size_t i = b; i < end; ++i) {
    const double q = (e.dx[i] * e.dx[i] + e.dy[i] * e.dy[i]) / (e.radius[i] * e.radius[i]);
    if (!(q <= limit2) && e.active[i]) take_worse(worst, {i, q});
  }
  return worst;
}
/// CPU time of the calling thread [s] (not the wall clock: a thread descheduled by other work on a shared
/// machine must not look slow).
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
inline double prefilter_limit(double limit2) { return limit2 * (1.0 - 1e-12); }
/// The forces of a step start from the weight, f = m g (K15), both components in one pass.
void weight(double* __restrict fx, double* __restrict fy, const double* __restrict m, Vec2 g, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    fx[i] = m[i] * g.x;
    fy[i] = m[i] * g.y;
  }
}

}  // namespace

Simulation::Simulation(Model model) : m_(std::move(model)) {
  const Elements& e = m_.elements;
  if (m_.numerics.dt <= 0.0) throw std::invalid_argument("numerics.dt must be positive");
  double rmin = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < e.size(); ++i) rmin = std::min(rmin, e.radius[i]);
  skin_ = m_.numerics.skin > 0.0 ? m_.numerics.skin : (e.size() ? 0.25 * rmin : 0.0);
  // Initial increments (docs/references.md §1.4, "plain" start): Δx_0 = v(0)Δt.
  Elements& w = m_.elements;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w.motion[i] == Motion::fixed) {
      w.vx[i] = w.vy[i] = w.omega[i] = 0.0;
    } else if (w.motion[i] == Motion::driven) {
      const Vec2 v = m_.drives[static_cast<std::size_t>(w.drive[i])].at(0.0);
      w.vx[i] = v.x;
      w.vy[i] = v.y;
      w.omega[i] = 0.0;
    }
    w.dx[i] = w.vx[i] * m_.numerics.dt;
    w.dy[i] = w.vy[i] * m_.numerics.dt;
    w.dphi[i] = w.omega[i] * m_.numerics.dt;
  }
  for (Wall& wl : m_.walls)
    wl.increment = wl.drive >= 0 ? m_.drives[static_cast<std::size_t>(wl.drive)].at(0.0) * m_.numerics.dt
                                 : Vec2{};
  rebuild();
  if (!m_.preloads.empty()) apply_preloads();
}

void Simulation::apply_preloads() {
  Elements& e = m_.elements;
  // The preload is the increment of a static zeroth step: contacts are formed and loaded by it with
  // 1/Δt = 0 (no dashpot forces); nothing is integrated. The increments of step 0 are then restored.
  std::vector<double> keep_dx = e.dx, keep_dy = e.dy, keep_dphi = e.dphi;
  std::fill(e.dx.begin(), e.dx.end(), 0.0);
  std::fill(e.dy.begin(), e.dy.end(), 0.0);
  std::fill(e.dphi.begin(), e.dphi.end(), 0.0);
  for (const Preload& p : m_.preloads) {
    const std::size_t i = index_of(p.element);  // the case's numbering (the elements may be reordered)
    const Vec2 c{e.x[i], e.y[i]}, d = c - p.about;
    const double cs = std::cos(p.rotation), sn = std::sin(p.rotation);
    const Vec2 moved = p.about + Vec2{cs * d.x - sn * d.y, sn * d.x + cs * d.y};
    e.dx[i] = moved.x - c.x;
    e.dy[i] = moved.y - c.y;
    e.dphi[i] = p.rotation;
    e.x[i] = moved.x;
    e.y[i] = moved.y;
    e.phi[i] += p.rotation;
  }
  for (Wall& w : m_.walls) w.force = {};
  std::vector<Vec2> wall_inc;
  for (Wall& w : m_.walls) {
    wall_inc.push_back(w.increment);
    w.increment = {};
  }
  preloading_ = true;
  if (threads_used() == 1) {
    sweep_scatter(0.0);  // onto the forces the elements hold
  } else {
    if (shares_.threads != threads_used()) share_work(threads_used());
    WorkerThreads& pool = workers(threads_used());
    auto body = [&](int t) {
      sweep_share(0.0, static_cast<std::size_t>(t), false);  // onto the forces the elements hold
      pool.signal_done(t);
      pool.wait_earlier(t);  // the slots that touch t's shared elements belong to the threads before it
      gather_shared(static_cast<std::size_t>(t), false);
    };
    pool.run(body);
  }
  sum_wall_forces();
  preloading_ = false;
  for (std::size_t k = 0; k < m_.walls.size(); ++k) m_.walls[k].increment = wall_inc[k];
  e.dx = keep_dx;
  e.dy = keep_dy;
  e.dphi = keep_dphi;
  rebuild();
}

bool Simulation::needs_rebuild() const {
  const double limit2 = rebuild_limit2();
  if (limit2 < 0.0) return true;
  const Elements& e = m_.elements;
  return any_displaced(e.x.data(), e.y.data(), x_ref_.data(), y_ref_.data(), limit2, e.size());
}

double Simulation::rebuild_limit2() const {
  // Rebuild once an element may have moved half the skin since the last rebuild, or its displacement
  // plus the walls' reaches the skin: d ≥ min(skin/2, skin − max_w). Compared on squared displacements
  // (no square root, a loop the compiler vectorises), with a 1e-12 relative margin so that the test never
  // fires later than the exact one. When a rebuild happens does not change results: every touching pair
  // is a candidate either way, and a candidate that does not touch contributes nothing.
  double max_w = 0.0;
  for (std::size_t k = 0; k < m_.walls.size(); ++k) {
    max_w = std::max(max_w, norm(m_.walls[k].a - wall_ref_[k]));
  }
  const double limit = std::min(0.5 * skin_, skin_ - max_w);
  if (!(limit > 0.0)) return -1.0;  // rebuild now
  return limit * limit * (1.0 - 1e-12);
}

void Simulation::rebuild() {
  const int nt = threads_used();
  if (nt == 1) {
    rebuild_on(Team{});
    return;
  }
  WorkerThreads& pool = workers(nt);
  bool done = true;
  auto body = [&](int t) {
    if (!rebuild_on(Team{&pool, t, nt}) && t == 0) done = false;
  };
  pool.run(body);
  if (!done) ContactIndex::check(linear_pairs_.size(), face_pairs_.size() + linear_walls_.size() + face_walls_.size());
}

void Simulation::wall_candidates(std::uint32_t b, std::uint32_t end, std::vector<LinearSlot>& lin,
                                 std::vector<FaceSlot>& face) const {
  const Elements& e = m_.elements;
  for (std::uint32_t i = b; i < end; ++i) {
    if (!e.active[i]) continue;
    const Vec2 c{e.x[i], e.y[i]};
    for (std::uint32_t k = 0; k < m_.walls.size(); ++k) {
      const Wall& w = m_.walls[k];
      if (w.open) continue;
      const double cut = e.radius[i] + skin_;
      const Vec2 d = closest_point(w, c) - c;
      if (dot(d, d) >= cut * cut) continue;
      const std::int32_t law = m_.law_index(e.material[i], w.material);
      if (law < 0) continue;
      if (m_.laws[static_cast<std::size_t>(law)].kind == LawKind::linear) {
        LinearSlot s;
        s.i = i, s.j = k, s.law = law;
        lin.push_back(s);
      } else {
        FaceSlot s;
        s.i = i, s.j = k, s.law = law;
        face.push_back(s);
      }
    }
  }
}

bool Simulation::rebuild_on(const Team& team) {
  const int t = team.t, nt = team.nt;
  const auto k = static_cast<std::size_t>(t);
  const Elements& e = m_.elements;
  if (t == 0) {
    if (m_.numerics.reorder_every > 0 && rebuilds_ % m_.numerics.reorder_every == 0) reorder_elements();
    ++rebuilds_;
    rebuild_cells_ = search_.sort_into_cells(e, skin_);
    // Each thread collects the candidates of an equal count of elements (the search costs about the same for
    // every element). Which thread collects what changes no result.
    const std::size_t n = e.size(), nn = static_cast<std::size_t>(nt);
    rebuild_first_.resize(nn + 1);
    for (std::size_t q = 0; q <= nn; ++q) rebuild_first_[q] = static_cast<std::uint32_t>(n * q / nn);
    if (rebuild_parts_.size() < nn) rebuild_parts_.resize(nn);
    x_ref_.resize(n);
    y_ref_.resize(n);
    travel_ = 0.0;  // the reference positions are the positions now (copied below)
  }
  team.sync();
  {  // element–element and element–wall candidates of this thread's elements, in (i, j) order
    std::vector<CandidatePair>& pairs = t == 0 ? candidates_ : rebuild_parts_[k].pairs;
    std::vector<LinearSlot>& lin = t == 0 ? linear_fresh_ : rebuild_parts_[k].lin;
    std::vector<FaceSlot>& face = t == 0 ? face_fresh_ : rebuild_parts_[k].face;
    pairs.clear();
    lin.clear();
    face.clear();
    if (rebuild_cells_) search_.collect(e, skin_, rebuild_first_[k], rebuild_first_[k + 1], pairs);
    wall_candidates(rebuild_first_[k], rebuild_first_[k + 1], lin, face);
    // the positions of this rebuild, for the next rebuild test
    const auto b = static_cast<std::ptrdiff_t>(rebuild_first_[k]);
    const auto end = static_cast<std::ptrdiff_t>(rebuild_first_[k + 1]);
    std::copy(e.x.begin() + b, e.x.begin() + end, x_ref_.begin() + b);
    std::copy(e.y.begin() + b, e.y.begin() + end, y_ref_.begin() + b);
  }
  team.sync();
  if (nt > 1) {  // join the parts in range order
    if (t == 0) {
      std::size_t np = candidates_.size(), nl = linear_fresh_.size(), nf = face_fresh_.size();
      for (std::size_t q = 1; q < static_cast<std::size_t>(nt); ++q) {
        RebuildPart& p = rebuild_parts_[q];
        p.at_pairs = np, p.at_lin = nl, p.at_face = nf;
        np += p.pairs.size(), nl += p.lin.size(), nf += p.face.size();
      }
      candidates_.resize(np);
      linear_fresh_.resize(nl);
      face_fresh_.resize(nf);
    }
    team.sync();
    if (t > 0) {
      const RebuildPart& p = rebuild_parts_[k];
      std::copy(p.pairs.begin(), p.pairs.end(), candidates_.begin() + static_cast<std::ptrdiff_t>(p.at_pairs));
      std::copy(p.lin.begin(), p.lin.end(), linear_fresh_.begin() + static_cast<std::ptrdiff_t>(p.at_lin));
      std::copy(p.face.begin(), p.face.end(), face_fresh_.begin() + static_cast<std::ptrdiff_t>(p.at_face));
    }
    team.sync();
  }
  // A fresh slot for every candidate of the law's kind (routed by the pair's law).
  auto fresh_pair = [this, &e](LawKind kind) {
    return [this, &e, kind](const CandidatePair& p, auto& s) {
      const std::int32_t law = m_.law_index(e.material[p.i], e.material[p.j]);
      if (law < 0 || m_.laws[static_cast<std::size_t>(law)].kind != kind) return false;
      s = {};
      s.i = p.i, s.j = p.j, s.law = law;
      return true;
    };
  };
  const int other = nt > 1 ? 1 : 0;
  if (nt == 1) {
    merge(PairColumns{linear_pairs_}, candidates_, fresh_pair(LawKind::linear));
    merge(SlotVector<FaceSlot>{face_pairs_}, candidates_, fresh_pair(LawKind::face));
  } else {  // the same lists, merged by element ranges
    merge_on(team, PairColumns{linear_pairs_}, candidates_, fresh_pair(LawKind::linear), rebuild_first_, linear_plan_,
             rebuild_parts_[k].linear_aside);
    const bool faces = !face_pairs_.empty() || std::any_of(m_.laws.begin(), m_.laws.end(), [](const PairLaw& l) {
      return l.kind == LawKind::face;
    });
    if (faces)  // (without a face law the list stays empty: no places to count)
      merge_on(team, SlotVector<FaceSlot>{face_pairs_}, candidates_, fresh_pair(LawKind::face), rebuild_first_,
               face_plan_, rebuild_parts_[k].face_aside);
  }
  if (t == other) {  // the wall slots (few) and the walls' references of the next rebuild test
    auto copy = [](const auto& fresh, auto& s) {
      s = fresh;
      return true;
    };
    merge(SlotVector<LinearSlot>{linear_walls_}, linear_fresh_, copy);
    merge(SlotVector<FaceSlot>{face_walls_}, face_fresh_, copy);
    wall_ref_.resize(m_.walls.size());
    for (std::size_t w = 0; w < m_.walls.size(); ++w) wall_ref_[w] = m_.walls[w].a;
  }
  team.sync();
  // The contact index (as index_contacts()): its linear row on thread 0; the rest of it, and the shares,
  // on thread 1 (or 0).
  // Too many slots for the index: every thread sees the same sizes and leaves; the caller throws after the job
  // (an exception inside a job would leave the other threads at a barrier).
  const std::size_t others = face_pairs_.size() + linear_walls_.size() + face_walls_.size();
  if (!ContactIndex::fits(linear_pairs_.size(), others)) {
    if (nt == 1) ContactIndex::check(linear_pairs_.size(), others);
    return false;
  }
  if (t == 0) index_.build_linear(e.size(), linear_pairs_.pair);
  if (t == other) index_others();
  team.sync();
  return true;
}

void Simulation::index_contacts() {
  ContactIndex::check(linear_pairs_.size(), face_pairs_.size() + linear_walls_.size() + face_walls_.size());
  index_.build_linear(m_.elements.size(), linear_pairs_.pair);
  index_others();
}

void Simulation::index_others() {
  index_.build_other(m_.elements.size(), face_pairs_, linear_walls_, face_walls_);
  face_push_.resize(face_pairs_.size());
  face_wall_push_.resize(face_walls_.size());
  shares_.threads = 0;
  if (threads_used() > 1) share_work(threads_used());
}

WorkerThreads& Simulation::workers(int threads) const {
  if (!workers_.pool || workers_.pool->size() != threads) workers_.pool = std::make_unique<WorkerThreads>(threads);
  return *workers_.pool;
}

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
  if (most > (1.0 + kBalanceTolerance) * mean) {
    balance_threads(busy_seconds_);
  } else {
    busy_.assign(busy_.size(), ThreadClock{});
    balance_steps_ = 0;
  }
}

void Simulation::sweep_scatter(double inv_dt) {
  sweep_linear_pairs<false>(inv_dt, 0, linear_pairs_.size());
  sweep_face_pairs<false>(inv_dt, 0, face_pairs_.size());
  sweep_linear_walls<false>(inv_dt, 0, linear_walls_.size());
  sweep_face_walls<false>(inv_dt, 0, face_walls_.size());
}

void Simulation::sweep_share(double inv_dt, std::size_t k, bool from_weight) {
  const std::size_t b = shares_.first[k], end = shares_.first[k + 1];
  if (from_weight) {  // (K15): gravity; the shared elements start from it in gather_forces
    Elements& e = m_.elements;
    weight(e.fx.data() + b, e.fy.data() + b, e.mass.data() + b, m_.gravity, end - b);
    std::fill(e.moment.begin() + static_cast<std::ptrdiff_t>(b), e.moment.begin() + static_cast<std::ptrdiff_t>(end), 0.0);
  }
  const auto& sl = shares_.slots;
  sweep_linear_pairs<true>(inv_dt, sl[0][k], sl[0][k + 1]);
  sweep_face_pairs<true>(inv_dt, sl[1][k], sl[1][k + 1]);
  sweep_linear_walls<true>(inv_dt, sl[2][k], sl[2][k + 1]);
  sweep_face_walls<true>(inv_dt, sl[3][k], sl[3][k + 1]);
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

/// The walls' reactions, in slot order (linear wall slots, then face wall slots), as the sweeps summed them.
void Simulation::sum_wall_forces() {
  for (const LinearSlot& s : linear_walls_) {
    if (!s.touching) continue;
    Wall& w = m_.walls[s.j];
    const double fx = -s.f.fn * s.nx + s.f.fs * s.ny, fy = -s.f.fn * s.ny - s.f.fs * s.nx;
    w.force.x -= fx;
    w.force.y -= fy;
  }
  for (std::size_t n = 0; n < face_walls_.size(); ++n) {
    const ElementPush& p = face_wall_push_[n];
    if (!p.applied) continue;
    Wall& w = m_.walls[face_walls_[n].j];
    w.force.x -= p.fx;
    w.force.y -= p.fy;
  }
}

Dashpots linear_dashpots(const PairLaw& law, double mass_i, double mass_j) {
  Dashpots d;
  if (law.damping_from_ratio) {
    // (K20, K25): η_n = 2ζ√(m K_n), η_s = η_n √(K_s/K_n); m per the mass basis.
    double m = 0.0;
    if (mass_j <= 0.0) m = mass_i;  // wall
    else m = law.mass_basis == MassBasis::reduced ? reduced_mass(mass_i, mass_j) : 0.5 * (mass_i + mass_j);
    d.eta_n = 2.0 * law.damping_ratio * std::sqrt(m * law.linear.kn);
    d.eta_s = law.linear.kn > 0.0 ? d.eta_n * std::sqrt(law.linear.ks / law.linear.kn) : 0.0;
  } else {
    d.eta_n = law.eta_n;
    d.eta_s = law.eta_s;
  }
  return d;
}

void Simulation::start_linear(std::int32_t law_index, double overlap, double du_n, double du_s, double mass_i,
                              double mass_j, double& eta_n, double& eta_s, LinearContactHistory& h) const {
  const PairLaw& law = m_.laws[static_cast<std::size_t>(law_index)];
  h = {};
  const Dashpots d = linear_dashpots(law, mass_i, mass_j);
  eta_n = d.eta_n;
  eta_s = d.eta_s;
  // Contacts present at the start, or formed with the overlap onset, start from the geometric
  // overlap: e_n = K_n δ after this step's increment is added (docs/references.md §1.4: e_0 = K x(0)).
  if (step_ == 0 || law.onset == Onset::overlap) {
    h.en = law.linear.kn * (overlap - du_n);  // the face law's start, operation for operation (M18)
    // The first increment of a plain start is the virtual v(0)Δt (docs/references.md §1.4): it drives the
    // dashpots, not the shear spring. A static preload is a real deformation: it loads the spring.
    h.es = preloading_ ? 0.0 : -law.linear.ks * du_s;
  }
}

namespace {
// One overlapping candidate's geometry (K3, K5), made one contact ahead of its law (below).
struct PairGeometry {
  std::size_t k;
  std::uint32_t i, j;
  double overlap, nx, ny, du_n, du_s;
};
}  // namespace

// The sweep runs in two stages one overlapping candidate apart: while the law and the scatter of one
// contact run, the next overlapping candidate's distance, square root and normal are already under way
// (they depend on nothing the law writes). Each stage performs the operations of the plain loop, and the
// laws run and add their forces in slot order: the same results bit for bit.
template <bool Shares>
void Simulation::sweep_linear_pairs(double inv_dt, std::size_t b, std::size_t end) {
  Elements& e = m_.elements;
  const double* const x = e.x.data();
  const double* const y = e.y.data();
  const double* const radius = e.radius.data();
  const std::uint8_t* const active = e.active.data();
  const double* const dx = e.dx.data();
  const double* const dy = e.dy.data();
  const double* const dphi = e.dphi.data();
  double* const fx_e = e.fx.data();  // local pointers: no reloads after stores
  double* const fy_e = e.fy.data();
  double* const moment = e.moment.data();
  [[maybe_unused]] const std::uint8_t* const shared = shares_.shared.data();
  const PairLaw* const laws = m_.laws.data();
  const SlotPair* const pairs = linear_pairs_.pair.data();  // read for every candidate (hot)
  std::uint8_t* const touching = linear_pairs_.touching.data();
  const std::int32_t* const law_of = linear_pairs_.law.data();  // read for touching pairs only (cold)
  LinearContactState* const state = linear_pairs_.state.data();
  LinearContactResultant* const resultant = linear_pairs_.resultant.data();
  const bool keep = keep_forces_;
  // Stage 1: from slot k on, ends the contacts of the candidates that do not overlap (K3) and makes the
  // geometry of the first one that does; false at the end of the range.
  auto next_overlap = [&](std::size_t& k, PairGeometry& g) {
    for (; k < end; ++k) {
      const std::uint32_t i = pairs[k].i, j = pairs[k].j;
      const double ddx = x[j] - x[i], ddy = y[j] - y[i];
      const double rs = radius[i] + radius[j];
      const double r2 = ddx * ddx + ddy * ddy;
      if (r2 > rs * rs || !active[i] || !active[j]) {  // (K3): not touching
        if (touching[k]) linear_pairs_.reset(k);
        continue;
      }
      const double dist = std::sqrt(r2);
      g.nx = ddx / dist, g.ny = ddy / dist;  // cos α, sin α (K3): from i towards j
      const double ux = dx[i] - dx[j], uy = dy[i] - dy[j];
      g.du_n = ux * g.nx + uy * g.ny;  // (K5)
      g.du_s = -ux * g.ny + uy * g.nx + radius[i] * dphi[i] + radius[j] * dphi[j];
      g.overlap = rs - dist;
      g.k = k++, g.i = i, g.j = j;
      return true;
    }
    return false;
  };
  std::size_t k = b;
  PairGeometry g{}, g_next{};
  bool more = next_overlap(k, g);
  while (more) {
    more = next_overlap(k, g_next);
    // Stage 2: the law of contact g (K6–K14) and its forces (K15).
    const std::size_t c = g.k;
    const std::uint32_t i = g.i, j = g.j;
    LinearContactState& s = state[c];
    const std::int32_t law_k = law_of[c];
    if (!touching[c]) {
      touching[c] = 1;
      start_linear(law_k, g.overlap, g.du_n, g.du_s, e.mass[i], e.mass[j], s.eta_n, s.eta_s, s.h);
    }
    const PairLaw& law = laws[static_cast<std::size_t>(law_k)];
    const ContactForce f = linear_contact_force(law.linear, s.eta_n, s.eta_s, g.du_n, g.du_s, inv_dt, s.h);
    const double nx = g.nx, ny = g.ny;
    g = g_next;
    if (f.opened) {  // (K8): the contact ends; if the cores still overlap it forms anew next step
      linear_pairs_.reset(c);
      continue;
    }
    // for outputs, if this step keeps them, and for gather_forces if an element is shared
    if (keep || (Shares && (shared[i] || shared[j]))) resultant[c] = {f.fn, f.fs, nx, ny};
    // (K15): force on i is −f_n n − f_s t, t = (−sin α, cos α); on j the opposite.
    const double fx = -f.fn * nx + f.fs * ny, fy = -f.fn * ny - f.fs * nx;
    if constexpr (!Shares) {
      fx_e[i] += fx;
      fy_e[i] += fy;
      fx_e[j] -= fx;
      fy_e[j] -= fy;
      moment[i] -= radius[i] * f.fs;
      moment[j] -= radius[j] * f.fs;
    } else {
      if (!shared[i]) {
        fx_e[i] += fx;
        fy_e[i] += fy;
        moment[i] -= radius[i] * f.fs;
      }
      if (!shared[j]) {
        fx_e[j] -= fx;
        fy_e[j] -= fy;
        moment[j] -= radius[j] * f.fs;
      }
    }
  }
}

void Simulation::open_wall(std::uint32_t w) {
  m_.walls[w].open = true;
  std::erase_if(linear_walls_, [w](const LinearSlot& s) { return s.j == w; });
  std::erase_if(face_walls_, [w](const FaceSlot& s) { return s.j == w; });
  tested_step_ = -1;
  index_contacts();  // the slot lists changed
}

template <bool Shares>
void Simulation::sweep_linear_walls(double inv_dt, std::size_t b, std::size_t end) {
  Elements& e = m_.elements;
  for (std::size_t k = b; k < end; ++k) {
    LinearSlot& s = linear_walls_[k];
    const std::uint32_t i = s.i;
    const Wall& w = m_.walls[s.j];
    const Vec2 c{e.x[i], e.y[i]};
    const Vec2 d = closest_point(w, c) - c;
    const double r2 = dot(d, d), r = e.radius[i];
    if (r2 > r * r || !e.active[i] || r2 == 0.0) {
      if (s.touching) reset_slot(s);
      continue;
    }
    const double dist = std::sqrt(r2);
    const double nx = d.x / dist, ny = d.y / dist;  // from the element towards the wall
    const double ux = e.dx[i] - w.increment.x, uy = e.dy[i] - w.increment.y;
    const double du_n = ux * nx + uy * ny;  // (K5) with the wall as element j, r_j = 0
    const double du_s = -ux * ny + uy * nx + r * e.dphi[i];
    if (!s.touching) {
      s.touching = 1;
      start_linear(s.law, r - dist, du_n, du_s, e.mass[i], 0.0, s.eta_n, s.eta_s, s.h);
    }
    const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
    const ContactForce f = linear_contact_force(law.linear, s.eta_n, s.eta_s, du_n, du_s, inv_dt, s.h);
    if (f.opened) {
      reset_slot(s);
      continue;
    }
    s.f = f;  // sum_wall_forces adds it, and gather_forces if the element is shared
    s.nx = nx;
    s.ny = ny;
    if (!Shares || !shares_.shared[i]) {
      e.fx[i] += -f.fn * nx + f.fs * ny;
      e.fy[i] += -f.fn * ny - f.fs * nx;
      e.moment[i] -= r * f.fs;
    }
  }
}

FaceConstants face_constants(const PairLaw& law, double r_i, double r_j, double m_eff, double thickness) {
  FaceConstants c;
  const int n = law.face.segments;
  c.half_length = r_j > 0.0 ? std::min(r_i, r_j) : r_i;
  const double area = 2.0 * c.half_length * thickness;  // (M1): A = 2 r l
  c.segment_area = area / n;
  if (law.face_modulus) {  // (M6): K = k A / ((r1 + r2) N); for a wall (r1 + r2) → r2 (M19)
    c.kn = law.face_kn * area / ((r_i + r_j) * n);
    c.ks = law.face_ks * area / ((r_i + r_j) * n);
  } else {
    c.kn = law.face_kn;
    c.ks = law.face_ks;
  }
  if (law.damping_from_ratio) {
    c.eta_n = 2.0 * law.damping_ratio * std::sqrt(c.kn * n * m_eff) / n;  // (M7.3)
    c.eta_s = c.kn > 0.0 ? c.eta_n * std::sqrt(c.ks / c.kn) : 0.0;         // (M7.4)
  } else {
    c.eta_n = law.eta_n;
    c.eta_s = law.eta_s;
  }
  return c;
}

namespace {
// The slot keeps the step's resultants (outputs), stored field by field: a whole-struct copy makes g++
// build the FaceForce on the stack and move it with wide loads over its narrow stores (a store-forwarding
// stall per face and step, measured in bench/journal.md).
inline void keep_forces(FaceForce& to, const FaceForce& f) {
  to.p = f.p;
  to.q = f.q;
  to.p_moment = f.p_moment;
  to.links = f.links;
  to.any_tensile = f.any_tensile;
}
}  // namespace

template <bool Shares>
void Simulation::sweep_face_pairs(double inv_dt, std::size_t b, std::size_t end) {
  Elements& e = m_.elements;
  for (std::size_t n = b; n < end; ++n) {
    FaceSlot& s = face_pairs_[n];
    ElementPush& push = face_push_[n];
    push.applied = 0;
    const std::uint32_t i = s.i, j = s.j;
    if (!e.active[i] || !e.active[j]) {
      if (s.touching) reset_slot(s);
      continue;
    }
    const double ddx = e.x[j] - e.x[i], ddy = e.y[j] - e.y[i];
    const double rs = e.radius[i] + e.radius[j];
    const double r2 = ddx * ddx + ddy * ddy;
    const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
    // Faces bonded at the start touch by construction (a generated lattice): accept them up to
    // round-off of the generated positions.
    const bool bond = step_ == 0 && (law.bond_at_start || (e.group[i] >= 0 && e.group[i] == e.group[j]));
    const double touch = bond ? rs * (1.0 + 1e-9) : rs;
    if (!s.touching && r2 > touch * touch) continue;  // not touching → touching when D ≤ r1 + r2
    const double dist = std::sqrt(r2);
    const double nx = ddx / dist, ny = ddy / dist;
    const double ux = e.dx[i] - e.dx[j], uy = e.dy[i] - e.dy[j];
    FaceKinematics k;
    k.du_projected = ux * nx + uy * ny;
    k.dv_translation = -ux * ny + uy * nx;
    const double ox = ddx - (e.dx[j] - e.dx[i]), oy = ddy - (e.dy[j] - e.dy[i]);  // centre line before the step
    k.du_exact = std::hypot(ox, oy) - dist;
    k.dbeta = std::atan2(ox * ddy - oy * ddx, ox * ddx + oy * ddy);
    k.dphi1 = e.dphi[i];
    k.dphi2 = e.dphi[j];
    k.r1 = e.radius[i];
    k.r2 = e.radius[j];
    if (!s.touching) {
      s.touching = 1;
      s.c = face_constants(law, e.radius[i], e.radius[j], reduced_mass(e.mass[i], e.mass[j]), m_.thickness);
      const bool bonded = bond;
      const bool geometric = step_ == 0 || law.onset == Onset::overlap;
      const double u0 = geometric ? (rs - dist) - k.du_projected : 0.0;
      start_face(law.face, s.c, u0, bonded, geometric, s.h);
      if (preloading_) s.h.geometric_start = 0;  // a static preload loads the shear springs
    }
    const FaceForce f = face_contact_force(law.face, s.c, k, inv_dt, s.h);
    keep_forces(s.f, f);
    s.nx = nx;
    s.ny = ny;
    if (f.links == 0) s.touching = 0;  // touching → not touching when no link remains
    push.fx = -f.p * nx + f.q * ny;  // (M12): on i; on j the opposite
    push.fy = -f.p * ny - f.q * nx;
    push.mi = -e.radius[i] * f.q + f.p_moment;
    push.mj = -e.radius[j] * f.q - f.p_moment;
    push.applied = 1;
    if (!Shares || !shares_.shared[i]) {
      e.fx[i] += push.fx;
      e.fy[i] += push.fy;
      e.moment[i] += push.mi;
    }
    if (!Shares || !shares_.shared[j]) {
      e.fx[j] -= push.fx;
      e.fy[j] -= push.fy;
      e.moment[j] += push.mj;
    }
  }
}

template <bool Shares>
void Simulation::sweep_face_walls(double inv_dt, std::size_t b, std::size_t end) {
  Elements& e = m_.elements;
  for (std::size_t n = b; n < end; ++n) {
    FaceSlot& s = face_walls_[n];
    ElementPush& push = face_wall_push_[n];
    push.applied = 0;
    const std::uint32_t i = s.i;
    const Wall& w = m_.walls[s.j];
    if (!e.active[i]) {
      if (s.touching) reset_slot(s);
      continue;
    }
    const Vec2 c{e.x[i], e.y[i]};
    const Vec2 d = closest_point(w, c) - c;
    const double r2 = dot(d, d), r = e.radius[i];
    const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
    const double touch = (step_ == 0 && law.bond_at_start) ? r * (1.0 + 1e-9) : r;
    if ((!s.touching && r2 > touch * touch) || r2 == 0.0) continue;
    const double dist = std::sqrt(r2);
    const double nx = d.x / dist, ny = d.y / dist;
    const double ux = e.dx[i] - w.increment.x, uy = e.dy[i] - w.increment.y;
    FaceKinematics k;  // (M19): the wall replaces one element; its frame does not turn
    k.du_projected = ux * nx + uy * ny;
    k.du_exact = k.du_projected;
    k.dv_translation = -ux * ny + uy * nx;
    k.dv_frame = k.dv_translation;
    k.dphi1 = e.dphi[i];
    k.r1 = r;
    if (!s.touching) {
      s.touching = 1;
      s.c = face_constants(law, r, 0.0, e.mass[i], m_.thickness);
      const bool geometric = step_ == 0 || law.onset == Onset::overlap;
      const double u0 = geometric ? (r - dist) - k.du_projected : 0.0;
      start_face(law.face, s.c, u0, step_ == 0 && law.bond_at_start, geometric, s.h);
      if (preloading_) s.h.geometric_start = 0;
    }
    const FaceForce f = face_contact_force(law.face, s.c, k, inv_dt, s.h);
    keep_forces(s.f, f);
    s.nx = nx;
    s.ny = ny;
    if (f.links == 0) s.touching = 0;
    push.fx = -f.p * nx + f.q * ny;
    push.fy = -f.p * ny - f.q * nx;
    push.mi = -r * f.q + f.p_moment;
    push.applied = 1;
    if (!Shares || !shares_.shared[i]) {
      e.fx[i] += push.fx;
      e.fy[i] += push.fy;
      e.moment[i] += push.mi;
    }
  }
}

int Simulation::threads_used() const {
  const std::size_t most = std::max<std::size_t>(1, m_.elements.size() / min_per_thread_);
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads_), most));
}

Simulation::Freedom Simulation::freedom(std::size_t b, std::size_t end) const {
  // The usual cases, every element free and active (or removed from the run): the same operations per
  // element, in branch-free loops that the compiler vectorises (the lanes round exactly as the scalar
  // code; no FMA contraction). Each thread asks it of its own elements (inside the step's job, not
  // serially before it).
  const Elements& e = m_.elements;
  std::uint8_t all = 1, active_free = 1;
  const std::uint8_t* __restrict act = e.active.data();
  const Motion* __restrict mot = e.motion.data();
  for (std::size_t i = b; i < end; ++i) {
    all &= (act[i] != 0) & (mot[i] == Motion::free);
    active_free &= (act[i] == 0) | (mot[i] == Motion::free);
  }
  return all ? Freedom::all_free : active_free ? Freedom::active_free : Freedom::general;
}

double Simulation::velocity_dt() const {
  // docs/references.md §1.4: a staggered start takes half a velocity step first, v_0 = v(Δt/2).
  const double dt = m_.numerics.dt;
  return (step_ == 0 && m_.numerics.velocity_start == VelocityStart::staggered) ? 0.5 * dt : dt;
}

Simulation::Overstep Simulation::integrate_range(std::size_t b, std::size_t end, double dt_v, Freedom freedom,
                                                 double limit2, double limit2_next, RangeTests& tests) {
  Elements& e = m_.elements;
  const double dt = m_.numerics.dt;
  const bool k19 = m_.numerics.integrator == Integrator::k19;
  if (limit2_next >= 0.0) {  // right after the integration, while the positions are in the caches
    const Overstep o = integrate_range(b, end, dt_v, freedom, limit2, -1.0, tests);
    // No element of the range can have moved √limit2_next from its reference position if the travel bound
    // of the steps before plus this step's largest increment stays below it: the exact test would say no,
    // so it is not made (travel_ in simulation.hpp). Otherwise (or if the bound is unknown: ∞) it is.
    tests.skipped = travel_ + std::sqrt(tests.max_d2) < kTravelMargin * std::sqrt(limit2_next);
    tests.displaced = tests.skipped ? 0 : any_displaced(e.x.data() + b, e.y.data() + b, x_ref_.data() + b,
                                                        y_ref_.data() + b, limit2_next, end - b);
    return o;
  }
  if (freedom != Freedom::general) {
    const bool masked = freedom == Freedom::active_free;
    auto all = k19 ? (masked ? integrate_free<true, true> : integrate_free<true, false>)
                   : (masked ? integrate_free<false, true> : integrate_free<false, false>);
    const bool may = all(e.vx.data() + b, e.vy.data() + b, e.omega.data() + b, e.fx.data() + b, e.fy.data() + b,
                         e.moment.data() + b, e.inv_mass.data() + b, e.inv_inertia.data() + b, e.dx.data() + b,
                         e.dy.data() + b, e.dphi.data() + b, e.x.data() + b, e.y.data() + b, e.phi.data() + b,
                         e.radius.data() + b, dt_v, dt, prefilter_limit(limit2), end - b, e.active.data() + b, tests.max_d2);
    return may ? find_overstep(e, b, end, limit2) : Overstep{};
  }
  for (std::size_t i = b; i < end; ++i) {
    if (!e.active[i]) continue;
    switch (e.motion[i]) {
      case Motion::free:  // (K17): v_t = v_{t−Δt} + a_t Δt
        e.vx[i] += dt_v * e.fx[i] * e.inv_mass[i];
        e.vy[i] += dt_v * e.fy[i] * e.inv_mass[i];
        e.omega[i] += dt_v * e.moment[i] * e.inv_inertia[i];
        break;
      case Motion::fixed:
        e.vx[i] = e.vy[i] = e.omega[i] = 0.0;
        break;
      case Motion::driven: {
        const Vec2 v = m_.drives[static_cast<std::size_t>(e.drive[i])].at(time_ + 0.5 * dt);
        e.vx[i] = v.x;
        e.vy[i] = v.y;
        e.omega[i] = 0.0;
        break;
      }
    }
    if (k19 && e.motion[i] == Motion::free) {  // (K19): averaged increment
      e.dx[i] = 0.5 * (e.dx[i] + e.vx[i] * dt);
      e.dy[i] = 0.5 * (e.dy[i] + e.vy[i] * dt);
      e.dphi[i] = 0.5 * (e.dphi[i] + e.omega[i] * dt);
    } else {  // (K18)
      e.dx[i] = e.vx[i] * dt;
      e.dy[i] = e.vy[i] * dt;
      e.dphi[i] = e.omega[i] * dt;
    }
    e.x[i] += e.dx[i];
    e.y[i] += e.dy[i];
    e.phi[i] += e.dphi[i];
  }
  const bool may = may_overstep(e.dx.data() + b, e.dy.data() + b, e.radius.data() + b, prefilter_limit(limit2), end - b, tests.max_d2);
  return may ? find_overstep(e, b, end, limit2) : Overstep{};
}

void Simulation::move_walls() {
  const double dt = m_.numerics.dt;
  for (Wall& w : m_.walls) {
    w.increment = w.drive >= 0 ? m_.drives[static_cast<std::size_t>(w.drive)].at(time_ + 0.5 * dt) * dt : Vec2{};
    w.a = w.a + w.increment;
    w.b = w.b + w.increment;
  }
}

double Simulation::next_rebuild_limit2() const {
  if (m_.base_plate.enabled) return -1.0;  // integrated after base friction, in a second pass
  for (const Wall& w : m_.walls)
    if (w.drive >= 0) return -1.0;  // the limit of the next step depends on where the walls move to
  return rebuild_limit2();          // static walls: the limit after this step's rebuild, if any, holds
}

void Simulation::step() {
  const int nt = threads_used();
  // The rebuild test of this step (needs_rebuild) was made by the last step's integration, element by
  // element in the same pass, if nothing changed the state since (tested_step_ == step_).
  const bool tested = step_ > 0 && tested_step_ == step_;
  if (tested) {
    std::uint8_t any = 0;
    for (std::uint8_t d : displaced_) any |= d;
    if (any) rebuild();
  }
  tested_step_ = -1;
  if (nt == 1 && step_ > 0 && !tested && needs_rebuild()) rebuild();  // on several threads: inside the job below
  for (Wall& w : m_.walls) w.force = {};
  const double inv_dt = 1.0 / m_.numerics.dt;
  const std::size_t n = m_.elements.size();
  // Base friction (M21) acts between the contact forces and the integration, on one thread; without
  // it each thread integrates the elements it has just summed.
  const bool plate = m_.base_plate.enabled;
  const double dt_v = velocity_dt();
  const double limit2_step = m_.numerics.max_step_fraction * m_.numerics.max_step_fraction;
  const double limit2_next = plate ? -1.0 : next_rebuild_limit2();  // < 0: the next step tests by itself
  if (nt == 1) {  // each slot adds its forces at once, in slot order
    Elements& e = m_.elements;
    weight(e.fx.data(), e.fy.data(), e.mass.data(), m_.gravity, n);  // (K15): gravity
    std::fill(e.moment.begin(), e.moment.end(), 0.0);
    sweep_scatter(inv_dt);
    sum_wall_forces();
    if (!plate) {
      range_tests_.assign(1, RangeTests{});
      oversteps_.assign(1, integrate_range(0, n, dt_v, freedom(0, n), limit2_step, limit2_next, range_tests_[0]));
      displaced_.assign(1, range_tests_[0].displaced);
    }
  } else {  // the same sums, shared as thread_shares.hpp says
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
      sweep_share(inv_dt, k, true);  // every contact law (K5–K14, M3–M12); (K15) on private elements
      pool.signal_done(t);
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
      pool.wait_earlier(t);  // their sweeps no longer read the shared elements, and their slots are complete
      const double c2 = timed ? thread_seconds() : 0.0;
      gather_shared(k, true);  // (K15): m g plus the contacts of the shared elements, in the fixed order
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
    };
    pool.run(body);
    if (index_failed)
      ContactIndex::check(linear_pairs_.size(), face_pairs_.size() + linear_walls_.size() + face_walls_.size());
    balance_if_uneven();  // the next step's shares (results do not depend on them)
  }
  if (plate) {
    travel_ = kTravelUnknown;  // (the next step tests by itself)
    advance_base_plate();
    RangeTests unused;
    if (nt == 1) {
      oversteps_.assign(1, integrate_range(0, n, dt_v, freedom(0, n), limit2_step, -1.0, unused));
    } else {
      oversteps_.assign(static_cast<std::size_t>(nt), Overstep{});
      auto body = [&](int t) {
        const std::size_t k = static_cast<std::size_t>(t);
        RangeTests none;
        oversteps_[k] = integrate_range(shares_.first[k], shares_.first[k + 1], dt_v, freedom(shares_.first[k], shares_.first[k + 1]), limit2_step, -1.0, none);
      };
      workers(nt).run(body);
    }
  } else {  // every element moved by at most the largest increment of the step's ranges
    double most = 0.0;
    for (const RangeTests& r : range_tests_) {
      most = r.max_d2 > most ? r.max_d2 : most;
      rebuild_tests_skipped_ += r.skipped;
    }
    // x += Δx rounds each coordinate by up to half an ulp, ≤ 2⁻⁵³ |x|: the position moved by at most
    // |Δx| + 2⁻⁵²·max(|x|, |y|), and no active element's coordinate exceeds the extent at the last
    // rebuild plus its travel since.
    const double step = std::sqrt(most);
    travel_ += step + kRoundoff * (search_.extent() + travel_ + step);
  }
  move_walls();
  if (limit2_next >= 0.0) tested_step_ = step_ + 1;
  ++step_;
  forces_step_ = keep_forces_ ? step_ : -1;
  time_ = static_cast<double>(step_) * m_.numerics.dt;
}

Simulation::Overstep Simulation::overstep() const {
  Overstep worst;
  for (const Overstep& o : oversteps_) take_worse(worst, o);  // shares in element order
  return worst;
}

void Simulation::advance_base_plate() {
  // (M21) on the velocities of the array, v_{k−1}: the velocity over [t − Δt, t], so the plate's is
  // taken at t − Δt/2; then the plate moves by its velocity over [t, t + Δt] (as a driven wall does).
  const double dt = m_.numerics.dt;
  add_base_friction(m_.elements, m_.base_plate, plate_velocity(m_.base_plate, m_.drives, time_ - 0.5 * dt));
  const Vec2 d = plate_velocity(m_.base_plate, m_.drives, time_ + 0.5 * dt) * dt;
  plate_travel_.displacement = plate_travel_.displacement + d;
  plate_travel_.travel += norm(d);
}

Energies Simulation::energies() const {
  // Summed in chunks of kEnergyChunk elements, and of kEnergyChunk slots of the slot lists taken one after
  // another (linear pairs, linear walls, face pairs, face walls): each chunk in order from zero, the chunk
  // sums in chunk order. The chunks do not depend on the threads, so neither does any bit of the sums; with
  // one chunk (up to kEnergyChunk elements and slots) the sums are those of a single pass in order.
  const Elements& e = m_.elements;
  const LinearPairSlots& lp = linear_pairs_;
  const std::size_t n = e.size();
  const std::size_t n_lp = lp.size(), n_lw = linear_walls_.size(), n_fp = face_pairs_.size(), n_fw = face_walls_.size();
  const std::size_t slots = n_lp + n_lw + n_fp + n_fw;
  const std::size_t element_chunks = (n + kEnergyChunk - 1) / kEnergyChunk;
  const std::size_t chunks = element_chunks + (slots + kEnergyChunk - 1) / kEnergyChunk;
  energy_chunks_.resize(chunks);
  auto sum_elements = [&](std::size_t b, std::size_t end, Energies& en) {
    for (std::size_t i = b; i < end; ++i) {
      if (!e.active[i]) continue;
      en.kinetic += 0.5 * e.mass[i] * (e.vx[i] * e.vx[i] + e.vy[i] * e.vy[i]) +
                    0.5 * e.inertia[i] * e.omega[i] * e.omega[i];
      en.potential -= e.mass[i] * (m_.gravity.x * e.x[i] + m_.gravity.y * e.y[i]);
    }
  };
  auto sum_slots = [&](std::size_t b, std::size_t end, Energies& en) {  // slots [b, end) of the lists in turn
    auto lin = [&](std::uint8_t touching, std::int32_t law, const LinearContactHistory& h) {
      if (!touching) return;
      const LinearSpringDashpot& l = m_.laws[static_cast<std::size_t>(law)].linear;
      if (l.kn > 0.0) en.elastic += 0.5 * h.en * h.en / l.kn;
      if (l.ks > 0.0) en.elastic += 0.5 * h.es * h.es / l.ks;
    };
    auto face = [&](const FaceSlot& s) {
      if (!s.touching) return;
      const int segments = m_.laws[static_cast<std::size_t>(s.law)].face.segments;
      for (int k = 0; k < segments; ++k) {
        const SegmentState& g = s.h.seg[static_cast<std::size_t>(k)];
        if (!g.linked) continue;
        if (s.c.kn > 0.0) en.elastic += 0.5 * g.pe * g.pe / s.c.kn;
        if (s.c.ks > 0.0) en.elastic += 0.5 * g.qe * g.qe / s.c.ks;
      }
    };
    std::size_t at = 0;  // where the list starts in the sequence
    for (std::size_t k = std::max(b, at); k < std::min(end, at + n_lp); ++k)
      lin(lp.touching[k - at], lp.law[k - at], lp.state[k - at].h);
    at += n_lp;
    for (std::size_t k = std::max(b, at); k < std::min(end, at + n_lw); ++k) {
      const LinearSlot& s = linear_walls_[k - at];
      lin(s.touching, s.law, s.h);
    }
    at += n_lw;
    for (std::size_t k = std::max(b, at); k < std::min(end, at + n_fp); ++k) face(face_pairs_[k - at]);
    at += n_fp;
    for (std::size_t k = std::max(b, at); k < std::min(end, at + n_fw); ++k) face(face_walls_[k - at]);
  };
  auto sum_chunks = [&](std::size_t c0, std::size_t c1) {
    for (std::size_t c = c0; c < c1; ++c) {
      Energies en;  // a local: the sums stay in registers
      if (c < element_chunks) {
        sum_elements(c * kEnergyChunk, std::min(n, (c + 1) * kEnergyChunk), en);
      } else {
        const std::size_t b = (c - element_chunks) * kEnergyChunk;
        sum_slots(b, std::min(slots, b + kEnergyChunk), en);
      }
      energy_chunks_[c] = en;
    }
  };
  const int nt = threads_used();
  if (nt == 1 || chunks < 2) {
    sum_chunks(0, chunks);
  } else {
    auto body = [&](int t) {  // a share of the element chunks and one of the slot chunks (they cost differently)
      const auto q = static_cast<std::size_t>(t), m = static_cast<std::size_t>(nt);
      const std::size_t ec = element_chunks, sc = chunks - element_chunks;
      sum_chunks(ec * q / m, ec * (q + 1) / m);
      sum_chunks(ec + sc * q / m, ec + sc * (q + 1) / m);
    };
    workers(nt).run(body);
  }
  Energies en;
  for (std::size_t c = 0; c < element_chunks; ++c) {
    en.kinetic += energy_chunks_[c].kinetic;
    en.potential += energy_chunks_[c].potential;
  }
  for (std::size_t c = element_chunks; c < chunks; ++c) en.elastic += energy_chunks_[c].elastic;
  return en;
}

void Simulation::require_contact_forces(const char* reader) const {
  if (!contact_forces_current())
    throw std::logic_error(fmt::format("Simulation::{}: the contact forces of step {} were not kept (keep_contact_forces)",
                                       reader, step_));
}

std::vector<ContactView> Simulation::contacts() const {
  require_contact_forces("contacts");
  std::vector<ContactView> out;
  const LinearPairSlots& lp = linear_pairs_;
  for (std::size_t k = 0; k < lp.size(); ++k) {
    if (!lp.touching[k]) continue;
    const LinearContactResultant& s = lp.resultant[k];
    out.push_back({lp.pair[k].i, lp.pair[k].j, false, s.nx, s.ny, s.fn, s.fs, 1});
  }
  for (const auto& s : face_pairs_)
    if (s.touching) out.push_back({s.i, s.j, false, s.nx, s.ny, s.f.p, s.f.q, s.f.links});
  for (const auto& s : linear_walls_)
    if (s.touching) out.push_back({s.i, s.j, true, s.nx, s.ny, s.f.fn, s.f.fs, 1});
  for (const auto& s : face_walls_)
    if (s.touching) out.push_back({s.i, s.j, true, s.nx, s.ny, s.f.p, s.f.q, s.f.links});
  return out;
}

Simulation::BandForce Simulation::wall_band_force(std::uint32_t w, double s0, double s1) const {
  const Wall& wall = m_.walls[w];
  const Vec2 ab = wall.b - wall.a;
  const double len = wall.kind == WallKind::segment ? norm(ab) : 0.0;
  const Vec2 along = len > 0.0 ? ab * (1.0 / len) : Vec2{0.0, 0.0};
  const Elements& e = m_.elements;
  BandForce out;
  auto add = [&](std::uint32_t i, std::uint32_t j, std::uint8_t touching, double nx, double ny, double fn, double fs) {
    if (j != w || !touching) return;
    const Vec2 n{nx, ny}, t{-ny, nx};                                   // t = n rotated by +90°
    const Vec2 point = closest_point(wall, Vec2{e.x[i], e.y[i]});       // where the element touches it
    const double s = len > 0.0 ? dot(point - wall.a, along) : 0.0;
    if (s < s0 || s >= s1) return;
    out.normal += fn;                                                   // compression positive
    out.tangential += dot(n * fn + t * fs, along);                      // force on the wall along a→b
    ++out.contacts;
  };
  for (const auto& c : linear_walls_) add(c.i, c.j, c.touching, c.nx, c.ny, c.f.fn, c.f.fs);
  for (const auto& c : face_walls_) add(c.i, c.j, c.touching, c.nx, c.ny, c.f.p, c.f.q);
  return out;
}

std::size_t Simulation::contact_count() const {
  std::size_t n = 0;
  for (std::uint8_t t : linear_pairs_.touching) n += t;
  for (const auto& s : face_pairs_) n += s.touching;
  for (const auto& s : linear_walls_) n += s.touching;
  for (const auto& s : face_walls_) n += s.touching;
  return n;
}

std::pair<double, std::size_t> Simulation::contact_force_sum() const {
  require_contact_forces("contact_force_sum");
  double sum = 0.0;
  std::size_t n = 0;
  auto add = [&](bool touching, double fn, double fs) {
    if (!touching || (fn == 0.0 && fs == 0.0)) return;
    sum += std::hypot(fn, fs);
    ++n;
  };
  for (std::size_t k = 0; k < linear_pairs_.size(); ++k)
    add(linear_pairs_.touching[k], linear_pairs_.resultant[k].fn, linear_pairs_.resultant[k].fs);
  for (const auto& s : linear_walls_) add(s.touching, s.f.fn, s.f.fs);
  for (const auto& s : face_pairs_) add(s.touching, s.f.p, s.f.q);
  for (const auto& s : face_walls_) add(s.touching, s.f.p, s.f.q);
  return {sum, n};
}

ContactView Simulation::contact(std::uint32_t i, std::uint32_t j, bool wall) const {
  if (!wall && j < i) std::swap(i, j);
  auto find = [&](const auto& slots) -> const auto* {
    auto it = std::lower_bound(slots.begin(), slots.end(), key(i, j),
                               [](const auto& s, std::uint64_t k) { return key(s.i, s.j) < k; });
    return (it != slots.end() && it->i == i && it->j == j && it->touching) ? &*it : nullptr;
  };
  if (wall) {
    if (const auto* s = find(linear_walls_)) return {i, j, wall, s->nx, s->ny, s->f.fn, s->f.fs, 1};
  } else {
    const std::vector<SlotPair>& p = linear_pairs_.pair;
    const auto it = std::lower_bound(p.begin(), p.end(), key(i, j),
                                     [](const SlotPair& s, std::uint64_t k) { return key(s.i, s.j) < k; });
    const std::size_t k = static_cast<std::size_t>(it - p.begin());
    if (it != p.end() && it->i == i && it->j == j && linear_pairs_.touching[k]) {
      require_contact_forces("contact");
      const LinearContactResultant& s = linear_pairs_.resultant[k];
      return {i, j, wall, s.nx, s.ny, s.fn, s.fs, 1};
    }
  }
  if (const auto* s = find(wall ? face_walls_ : face_pairs_))
    return {i, j, wall, s->nx, s->ny, s->f.p, s->f.q, s->f.links};
  return {i, j, wall, 0.0, 0.0, 0.0, 0.0, 0};
}

}  // namespace dem

// ---------------------------------------------------------------------------------------------------
// Time-step guard: the bound over every contact the case can form (stability.cpp).
namespace dem {

StabilityBound Simulation::stability_bound() const {
  return assembly_stability_bound(m_, registered_stability_terms(m_));
}

double Simulation::stability_limit() const { return stability_bound().limit; }

}  // namespace dem
