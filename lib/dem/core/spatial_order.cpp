#include "dem/core/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "dem/core/simulation.hpp"

namespace dem {

namespace {

/// The bits of v spread to the even positions of a 64-bit word.
std::uint64_t spread(std::uint32_t v) {
  std::uint64_t x = v;
  x = (x | (x << 16)) & 0x0000FFFF0000FFFFull;
  x = (x | (x << 8)) & 0x00FF00FF00FF00FFull;
  x = (x | (x << 4)) & 0x0F0F0F0F0F0F0F0Full;
  x = (x | (x << 2)) & 0x3333333333333333ull;
  x = (x | (x << 1)) & 0x5555555555555555ull;
  return x;
}

/// The cell number of a coordinate u ≥ lo: ⌊(u − lo)/cell⌋, clamped to [0, 2³² − 2] (NaN: 0).
std::uint32_t cell_of(double u, double lo, double inv_cell) {
  const double c = std::floor((u - lo) * inv_cell);
  if (!(c >= 0.0)) return 0;
  if (c >= 4294967294.0) return 4294967294u;
  return static_cast<std::uint32_t>(c);
}

template <class T>
void permute(std::vector<T>& a, const std::vector<std::uint32_t>& order, std::vector<T>& tmp) {
  if (a.size() != order.size()) throw std::invalid_argument("permute_elements: an element array has the wrong size");
  tmp.resize(a.size());
  for (std::size_t k = 0; k < order.size(); ++k) tmp[k] = a[order[k]];
  a.swap(tmp);
}

inline std::uint64_t pair_key(std::uint32_t i, std::uint32_t j) { return (std::uint64_t{i} << 32) | j; }

template <class Slot>
void sort_slots(std::vector<Slot>& slots) {
  std::sort(slots.begin(), slots.end(),
            [](const Slot& a, const Slot& b) { return pair_key(a.i, a.j) < pair_key(b.i, b.j); });
}

}  // namespace

std::uint64_t morton_key(std::uint32_t cx, std::uint32_t cy) { return spread(cx) | (spread(cy) << 1); }

void spatial_order(const Elements& e, double cell, std::vector<std::uint32_t>& order,
                   std::vector<std::uint64_t>& keys) {
  const std::size_t n = e.size();
  if (!(cell > 0.0) || !std::isfinite(cell)) throw std::invalid_argument("spatial_order: the cell size must be positive");
  double xlo = std::numeric_limits<double>::infinity(), ylo = xlo;
  for (std::size_t i = 0; i < n; ++i)
    if (e.active[i]) xlo = std::min(xlo, e.x[i]), ylo = std::min(ylo, e.y[i]);
  const double inv_cell = 1.0 / cell;
  keys.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    keys[i] = e.active[i] ? morton_key(cell_of(e.x[i], xlo, inv_cell), cell_of(e.y[i], ylo, inv_cell))
                          : std::numeric_limits<std::uint64_t>::max();  // inactive: last
  order.resize(n);
  std::iota(order.begin(), order.end(), std::uint32_t{0});
  // (key, current index): a total order, so the result does not depend on the sort's algorithm
  std::sort(order.begin(), order.end(),
            [&keys](std::uint32_t a, std::uint32_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
}

void invert_permutation(const std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& new_of_old) {
  const std::size_t n = order.size();
  new_of_old.assign(n, std::numeric_limits<std::uint32_t>::max());
  for (std::size_t k = 0; k < n; ++k) {
    if (order[k] >= n || new_of_old[order[k]] != std::numeric_limits<std::uint32_t>::max())
      throw std::invalid_argument(fmt::format("element order: entry {} ({}) is out of range or repeated", k, order[k]));
    new_of_old[order[k]] = static_cast<std::uint32_t>(k);
  }
}

void permute_elements(Elements& e, const std::vector<std::uint32_t>& order, PermuteScratch& s) {
  if (order.size() != e.size()) throw std::invalid_argument("permute_elements: the order has the wrong size");
  for (auto* v : {&e.x, &e.y, &e.phi, &e.dx, &e.dy, &e.dphi, &e.vx, &e.vy, &e.omega, &e.fx, &e.fy, &e.moment,
                  &e.radius, &e.mass, &e.inertia, &e.inv_mass, &e.inv_inertia})
    permute(*v, order, s.d);
  permute(e.material, order, s.i32);
  permute(e.group, order, s.i32);
  permute(e.drive, order, s.i32);
  permute(e.shape, order, s.shape);
  permute(e.motion, order, s.motion);
  permute(e.active, order, s.u8);
  permute(e.id, order, s.u32);
}

void renumber_pair_slots(LinearPairSlots& slots, const std::vector<std::uint32_t>& new_of_old) {
  const std::size_t n = slots.size();
  for (std::size_t k = 0; k < n; ++k) {
    SlotPair& p = slots.pair[k];
    std::uint32_t i = new_of_old[p.i], j = new_of_old[p.j];
    if (i > j) {  // turned round: the normal from the new i towards the new j (K4) is the old one reversed
      std::swap(i, j);
      slots.resultant[k].nx = -slots.resultant[k].nx;
      slots.resultant[k].ny = -slots.resultant[k].ny;
      if (slots.with_rolling) {  // the rolling moments are those on i (R3, R6): on the new i, the opposite
        slots.rolling[k].mk = -slots.rolling[k].mk;
        slots.rolling[k].m = -slots.rolling[k].m;
      }
    }
    p = {i, j};
  }
  // sorted by (i, j): every column takes the order of the pairs (the keys are unique)
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), std::uint32_t{0});
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return pair_key(slots.pair[a].i, slots.pair[a].j) < pair_key(slots.pair[b].i, slots.pair[b].j);
  });
  std::vector<SlotPair> p;
  std::vector<std::uint8_t> t;
  std::vector<std::int32_t> l;
  std::vector<LinearContactState> st;
  std::vector<LinearContactResultant> re;
  permute(slots.pair, order, p);
  permute(slots.touching, order, t);
  permute(slots.law, order, l);
  permute(slots.state, order, st);
  permute(slots.resultant, order, re);
  if (slots.with_rolling) {
    std::vector<RollingState> ro;
    permute(slots.rolling, order, ro);
  }
}

template <class Slot>
void renumber_wall_slots(std::vector<Slot>& slots, const std::vector<std::uint32_t>& new_of_old) {
  for (Slot& s : slots) s.i = new_of_old[s.i];
  sort_slots(slots);
}
template void renumber_wall_slots(std::vector<LinearSlot>&, const std::vector<std::uint32_t>&);
template void renumber_wall_slots(std::vector<FaceSlot>&, const std::vector<std::uint32_t>&);

std::size_t index_of_id(const Elements& e, std::uint32_t id) {
  if (e.id.empty() || (id < e.id.size() && e.id[id] == id)) return id;
  const auto it = std::find(e.id.begin(), e.id.end(), id);
  if (it == e.id.end()) throw std::invalid_argument(fmt::format("element {} does not exist", id));
  return static_cast<std::size_t>(it - e.id.begin());
}

// ---------------------------------------------------------------------------------------------------
// The simulation's side: reorder at a neighbour-list rebuild, restore a checkpoint's order.

void Simulation::reorder_elements() {
  for (const PairLaw& law : m_.laws)
    if (law.kind == LawKind::face)
      throw std::invalid_argument("numerics.reorder_every: spatial reordering needs linear contact laws only (this "
                                  "case has a face law, whose history is not symmetric in its two elements)");
  Elements& e = m_.elements;
  if (e.id.size() != e.size()) {  // elements assembled by hand: ids are the indices
    e.id.resize(e.size());
    std::iota(e.id.begin(), e.id.end(), std::uint32_t{0});
  }
  double rmax = 0.0;
  for (double r : e.radius) rmax = std::max(rmax, r);
  spatial_order(e, 2.0 * rmax + skin_, order_, order_keys_);  // the neighbour grid's cells
  apply_order();
}

void Simulation::apply_order() {
  Elements& e = m_.elements;
  invert_permutation(order_, new_of_old_);
  permute_elements(e, order_, permute_scratch_);
  renumber_pair_slots(linear_pairs_, new_of_old_);
  renumber_wall_slots(linear_walls_, new_of_old_);
  renumber_wall_slots(face_walls_, new_of_old_);
  // candidates_, x_ref_, y_ref_ and the contact index are made anew by the rebuild that follows (or
  // read from the checkpoint)
  for (CandidatePair& c : candidates_) {
    c.i = new_of_old_[c.i], c.j = new_of_old_[c.j];
    if (c.i > c.j) std::swap(c.i, c.j);
  }
  index_of_id_.resize(e.size());
  for (std::size_t k = 0; k < e.size(); ++k) index_of_id_[e.id[k]] = static_cast<std::uint32_t>(k);
  shares_.forget_rates();  // measured on index ranges that now hold other elements
  tested_step_ = -1;       // the rebuild test was made on the old order
  travel_ = kTravelUnknown;  // x_ref_ is not permuted: unknown until the rebuild (or the checkpoint's)
}

void Simulation::restore_order(const std::vector<std::uint32_t>& ids) {
  Elements& e = m_.elements;
  const std::size_t n = e.size();
  if (ids.size() != n)
    throw std::invalid_argument(fmt::format("element order: {} ids for {} elements", ids.size(), n));
  if (e.id.size() != n) {
    e.id.resize(n);
    std::iota(e.id.begin(), e.id.end(), std::uint32_t{0});
  }
  if (ids == e.id) return;
  // order_[k] = the current index of the element with id ids[k]
  invert_permutation(e.id, new_of_old_);  // new_of_old_[id] = current index (and e.id is a bijection)
  order_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (ids[k] >= n) throw std::invalid_argument(fmt::format("element order: id {} of {} elements", ids[k], n));
    order_[k] = new_of_old_[ids[k]];
  }
  apply_order();  // checks that ids is a bijection
}

}  // namespace dem

namespace dem {

std::vector<ContactView> contacts_in_id_order(const Simulation& sim) {
  std::vector<ContactView> out = sim.contacts();
  if (!sim.reordered()) return out;
  for (ContactView& c : out)
    if (!c.wall && sim.id_of(c.i) > sim.id_of(c.j)) {
      std::swap(c.i, c.j);
      c.nx = -c.nx;
      c.ny = -c.ny;
      c.mr = -c.mr;  // the moment on the new i (R6)
    }
  auto key = [&](const ContactView& c) {
    return std::tuple{c.wall, sim.id_of(c.i), c.wall ? c.j : sim.id_of(c.j)};
  };
  std::stable_sort(out.begin(), out.end(), [&](const ContactView& a, const ContactView& b) { return key(a) < key(b); });
  return out;
}

}  // namespace dem
