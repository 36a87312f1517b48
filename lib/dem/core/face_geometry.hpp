#pragma once
// The geometry of a face contact between two elements, shared by the contact sweep (contact_sweeps.cpp) and
// the reference step (reference_step.cpp): when a face forms, and the motion of a step in the contact frame
// that the face law (M3–M12, face_contact.hpp) reads.
#include <cmath>
#include <cstdint>

#include "dem/contact/face_contact.hpp"
#include "dem/core/elements.hpp"
#include "dem/core/model.hpp"

namespace dem {

/// Faces bonded at the start (step 0): the law bonds every face then, or both elements belong to one generated
/// lattice (bond group).
inline bool face_bonded_at_start(const PairLaw& law, const Elements& e, std::uint32_t i, std::uint32_t j,
                                 std::int64_t step) {
  return step == 0 && (law.bond_at_start || (e.group[i] >= 0 && e.group[i] == e.group[j]));
}

/// Whether a pair that does not touch stays apart: a face forms when D ≤ r1 + r2 (r2: D²; rs: r1 + r2). A face
/// bonded at the start touches by construction, up to the round-off of the generated positions.
inline bool face_pair_apart(double r2, double rs, bool bonded) {
  const double touch = bonded ? rs * (1.0 + 1e-9) : rs;
  return r2 > touch * touch;
}

/// The motion of the step between elements i and j in the current contact frame: d = (ddx, ddy) = x_j − x_i
/// after the step, of length dist, n = d/dist from i towards j.
inline FaceKinematics face_pair_kinematics(const Elements& e, std::uint32_t i, std::uint32_t j, double ddx,
                                           double ddy, double dist, double nx, double ny) {
  const double ux = e.dx[i] - e.dx[j], uy = e.dy[i] - e.dy[j];
  FaceKinematics k;
  k.du_projected = ux * nx + uy * ny;  // (M15.1), as (K5.a)
  k.dv_translation = -ux * ny + uy * nx;
  const double ox = ddx - (e.dx[j] - e.dx[i]), oy = ddy - (e.dy[j] - e.dy[i]);  // centre line before the step
  k.du_exact = std::hypot(ox, oy) - dist;                           // (M3.1): the exact approach
  k.dbeta = std::atan2(ox * ddy - oy * ddx, ox * ddx + oy * ddy);  // the contact frame's turn
  k.dphi1 = e.dphi[i];
  k.dphi2 = e.dphi[j];
  k.r1 = e.radius[i];
  k.r2 = e.radius[j];
  return k;
}

}  // namespace dem
