#include "dem/core/polygon.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace dem {

PolygonProperties polygon_properties(const std::vector<Vec2>& v) {
  // (P1) Green's theorem over the edges (v_k, v_{k+1}): A = ½ Σ c_k, c_k = v_k × v_{k+1};
  // centroid = Σ (v_k + v_{k+1}) c_k / (6A); J_o = Σ c_k (v_k·v_k + v_k·v_{k+1} + v_{k+1}·v_{k+1}) / 12,
  // then (P2) J_c = J_o − A |centroid|² (parallel axes).
  PolygonProperties p;
  const std::size_t n = v.size();
  if (n < 3) return p;
  // about the first corner: keeps the round-off of far-off coordinates out of the sums
  const Vec2 o = v[0];
  double a2 = 0.0, jo = 0.0;
  Vec2 c{};
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 p0 = v[k] - o, p1 = v[(k + 1) % n] - o;
    const double ck = cross(p0, p1);
    a2 += ck;
    c = c + (p0 + p1) * ck;
    jo += ck * (dot(p0, p0) + dot(p0, p1) + dot(p1, p1));
  }
  p.area = 0.5 * a2;
  const Vec2 g = c * (1.0 / (3.0 * a2));
  p.centroid = o + g;
  p.polar = jo / 12.0 - p.area * dot(g, g);
  for (const Vec2& q : v) p.circumradius = std::max(p.circumradius, norm(q - p.centroid));
  return p;
}

std::string polygon_problem(const std::vector<Vec2>& v) {
  const std::size_t n = v.size();
  if (n < 3) return fmt::format("a polygon needs three or more corners, got {}", n);
  double scale = 0.0;
  for (const Vec2& q : v) scale = std::max({scale, std::abs(q.x - v[0].x), std::abs(q.y - v[0].y)});
  if (!(scale > 0.0) || !std::isfinite(scale)) return "the corners must be finite and not all at one point";
  for (std::size_t k = 0; k < n; ++k)
    if (norm(v[(k + 1) % n] - v[k]) <= 1e-12 * scale) return fmt::format("corners {} and {} coincide", k, (k + 1) % n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 a = v[k], b = v[(k + 1) % n], c = v[(k + 2) % n];
    const double turn = cross(b - a, c - b);
    if (std::abs(turn) <= 1e-12 * scale * scale)
      return fmt::format("corner {} lies on the line of its neighbours (remove it)", (k + 1) % n);
    if (turn < 0.0)
      return fmt::format("the corners must be listed counter-clockwise around a convex polygon; corner {} turns clockwise",
                         (k + 1) % n);
  }
  // every turn left: convex if the corners go round once (the angles of the edges sum to 2π)
  double total = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 a = v[k] - v[(k + n - 1) % n], b = v[(k + 1) % n] - v[k];
    total += std::atan2(cross(a, b), dot(a, b));
  }
  if (std::abs(total - 2.0 * 3.14159265358979323846) > 1e-6) return "the corners go round more than once (the outline crosses itself)";
  return "";
}

PolygonShape centred_shape(const std::vector<Vec2>& vertices) {
  const PolygonProperties p = polygon_properties(vertices);
  PolygonShape s;
  s.vertices.reserve(vertices.size());
  for (const Vec2& q : vertices) s.vertices.push_back(q - p.centroid);
  return s;
}

std::vector<Vec2> rectangle_vertices(double width, double height) {
  const double a = 0.5 * width, b = 0.5 * height;
  return {{-a, -b}, {a, -b}, {a, b}, {-a, b}};
}

}  // namespace dem
