#pragma once
// Contact history storage. A slot exists for every candidate pair of the neighbour list (element–
// element or element–wall); it carries the contact's history, so history survives rebuilds: a
// rebuild merges the old, sorted slot list into the new, sorted candidate list by the key (i, j).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dem/contact/face_contact.hpp"
#include "dem/contact/linear_contact.hpp"
#include "dem/contact/rolling_resistance.hpp"

namespace dem {

struct LinearSlot {
  std::uint32_t i = 0, j = 0;  // element i; element j (pairs) or wall index (wall slots)
  std::int32_t law = -1;       // index into Model::laws
  std::uint8_t touching = 0;
  double eta_n = 0.0, eta_s = 0.0;  // dashpots of this pair [N·s/m]
  LinearContactHistory h;
  ContactForce f;              // forces of the last step (outputs)
  RollingState rolling;        // rolling resistance (R1–R6), zero if the law has none
  double nx = 0.0, ny = 0.0;   // normal of the last step, from i towards j
};

/// What a linear element–element contact carries from step to step while it touches (zero otherwise):
/// 32 bytes, two slots to a cache line.
struct alignas(32) LinearContactState {
  double eta_n = 0.0, eta_s = 0.0;  // dashpots of this pair [N·s/m]
  LinearContactHistory h;
};

/// What a step's law gives a touching linear element–element contact, for outputs: written only by the
/// steps that keep it (Simulation::keep_contact_forces), since nothing in the next step reads it.
struct alignas(32) LinearContactResultant {
  double fn = 0.0, fs = 0.0;  // forces of the step, compression positive [N]
  double nx = 0.0, ny = 0.0;  // normal of the step, from i towards j
};

struct SlotPair {
  std::uint32_t i = 0, j = 0;
};

/// The linear element–element slots, one per candidate pair, in columns (bench/journal.md, "Where the time
/// and the bytes go"): the sweep reads the pair and `touching` of every candidate (9 bytes), the law and
/// the state only of the pairs whose cores overlap or that touched at the last step. Slot k is (pair[k],
/// touching[k], law[k], state[k], resultant[k]); a slot that does not touch has a zero state, and its
/// resultant means nothing. Sorted by (i, j) like every slot list. The resultants do not move with their
/// slots (merge, move): every step that keeps them writes those of every touching slot afresh.
struct LinearPairSlots {
  std::vector<SlotPair> pair;
  std::vector<std::uint8_t> touching;
  std::vector<std::int32_t> law;  // index into Model::laws
  std::vector<LinearContactState> state;
  std::vector<LinearContactResultant> resultant;
  /// Rolling resistance (R1–R6), a column of its own that exists only if some law of the model rolls
  /// (`with_rolling`), so that a model without it keeps the 32-byte state alone; it moves with its slot, and
  /// its moment `m` is the step's, like the resultants, for the slots whose law rolls.
  bool with_rolling = false;
  std::vector<RollingState> rolling;

  std::size_t size() const { return pair.size(); }
  std::size_t capacity() const { return pair.capacity(); }
  void reserve(std::size_t n) {
    pair.reserve(n), touching.reserve(n), law.reserve(n), state.reserve(n), resultant.reserve(n);
    if (with_rolling) rolling.reserve(n);
  }
  void resize(std::size_t n) {
    pair.resize(n), touching.resize(n), law.resize(n), state.resize(n), resultant.resize(n);
    rolling.resize(with_rolling ? n : 0);
  }
  void clear() { resize(0); }
  void move(std::size_t to, std::size_t from) {
    pair[to] = pair[from], touching[to] = touching[from], law[to] = law[from], state[to] = state[from];
    if (with_rolling) rolling[to] = rolling[from];
  }
  /// A fresh slot (no contact) for the pair (i, j) with this law.
  void put_fresh(std::size_t k, std::uint32_t i, std::uint32_t j, std::int32_t l) {
    pair[k] = {i, j}, touching[k] = 0, law[k] = l, state[k] = {};
    if (with_rolling) rolling[k] = {};
  }
  /// Ends a contact: the slot stays (it is a candidate pair) but forgets its history.
  void reset(std::size_t k) {
    touching[k] = 0;
    state[k] = {};
    if (with_rolling) rolling[k] = {};
  }
};

struct FaceSlot {
  std::uint32_t i = 0, j = 0;
  std::int32_t law = -1;
  std::uint8_t touching = 0;
  FaceConstants c;
  FaceHistory h;
  FaceForce f;
  double nx = 0.0, ny = 0.0;
};

/// A history that must outlive a neighbour-list rebuild even if the pair left the candidate list
/// (a bonded face stretched beyond the skin).
inline bool must_keep(const LinearSlot&) { return false; }
inline bool must_keep(const FaceSlot& s) { return s.touching != 0; }

}  // namespace dem
