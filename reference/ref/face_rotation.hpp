#pragma once
// A square element bonded along one face to a fixed straight wall (the x axis), turned rigidly by θ
// (counter-clockwise positive) about its own centre c = (0, r), the centre not moving (refs §4.7).
// Each of the N discrete springs joins the wall point (s_i, 0) to the element's material point that sat
// there at the start. After the turn that point is at c + R(θ)(s_i, −r), so the spring's stretch is
//   d_i = (s_i (cos θ − 1) + r sin θ,  s_i sin θ + r (1 − cos θ)),
// and the spring pulls the wall towards the element's point with (K_s d_x,i, K_n d_y,i): the force of
// the element on the wall is the sum. The element feels the opposite force; where it acts is a model
// choice: at the wall's points (s_i, 0) (the paper's wall frame, M19), its moment about the centre is
//   M = Σ [ s_i (−K_n d_y,i) − (−r)(−K_s d_x,i) ] = −Σ (s_i K_n d_y,i + r K_s d_x,i).
// Positions s_i = r ξ_i, at the segment centres ξ_i = (2i − 1 − N)/N (M13.1) or, N = 2, at the face
// ends ξ = ±1 (M13.2).
// This is the geometry of a rigid rotation, written with a rotation matrix and not with the paper's
// M2: the exact displacement M2.1, M2.2 (consistent reading) must equal it, and the linearised M14
// misses its O(θ²) terms (no lift of the face, r θ instead of r sin θ along it).
// Accuracy: exact up to rounding.

#include <cmath>

#include "ref/require.hpp"

namespace ref {

struct FaceRotationForce {
  double fx = 0.0, fy = 0.0;  // force of the element on the wall [N]
  double moment = 0.0;         // moment on the element about its centre, forces at the wall points [N m]
};

inline FaceRotationForce face_rotation_wall_force(double kn, double ks, double r, int segments, bool ends, double theta) {
  constexpr const char* where = "ref::face_rotation_wall_force";
  detail::require_positive(where, "kn", kn);
  detail::require_non_negative(where, "ks", ks);
  detail::require_positive(where, "r", r);
  if (segments < 1 || (ends && segments != 2)) detail::fail(where, "segments must be >= 1, and 2 with face ends", segments);
  detail::require_finite(where, "theta", theta);
  const double c = std::cos(theta), s = std::sin(theta);
  FaceRotationForce f;
  for (int i = 1; i <= segments; ++i) {
    const double xi = ends ? (i == 1 ? -1.0 : 1.0) : static_cast<double>(2 * i - 1 - segments) / segments;
    const double si = r * xi;
    const double dx = si * (c - 1.0) + r * s, dy = si * s + r * (1.0 - c);
    f.fx += ks * dx;
    f.fy += kn * dy;
    f.moment -= si * kn * dy + r * ks * dx;
  }
  return f;
}

}  // namespace ref
