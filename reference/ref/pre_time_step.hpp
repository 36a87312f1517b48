#pragma once
// Matsui's time step for one PRE contact (M26), Δt < h_n √(m/k_n), read with k_n the whole face's
// stiffness N·K_n (docs/findings.md M-3) and m the mass on the contact (the element's against a wall).
// With ω₀ = √(k/m) it is ω₀Δt < h_n: above K18's exact limit 2(√(1 + h²) − h) when h_n > 2/√5 ≈ 0.894,
// below K19's min(2h, 2(√(h² + 3) − h)) for every h_n > 0 (refs §1.5).
// Accuracy: exact up to rounding.

#include <cmath>

#include "ref/require.hpp"

namespace ref {

inline double matsui_time_step(double damping_ratio, double mass, double face_stiffness) {
  constexpr const char* where = "ref::matsui_time_step";
  detail::require_non_negative(where, "damping_ratio", damping_ratio);
  detail::require_positive(where, "mass", mass);
  detail::require_positive(where, "face_stiffness", face_stiffness);
  return damping_ratio * std::sqrt(mass / face_stiffness);  // (M26)
}

}  // namespace ref
