// Simulation's rebuild (simulation.hpp): the rebuild test and its limit, the candidates (neighbour search,
// wall candidates), the slot lists merged with their histories (merge, merge_on), the contact index.
#include "dem/core/simulation.hpp"

#include <algorithm>
#include <limits>

#include "dem/core/step_loops.hpp"

namespace dem {

using step_detail::any_displaced;
using step_detail::key;

namespace {

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
  Full load(std::size_t k) const {
    return {v.pair[k], v.touching[k], v.law[k], v.state[k], v.with_rolling ? v.rolling[k] : RollingState{}};
  }
  void store(std::size_t k, const Full& s) {
    v.pair[k] = s.pair, v.touching[k] = s.touching, v.law[k] = s.law, v.state[k] = s.state;
    if (v.with_rolling) v.rolling[k] = s.rolling;
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

}  // namespace

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
    if (!e.active[i] || e.shape[i] == Shape::polygon) continue;  // (polygons: rebuild_polygons)
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
  PhaseTimes* const phase = phases(t);
  const PhaseTimer whole(phase ? &phase->rebuild : nullptr);  // (step_timings.hpp)
  if (t == 0) {
    const PhaseTimer serial(phase ? &timings_.rebuild_serial : nullptr);
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
      if (polygons_ && (e.shape[p.i] == Shape::polygon || e.shape[p.j] == Shape::polygon)) return false;
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
  if (t == 0 && polygons_) rebuild_polygons();  // (one thread: threads_asked)
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

}  // namespace dem
