// Simulation::take_bond_breaks: the bond-break log of a bonded PRE lattice (which links broke, where and
// when: Matsui & Nishimura's crack pattern, Fig. 10(a)). The face law marks a link whose bond breaks in
// tension (M8, SegmentState::broke); this collects the marks after a step and clears them.
#include "dem/core/simulation.hpp"

namespace dem {

std::vector<Simulation::BondBreak> Simulation::take_bond_breaks() {
  std::vector<BondBreak> out;
  const Elements& e = m_.elements;
  // The link's place: the face centre plus ξ_i a along t = (−n_y, n_x), n from i towards j (or the wall):
  // the side on which a compressive link turns i by +ξ a P (the moment of face_contact_force, M12).
  auto collect = [&](FaceSlot& s, bool wall) {
    const FaceLaw& law = m_.laws[static_cast<std::size_t>(s.law)].face;
    const Vec2 ci{e.x[s.i], e.y[s.i]}, t{-s.ny, s.nx};
    Vec2 centre;
    if (wall) {
      centre = closest_point(m_.walls[s.j], ci);
    } else {
      const Vec2 cj{e.x[s.j], e.y[s.j]};
      const double share = e.radius[s.i] / (e.radius[s.i] + e.radius[s.j]);
      centre = ci + (cj - ci) * share;
    }
    const double* xis = kSegmentXi.xi[law.positions == SegmentPositions::ends ? 1 : 0][law.segments];
    for (int k = 0; k < law.segments; ++k) {
      SegmentState& g = s.h.seg[static_cast<std::size_t>(k)];
      if (!g.broke) continue;
      g.broke = 0;
      out.push_back({s.i, s.j, wall, k, xis[k], centre + t * (xis[k] * s.c.half_length)});
    }
  };
  for (FaceSlot& s : face_pairs_)
    if (s.law >= 0) collect(s, false);
  for (FaceSlot& s : face_walls_)
    if (s.law >= 0) collect(s, true);
  return out;
}

}  // namespace dem
