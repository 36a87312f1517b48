#pragma once
// The extent dem2d represents: every coordinate a case gives or generates (element centres plus their
// radius, wall end points, a random arrangement's region) lies within |x|, |y| <= kMaxCoordinate. Far
// beyond any granular assembly, and small enough that differences of coordinates, cell indices of the
// neighbour grid and of the random fill stay finite and exact integers; a case beyond it is refused
// with file:line: key before anything runs (NaN and ±inf included).
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "dem/core/vec2.hpp"

namespace dem {

inline constexpr double kMaxCoordinate = 1e6;  // [m]
// The largest number of cells of side 2 r_max + gap a random fill's region may span along an axis (its
// cell index is an int64 from a double: exact below 2^53).
inline constexpr double kMaxFillCells = 1e12;

/// Whether a disk of this radius at p lies inside the extent (false for NaN or ±inf).
inline bool within_extent(Vec2 p, double radius = 0.0) {
  return std::abs(p.x) + radius <= kMaxCoordinate && std::abs(p.y) + radius <= kMaxCoordinate;
}

/// What a case file error says of a point outside the extent.
inline std::string outside_extent(Vec2 p, double radius = 0.0) {
  return fmt::format("({:.6g}, {:.6g}) m{} lies outside the extent dem2d represents (|x|, |y| <= {:g} m)", p.x, p.y,
                     radius > 0.0 ? fmt::format(" with radius {:.6g} m", radius) : "", kMaxCoordinate);
}

}  // namespace dem
