// Simulation::face_segments: the link state of each segment of one PRE face contact (M8–M10: linked or
// not, bond intact or broken), for the per-contact output (run/contacts_csv.hpp).
#include "dem/core/simulation.hpp"

#include <algorithm>
#include <utility>

#include "dem/core/step_loops.hpp"

namespace dem {

using step_detail::key;

Simulation::FaceSegments Simulation::face_segments(std::uint32_t i, std::uint32_t j, bool wall) const {
  if (!wall && j < i) std::swap(i, j);  // pair slots hold i < j (the caller turns the order round if it did)
  const std::vector<FaceSlot>& slots = wall ? face_walls_ : face_pairs_;
  const auto it = std::lower_bound(slots.begin(), slots.end(), key(i, j),
                                   [](const FaceSlot& s, std::uint64_t k) { return key(s.i, s.j) < k; });
  FaceSegments out;
  if (it == slots.end() || it->i != i || it->j != j || !it->touching || it->law < 0) return out;
  out.n = m_.laws[static_cast<std::size_t>(it->law)].face.segments;
  out.seg = it->h.seg;
  return out;
}

}  // namespace dem
