#pragma once
// Free fall under constant acceleration: x(t) = x0 + v0 t + g t^2/2, v(t) = v0 + g t
// (refs §1.6 "free fall" row). g is the signed acceleration along the coordinate.
// Accuracy: exact up to rounding (a few ulp of the largest term).

#include "ref/require.hpp"

namespace ref {

inline double free_fall_position(double x0, double v0, double g, double t) {
  constexpr const char* where = "ref::free_fall_position";
  detail::require_finite(where, "x0", x0);
  detail::require_finite(where, "v0", v0);
  detail::require_finite(where, "g", g);
  detail::require_finite(where, "t", t);
  return x0 + v0 * t + 0.5 * g * t * t;
}

inline double free_fall_velocity(double v0, double g, double t) {
  constexpr const char* where = "ref::free_fall_velocity";
  detail::require_finite(where, "v0", v0);
  detail::require_finite(where, "g", g);
  detail::require_finite(where, "t", t);
  return v0 + g * t;
}

}  // namespace ref
