#pragma once
// Rigid convex polygon elements (docs/model.md §5, P1–P3): the shape in the body frame, its exact area,
// centroid and second moment, and its corners in the world frame. A polygon element moves as every element
// does (centre = the centroid, rotation φ); its `radius` in Elements is the circumradius R = max |v_k|, which
// the neighbour search, the rebuild skin and the blow-up test read.
#include <cstdint>
#include <string>
#include <vector>

#include "dem/core/vec2.hpp"

namespace dem {

struct PolygonShape {
  std::vector<Vec2> vertices;  // body frame, counter-clockwise, centroid at the origin [m]
};

/// Area, centroid and polar second moment about the centroid (per unit thickness) of a simple polygon
/// given counter-clockwise (P1, P2).
struct PolygonProperties {
  double area = 0.0;      // A [m²]
  Vec2 centroid;          // [m], in the frame of the given vertices
  double polar = 0.0;     // J_c = ∫(x² + y²) dA about the centroid [m⁴]
  double circumradius = 0.0;  // max |v_k − centroid| [m]
};
PolygonProperties polygon_properties(const std::vector<Vec2>& vertices);

/// Why these vertices are not a convex polygon listed counter-clockwise ("" if they are): fewer than three,
/// a repeated or collinear corner, a clockwise order or a reflex corner.
std::string polygon_problem(const std::vector<Vec2>& vertices);

/// The shape of `vertices` (counter-clockwise, any frame) moved so that its centroid is the origin.
PolygonShape centred_shape(const std::vector<Vec2>& vertices);

/// Corner k in the world frame: x + R(φ) v_k (P3).
inline Vec2 world_vertex(const PolygonShape& s, std::size_t k, double x, double y, double cphi, double sphi) {
  const Vec2 v = s.vertices[k];
  return {x + cphi * v.x - sphi * v.y, y + sphi * v.x + cphi * v.y};
}

/// A rectangle w × h centred on the origin, counter-clockwise from the lower left corner.
std::vector<Vec2> rectangle_vertices(double width, double height);

}  // namespace dem
