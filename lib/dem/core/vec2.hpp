#pragma once
// A 2D vector value type for geometry outside the hot arrays (which are stored per component).
#include <cmath>

namespace dem {

struct Vec2 {
  double x = 0.0, y = 0.0;
  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator*(double s) const { return {x * s, y * s}; }
  constexpr Vec2 operator-() const { return {-x, -y}; }
  constexpr bool operator==(const Vec2&) const = default;
};
constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double norm(Vec2 a) { return std::hypot(a.x, a.y); }
/// The vector rotated by +90 degrees (counter-clockwise): the tangent t of a contact with normal n.
constexpr Vec2 perp(Vec2 a) { return {-a.y, a.x}; }

}  // namespace dem
