#pragma once
// Equilibrium overlap of a body of mass m resting under gravity g on a linear contact spring K:
// K x_eq = m g, so x_eq = m g / K (refs §1.6 "resting on a wall", §1.7). The dashpot carries no
// force at rest, so x_eq does not depend on eta.
// Accuracy: exact up to rounding.

#include "ref/require.hpp"

namespace ref {

inline double resting_overlap(double mass, double gravity, double stiffness) {
  constexpr const char* where = "ref::resting_overlap";
  detail::require_positive(where, "mass", mass);
  detail::require_non_negative(where, "gravity", gravity);
  detail::require_positive(where, "stiffness", stiffness);
  return mass * gravity / stiffness;
}

}  // namespace ref
