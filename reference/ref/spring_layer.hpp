#pragma once
// A straight face of length 2a carrying a uniform layer of normal springs, total stiffness k (force
// per unit uniform approach), i.e. k/(2a) per unit length. A small rigid rotation θ about the face
// centre compresses the layer by s·θ at s ∈ [−a, a], so the restoring moment is
//   M = ∫ s (k/2a) s θ ds = k a² θ / 3,
// the continuum that N discrete springs (docs/model.md §2, M6) approximate (docs/references.md §4.3: at the
// segment centres Σ(aξᵢ)²/N = (a²/3)(1 − 1/N²)).
// Accuracy: exact for the linear layer; a finite rotation changes it by O(θ²).

#include "ref/require.hpp"

namespace ref {

inline double spring_layer_moment(double stiffness, double half_length, double rotation) {
  constexpr const char* where = "ref::spring_layer_moment";
  detail::require_positive(where, "stiffness", stiffness);
  detail::require_positive(where, "half_length", half_length);
  return stiffness * half_length * half_length * rotation / 3.0;
}

}  // namespace ref
