#pragma once
// Spatial order of the elements (locality). A packing whose elements were generated, poured or mixed in
// random order touches memory at random in every contact sweep: the partners of element i sit anywhere
// in the arrays. Every few neighbour-list rebuilds the run can renumber the elements in the Morton
// (Z-curve) order of the neighbour grid's cells, so that neighbours in space are neighbours in memory.
// The contact slots follow their elements (histories carried along, re-sorted into the sweep's (i, j)
// order); each element keeps its id (Elements::id), which outputs, probes and checkpoints use.
//
// Reordering changes which element is i and which is j in a pair and the order in which forces are
// summed: results change at round-off, never in the physics (docs/model.md §1, "Spatial reordering").
#include <cstdint>
#include <vector>

#include "dem/contact/contact_slots.hpp"
#include "dem/core/elements.hpp"

namespace dem {

/// The Morton key of the cell (cx, cy): the bits of cx and cy interleaved (cx in the even bits).
std::uint64_t morton_key(std::uint32_t cx, std::uint32_t cy);

/// order[k] = the current index of the element that goes to index k: active elements in the Morton
/// order of their cells (square cells of side `cell` from the lowest corner of the active elements),
/// within a cell by current index; inactive elements last, by current index. Deterministic: a function
/// of the positions, the active flags and the current order only. `keys` is scratch.
void spatial_order(const Elements& e, double cell, std::vector<std::uint32_t>& order,
                   std::vector<std::uint64_t>& keys);

/// new_of_old[order[k]] = k. Throws std::invalid_argument if order is not a permutation of 0..n−1.
void invert_permutation(const std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& new_of_old);

/// Scratch buffers of permute_elements (kept by the caller: no allocation once sized).
struct PermuteScratch {
  std::vector<double> d;
  std::vector<std::int32_t> i32;
  std::vector<std::uint32_t> u32;
  std::vector<std::uint8_t> u8;
  std::vector<Shape> shape;
  std::vector<Motion> motion;
};

/// Every array of e (state, increments, forces, properties, id) takes the order: new[k] = old[order[k]].
void permute_elements(Elements& e, const std::vector<std::uint32_t>& order, PermuteScratch& scratch);

/// Element–element linear slots follow their elements: i, j → new_of_old[i], new_of_old[j]; a pair whose
/// sides come out as i > j is turned round (j, i): the normal stored for outputs flips, the history
/// (e_n, e_s), the dashpots and the forces (f_n, f_s) stay, since the linear law is symmetric in i and j
/// (with n → −n and t → −t: Δu_n, Δu_s, f_n, f_s and the moments r f_s are unchanged, (K5)–(K15)).
/// Then the slots are sorted by (i, j), the order of the sweep and of the rebuild's merge.
void renumber_pair_slots(LinearPairSlots& slots, const std::vector<std::uint32_t>& new_of_old);

/// Element–wall slots: i → new_of_old[i] (j is a wall), sorted by (i, j).
template <class Slot>
void renumber_wall_slots(std::vector<Slot>& slots, const std::vector<std::uint32_t>& new_of_old);

/// The index of the element with this id (ids as Elements::id; an empty id array: index = id). O(1)
/// when the elements are in case order, else a search (for set-up code, not the time loop).
std::size_t index_of_id(const Elements& e, std::uint32_t id);

}  // namespace dem

namespace dem {
class Simulation;
struct ContactView;
/// Simulation::contacts() in the order and orientation they have without reordering: element–element
/// contacts by (id_i, id_j) with id_i < id_j (a contact turned round has its normal reversed; f_n, f_s are
/// symmetric), then wall contacts by (id_i, wall). i and j stay array indices (for looking up the
/// elements); without reordering this is contacts() itself.
std::vector<ContactView> contacts_in_id_order(const Simulation& sim);
}  // namespace dem
