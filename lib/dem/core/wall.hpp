#pragma once
// Walls: straight segments and points (docs/model.md §1, "Walls"). A wall is a rigid body of infinite
// mass; it may move with a prescribed velocity history. A point wall (the slit corners of the silo)
// contacts in every direction.
#include <cstdint>
#include <string>

#include "dem/core/vec2.hpp"

namespace dem {

enum class WallKind : std::uint8_t { segment, point };

struct Wall {
  std::string name;
  WallKind kind = WallKind::segment;
  bool open = false;  // an opened gate (a silo's slit in discharge, core/discharge.hpp): no contacts.
                      // Case data, fixed for the run: a checkpoint does not save it
  Vec2 a, b;                  // end points [m] (a point wall uses a only)
  std::int32_t material = 0;  // index into the materials table
  std::int32_t drive = -1;    // velocity history index, -1 for a fixed wall
  Vec2 increment;             // displacement of the current step [m]
  Vec2 force;                 // force the elements exert on the wall in the current step [N]
};

/// Closest point of a wall to p, and the squared distance.
inline Vec2 closest_point(const Wall& w, Vec2 p) {
  if (w.kind == WallKind::point) return w.a;
  const Vec2 ab = w.b - w.a;
  const double len2 = dot(ab, ab);
  double s = len2 > 0.0 ? dot(p - w.a, ab) / len2 : 0.0;
  s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
  return w.a + ab * s;
}

}  // namespace dem
