#pragma once
// Which contact slots act on each element, in the order their forces are summed (lib/README.md,
// "Determinism"). A step first computes every slot's force into the slot (any order, any thread), then
// every element sums its slots in this fixed order: the linear pairs by ascending slot (= ascending
// partner index, since slots are sorted by (i, j)), then the face pairs, the linear wall slots and the
// face wall slots, each by ascending slot. That is exactly the order in which the one-thread sweeps
// of the past added them, so the sums are the same bit for bit, for any number of threads.
//
// Two compressed rows (CSR) per element: the linear pairs (the common case, one kind), and the rest
// (a kind tag per entry). Rebuilt after every change of the slot lists; buffers are reused.
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace dem {

/// Forces of one face slot on its elements in this step (the face law's output, M12).
struct ElementPush {
  double fx = 0.0, fy = 0.0;  // force on element i (element j gets the opposite) [N]
  double mi = 0.0, mj = 0.0;  // moments added to i and to j [N·m]
  std::uint8_t applied = 0;   // 0: the slot added nothing this step
};

enum class SlotKind : std::uint32_t { face_pair = 0, linear_wall = 1, face_wall = 2 };

struct ContactIndex {
  // linear pairs: entry = slot << 1 | side (side 1: the element is the slot's j)
  std::vector<std::uint32_t> linear_start, linear_items;
  // others: entry = slot << 3 | kind << 1 | side
  std::vector<std::uint32_t> other_start, other_items;
  std::vector<std::uint32_t> cursor, other_cursor;  // scratch

  static std::uint32_t linear_slot(std::uint32_t entry) { return entry >> 1; }
  static std::uint32_t other_slot(std::uint32_t entry) { return entry >> 3; }
  static SlotKind other_kind(std::uint32_t entry) { return static_cast<SlotKind>((entry >> 1) & 3u); }
  static bool is_j(std::uint32_t entry) { return (entry & 1u) != 0; }

  /// The sizes the entries can hold (before build_linear and build_other, which two threads may run at once).
  static bool fits(std::size_t linear_pairs, std::size_t others) {
    return linear_pairs < (std::size_t{1} << 31) && others < (std::size_t{1} << 29);
  }
  static void check(std::size_t linear_pairs, std::size_t others) {
    if (!fits(linear_pairs, others)) throw std::length_error("contact index: too many contact slots");
  }
  /// The row of the linear pairs.
  template <class LinearPairs>
  void build_linear(std::size_t elements, const LinearPairs& linear_pairs) {
    linear_start.assign(elements + 1, 0);
    for (const auto& s : linear_pairs) ++linear_start[s.i + 1], ++linear_start[s.j + 1];
    for (std::size_t k = 0; k < elements; ++k) linear_start[k + 1] += linear_start[k];
    linear_items.resize(linear_start[elements]);
    cursor.assign(linear_start.begin(), linear_start.end() - 1);
    for (std::uint32_t k = 0; k < linear_pairs.size(); ++k) {
      linear_items[cursor[linear_pairs[k].i]++] = k << 1;
      linear_items[cursor[linear_pairs[k].j]++] = (k << 1) | 1u;
    }
  }
  /// The row of the rest, in the order face pairs, linear walls, face walls.
  template <class FaceSlots, class LinearWalls>
  void build_other(std::size_t elements, const FaceSlots& face_pairs, const LinearWalls& linear_walls,
                   const FaceSlots& face_walls) {
    std::vector<std::uint32_t>& cursor = other_cursor;
    other_start.assign(elements + 1, 0);
    for (const auto& s : face_pairs) ++other_start[s.i + 1], ++other_start[s.j + 1];
    for (const auto& s : linear_walls) ++other_start[s.i + 1];
    for (const auto& s : face_walls) ++other_start[s.i + 1];
    for (std::size_t k = 0; k < elements; ++k) other_start[k + 1] += other_start[k];
    other_items.resize(other_start[elements]);
    cursor.assign(other_start.begin(), other_start.end() - 1);
    auto tag = [](std::uint32_t k, SlotKind kind, std::uint32_t side) {
      return (k << 3) | (static_cast<std::uint32_t>(kind) << 1) | side;
    };
    for (std::uint32_t k = 0; k < face_pairs.size(); ++k) {
      other_items[cursor[face_pairs[k].i]++] = tag(k, SlotKind::face_pair, 0);
      other_items[cursor[face_pairs[k].j]++] = tag(k, SlotKind::face_pair, 1);
    }
    for (std::uint32_t k = 0; k < linear_walls.size(); ++k)
      other_items[cursor[linear_walls[k].i]++] = tag(k, SlotKind::linear_wall, 0);
    for (std::uint32_t k = 0; k < face_walls.size(); ++k)
      other_items[cursor[face_walls[k].i]++] = tag(k, SlotKind::face_wall, 0);
  }
};

}  // namespace dem
