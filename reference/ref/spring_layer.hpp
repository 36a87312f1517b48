#pragma once
// A straight face of length 2a carrying a uniform layer of normal springs, total stiffness k (force
// per unit uniform approach), i.e. k/(2a) per unit length. A small rigid rotation θ about the face
// centre compresses the layer by s·θ at s ∈ [−a, a], so the restoring moment is
//   M = ∫ s (k/2a) s θ ds = k a² θ / 3,
// the continuum that N discrete springs (docs/model.md §2, M6) approximate (docs/references.md §4.3: at the
// segment centres Σ(aξᵢ)²/N = (a²/3)(1 − 1/N²)).
// Accuracy: exact for the linear layer; a finite rotation changes it by O(θ²).

#include <cmath>

#include "ref/require.hpp"

namespace ref {

inline double spring_layer_moment(double stiffness, double half_length, double rotation) {
  constexpr const char* where = "ref::spring_layer_moment";
  detail::require_positive(where, "stiffness", stiffness);
  detail::require_positive(where, "half_length", half_length);
  return stiffness * half_length * half_length * rotation / 3.0;
}

/// N discrete normal springs of k/N each at the segment centres aξ_i, ξ_i = (2i + 1 − N)/N (M13.1), on a face
/// pressed into a wall by the approach δ and turned statically by θ about its contact point (the element's
/// centre at r − δ from the wall): the centre's approach grows by (r − δ)(1 − cos θ) (the rigid turn), each
/// segment's by a ξ_i θ (the linearised lever, M15.1), and a segment whose approach is negative carries
/// nothing (no tension, M8). Returns the size of the restoring moment Σ (k/N) u_i a ξ_i over the loaded segments.
/// Exact for the linearised face; before any segment opens it is k a² θ/3 (1 − 1/N²) plus the turn's O(θ²).
inline double no_tension_face_moment(double stiffness, double half_length, int segments, double approach,
                                     double radius, double rotation) {
  constexpr const char* where = "ref::no_tension_face_moment";
  detail::require_positive(where, "stiffness", stiffness);
  detail::require_positive(where, "half_length", half_length);
  detail::require_positive(where, "radius", radius);
  detail::require_non_negative(where, "approach", approach);
  detail::require_non_negative(where, "rotation", rotation);
  if (segments < 1 || segments > 1000) detail::fail(where, "segments must be in [1, 1000]", segments);
  const double centre = approach + (radius - approach) * (1.0 - std::cos(rotation));
  double moment = 0.0;
  for (int i = 0; i < segments; ++i) {
    const double lever = half_length * (2.0 * i + 1.0 - segments) / segments;
    const double u = centre + lever * rotation;
    if (u > 0.0) moment += stiffness / segments * u * lever;
  }
  return moment;
}

}  // namespace ref
