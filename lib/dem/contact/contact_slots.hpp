#pragma once
// Contact history storage. A slot exists for every candidate pair of the neighbour list (element–
// element or element–wall); it carries the contact's history, so history survives rebuilds: a
// rebuild merges the old, sorted slot list into the new, sorted candidate list by the key (i, j).
#include <cstdint>

#include "dem/contact/face_contact.hpp"
#include "dem/contact/linear_contact.hpp"

namespace dem {

struct LinearSlot {
  std::uint32_t i = 0, j = 0;  // element i; element j (pairs) or wall index (wall slots)
  std::int32_t law = -1;       // index into Model::laws
  std::uint8_t touching = 0;
  double eta_n = 0.0, eta_s = 0.0;  // dashpots of this pair [N·s/m]
  LinearContactHistory h;
  ContactForce f;              // forces of the last step (outputs)
  double nx = 0.0, ny = 0.0;   // normal of the last step, from i towards j
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
