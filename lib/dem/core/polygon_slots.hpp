#pragma once
// The contact histories of polygon elements (docs/model.md §5): one slot per candidate pair (polygon–polygon,
// polygon–disk) or polygon–wall, holding the contact points that touch, each a linear contact (K6–K14) with
// its own history, known from step to step by (side, corner) (corner_contacts.hpp).
#include <cstdint>
#include <vector>

#include "dem/contact/linear_contact.hpp"

namespace dem {

struct CornerSlot {
  std::uint8_t side = 0;
  std::uint16_t corner = 0;
  double eta_n = 0.0, eta_s = 0.0;  // dashpots [N·s/m]
  LinearContactHistory h;
  ContactForce f;             // forces of the last step
  double px = 0.0, py = 0.0;  // contact point of the last step [m]
  double nx = 0.0, ny = 0.0;  // normal of the last step, from i towards j
};

struct PolygonSlot {
  std::uint32_t i = 0, j = 0;  // polygon i; element j (i < j; j may be the polygon) or wall j
  std::int32_t law = -1;       // index into Model::laws
  bool swapped = false;        // pairs: element i of the key (the smaller index) is not the polygon: the
                               // geometry takes the polygon as its i (the other is a polygon or a disk)
  std::vector<CornerSlot> corners;  // the touching points, by (side, corner)
};

}  // namespace dem
