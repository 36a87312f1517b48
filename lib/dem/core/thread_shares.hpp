#pragma once
// How a step on several threads shares its work ("owner computes"; lib/README.md, "Determinism").
// Thread t owns the elements [first[t], first[t+1]) and computes the contact slots whose element i it
// owns: since every slot list is sorted by (i, j), a contiguous run of each list. A slot adds its forces
// at once to each of its elements that is *private* — an element all of whose slots its owner computes —
// so a private element receives its slots in slot order on one thread: the one-thread sweep's order. An
// element with a slot that another thread computes (a j whose partner i belongs to an earlier range, i.e.
// near the boundaries between the ranges) is *shared*: nobody adds to it while the slots are computed;
// once the threads before its owner have swept (only they compute slots with it as j), its owner sums its
// slots in the fixed order of the contact index (contact_index.hpp),
// which is again the one-thread order. So the forces are the same bit for bit for any number of threads.
// The ranges are balanced by an estimate of each element's work (its integration and the slots it
// computes), weighted by the CPU time each thread measured per unit of estimate on its range (balance():
// a touching contact costs several times a candidate that does not touch, and in a settle the touching
// ones sit in the rows that landed first, i.e. in one thread's range). Where the boundaries lie changes
// no result, only which thread computes what. Rebuilt with the contact index; a balance between rebuilds
// costs binary searches and one pass over the elements (prefix sums of the estimate, each element's lowest
// partner), not a pass over the slots: it runs between two steps, on one thread. Buffers are reused.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dem {

struct ThreadShares {
  int threads = 0;                                 // 0: not built
  std::vector<std::uint32_t> first;                // element ranges: threads + 1 boundaries
  std::array<std::vector<std::size_t>, 4> slots;   // per slot list (linear pairs, face pairs, linear
                                                   // walls, face walls): threads + 1 boundaries
  std::vector<std::uint8_t> shared;                // per element: 1 if summed after the sweeps
  std::vector<std::uint32_t> shared_start, shared_items;  // per thread, its shared elements (ascending)
  // per thread: its elements from here to the end of its range are all private (one past its last shared
  // element; the first of its range if it has none): integrated right after the thread's sweep
  std::vector<std::uint32_t> private_from;
  // The work estimate of the last build as prefix sums: elements [a, b) weigh prefix[b] − prefix[a].
  std::vector<std::uint64_t> prefix;
  // per element k: the lowest i of a pair slot (i, k) of the last build (k if none). k is shared exactly
  // when that i lies before k's range: its slot is computed by an earlier thread (a pair's j is never
  // below its i). So a balance finds the shared elements in one pass over the elements, not the slots.
  std::vector<std::uint32_t> lowest;
  // Measured cost per unit of work estimate of each thread's range [rate_first[t], rate_first[t+1])
  // (balance()); empty: none. The next builds weight each element's estimate by the rate of the range it
  // lay in, until forget_rates() (the elements were renumbered).
  std::vector<double> rate;
  std::vector<std::uint32_t> rate_first, previous;  // previous: scratch
  std::vector<double> below, measured;             // scratch: the weighted estimate before each rated range; rates

  // Work estimates per element and per slot the element computes (a face contact costs several times
  // a linear one: N segments, a square root, atan2 and hypot).
  static constexpr std::uint64_t element_work = 1, linear_work = 4, face_work = 32;

  template <class LinearPairs, class FaceSlots, class LinearWalls>
  void build(int nt, std::size_t elements, const LinearPairs& linear_pairs, const FaceSlots& face_pairs,
             const LinearWalls& linear_walls, const FaceSlots& face_walls) {
    threads = nt < 1 ? 1 : nt;
    prefix.assign(elements + 1, element_work);  // prefix[k + 1]: element k's work, summed below
    prefix[0] = 0;
    for (const auto& s : linear_pairs) prefix[s.i + 1] += linear_work;
    for (const auto& s : face_pairs) prefix[s.i + 1] += face_work;
    for (const auto& s : linear_walls) prefix[s.i + 1] += linear_work;
    for (const auto& s : face_walls) prefix[s.i + 1] += face_work;
    for (std::size_t k = 0; k < elements; ++k) prefix[k + 1] += prefix[k];
    lowest.resize(elements);
    for (std::size_t k = 0; k < elements; ++k) lowest[k] = static_cast<std::uint32_t>(k);
    for (const auto& s : linear_pairs) lowest[s.j] = std::min<std::uint32_t>(lowest[s.j], s.i);
    for (const auto& s : face_pairs) lowest[s.j] = std::min<std::uint32_t>(lowest[s.j], s.i);
    divide(elements, true);
    assign(linear_pairs, face_pairs, linear_walls, face_walls);
  }

  /// Moves the boundaries so that every thread gets the same share of the work as measured: thread t took
  /// seconds[t] on its range of the current shares. Each element's estimate is weighted by its thread's cost
  /// per unit of estimate, and the weighted total is divided evenly. The slot lists must be those of the
  /// last build (no rebuild in between). damped: the boundaries move half the way. Costs a pass over the
  /// elements (the shared ones) and binary searches: no pass over the slots.
  template <class LinearPairs, class FaceSlots, class LinearWalls>
  void balance(const std::vector<double>& seconds, const LinearPairs& linear_pairs, const FaceSlots& face_pairs,
               const LinearWalls& linear_walls, const FaceSlots& face_walls, bool damped = true) {
    const std::size_t n = static_cast<std::size_t>(threads), elements = lowest.size();
    if (seconds.size() != n || first.size() != n + 1 || first[n] != elements || prefix.size() != elements + 1) return;
    std::vector<double>& r = measured;
    r.assign(n, 0.0);
    double known = 0.0;
    std::size_t with = 0;
    for (std::size_t t = 0; t < n; ++t) {
      const std::uint64_t w = prefix[first[t + 1]] - prefix[first[t]];
      if (w > 0 && seconds[t] > 0.0 && std::isfinite(seconds[t])) {
        r[t] = seconds[t] / static_cast<double>(w);
        known += r[t];
        ++with;
      }
    }
    if (with == 0) return;
    for (double& x : r)
      if (x <= 0.0) x = known / static_cast<double>(with);  // an empty range: the mean rate
    rate.assign(r.begin(), r.end());
    rate_first.assign(first.begin(), first.end());
    divide(elements, damped);
    assign(linear_pairs, face_pairs, linear_walls, face_walls);
  }
  void forget_rates() {
    rate.clear();
    rate_first.clear();
  }

 private:
  // first[]: the estimate (weighted by the measured rates if there are any) divided evenly: boundary t is
  // the largest e whose elements [0, e) weigh at most t/n of the total. damped: with rates, the boundaries
  // move only half the way from where they were (the measured rate is the mean of a range, not the rate
  // near its boundary, and the times are noisy on a machine shared with other work: a full step overshoots
  // and swings back).
  void divide(std::size_t elements, bool damped) {
    const std::size_t n = static_cast<std::size_t>(threads);
    const bool had = first.size() == n + 1 && first[n] == elements;
    previous.assign(first.begin(), first.end());
    first.assign(n + 1, 0);
    first[n] = static_cast<std::uint32_t>(elements);
    const bool rated = rate.size() == n && rate_first.size() == n + 1 && rate_first[n] == elements;
    if (!rated) {
      const std::uint64_t total = prefix[elements];
      for (std::size_t t = 1; t < n; ++t) {
        const std::uint64_t target = total / n * t + total % n * t / n;  // total·t/n without overflow
        first[t] = static_cast<std::uint32_t>(std::upper_bound(prefix.begin(), prefix.end(), target) - prefix.begin() - 1);
      }
      return;
    }
    // the weighted estimate of the elements [0, e): below[q] + rate[q]·(prefix[e] − prefix[rate_first[q]]) in
    // the rated range q that holds e; nondecreasing in e (and continuous at the ranges' boundaries)
    below.assign(n + 1, 0.0);
    for (std::size_t q = 0; q < n; ++q)
      below[q + 1] = below[q] + rate[q] * static_cast<double>(prefix[rate_first[q + 1]] - prefix[rate_first[q]]);
    const double total = below[n];
    std::size_t q = 0;
    for (std::size_t t = 1; t < n; ++t) {
      const double target = total * static_cast<double>(t) / static_cast<double>(n);
      while (q + 1 < n && below[q + 1] <= target) ++q;  // the range where the estimate passes the target
      const auto lo = prefix.begin() + rate_first[q], hi = prefix.begin() + rate_first[q + 1] + 1;
      const std::uint64_t base = prefix[rate_first[q]];
      const auto past = std::partition_point(lo, hi, [&](std::uint64_t p) {
        return below[q] + rate[q] * static_cast<double>(p - base) <= target;
      });
      first[t] = static_cast<std::uint32_t>(past - prefix.begin() - 1);
      if (damped && had) first[t] = static_cast<std::uint32_t>((std::uint64_t{first[t]} + previous[t] + 1) / 2);
    }
  }
  // The slot runs, the shared elements and each thread's list of them, for the boundaries in first[].
  template <class LinearPairs, class FaceSlots, class LinearWalls>
  void assign(const LinearPairs& linear_pairs, const FaceSlots& face_pairs, const LinearWalls& linear_walls,
              const FaceSlots& face_walls) {
    const std::size_t n = static_cast<std::size_t>(threads), elements = lowest.size();
    split(linear_pairs, slots[0]);
    split(face_pairs, slots[1]);
    split(linear_walls, slots[2]);
    split(face_walls, slots[3]);
    shared.resize(elements);
    shared_start.assign(n + 1, 0);
    shared_items.clear();
    private_from.assign(n, 0);
    for (std::size_t t = 0; t < n; ++t) {
      const std::uint32_t from = first[t];
      for (std::uint32_t k = from; k < first[t + 1]; ++k) {
        shared[k] = lowest[k] < from;  // a pair slot (i, k) with i in an earlier thread's range
        if (shared[k]) shared_items.push_back(k);
      }
      shared_start[t + 1] = static_cast<std::uint32_t>(shared_items.size());
      private_from[t] = shared_start[t + 1] > shared_start[t] ? shared_items.back() + 1 : first[t];
    }
  }
  // The run of slots whose element i lies in each range (the list is sorted by i).
  template <class Slots>
  void split(const Slots& list, std::vector<std::size_t>& bounds) const {
    const std::size_t n = first.size() - 1;
    bounds.assign(n + 1, 0);
    for (std::size_t t = 1; t < n; ++t) {
      const std::uint32_t from = first[t];
      bounds[t] = static_cast<std::size_t>(
          std::partition_point(list.begin() + static_cast<std::ptrdiff_t>(bounds[t - 1]), list.end(),
                               [from](const auto& s) { return s.i < from; }) - list.begin());
    }
    bounds[n] = list.size();
  }
};

}  // namespace dem
