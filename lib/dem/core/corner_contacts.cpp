#include "dem/core/corner_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dem {

EdgeDistance nearest_edge(const std::vector<Vec2>& poly, Vec2 p, Vec2 prefer, double window) {
  const std::size_t n = poly.size();
  double smax = -std::numeric_limits<double>::infinity();
  if (window > 0.0)  // the largest s first: the window is measured from it
    for (std::size_t e = 0; e < n; ++e) {
      const Vec2 a = poly[e], d = poly[(e + 1) % n] - a;
      smax = std::max(smax, dot(Vec2{d.y, -d.x}, p - a) / norm(d));
    }
  EdgeDistance best;
  best.s = -std::numeric_limits<double>::infinity();
  double best_turn = -std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < n; ++e) {
    const Vec2 a = poly[e], d = poly[(e + 1) % n] - a;
    const double len = norm(d);
    const Vec2 ne{d.y / len, -d.x / len};  // outward for counter-clockwise corners
    const double s = dot(ne, p - a);
    if (window <= 0.0) {
      if (s > best.s) best = {s, static_cast<std::uint16_t>(e), ne};
    } else if (s >= smax - window && dot(ne, prefer) > best_turn) {  // near a corner: the edge facing `prefer`
      best = {s, static_cast<std::uint16_t>(e), ne};
      best_turn = dot(ne, prefer);
    }
  }
  return best;
}

namespace {

Vec2 mean(const std::vector<Vec2>& v) {
  Vec2 c{};
  for (const Vec2& q : v) c = c + q;
  return c * (1.0 / static_cast<double>(v.size()));
}

double shortest_edge(const std::vector<Vec2>& v) {
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < v.size(); ++k) m = std::min(m, norm(v[(k + 1) % v.size()] - v[k]));
  return m;
}

}  // namespace

void polygon_pair_hits(const std::vector<Vec2>& pi, const std::vector<Vec2>& pj, std::vector<CornerHit>& out) {
  const std::size_t first = out.size();
  // Near a corner of the other outline two edges are about as near: the one that faces the other body
  // (its normal along the line between the centres) is taken, within kCornerWindow of the shorter edges.
  const Vec2 towards_i = mean(pi) - mean(pj);
  const double window = kCornerWindow * std::min(shortest_edge(pi), shortest_edge(pj));
  for (std::size_t k = 0; k < pi.size(); ++k) {  // corners of i in j: n = −n_e(j)
    const EdgeDistance d = nearest_edge(pj, pi[k], towards_i, window);
    if (d.s <= 0.0) out.push_back({0, static_cast<std::uint16_t>(k), pi[k], -d.normal, -d.s});
  }
  const std::size_t own = out.size();
  for (std::size_t k = 0; k < pj.size(); ++k) {  // corners of j in i: n = n_e(i)
    const EdgeDistance d = nearest_edge(pi, pj[k], -towards_i, window);
    if (d.s > 0.0) continue;
    // a corner of j on a corner of i that is already a point (corner on corner, as in a stack of equal
    // blocks): one point there, not two. The two corners are then at most their depths apart.
    bool twin = false;
    for (std::size_t h = first; h < own && !twin; ++h)
      twin = out[h].side == 0 && norm(out[h].point - pj[k]) <= 2.0 * std::max(out[h].depth, -d.s);
    if (!twin) out.push_back({1, static_cast<std::uint16_t>(k), pj[k], d.normal, -d.s});
  }
}

void polygon_wall_hits(const std::vector<Vec2>& pi, Vec2 c, Vec2 a, Vec2 b, bool point, std::vector<CornerHit>& out) {
  if (!point) {
    const Vec2 ab = b - a;
    const double len = norm(ab);
    Vec2 nw{-ab.y / len, ab.x / len};  // the wall's normal on the side of the centroid
    if (dot(nw, c - a) < 0.0) nw = -nw;
    for (std::size_t k = 0; k < pi.size(); ++k) {
      const double s = dot(nw, pi[k] - a), along = dot(pi[k] - a, ab);
      if (s <= 0.0 && along >= 0.0 && along <= len * len) out.push_back({0, static_cast<std::uint16_t>(k), pi[k], -nw, -s});
    }
  }
  const Vec2 ends[2] = {a, b};
  for (std::uint16_t k = 0; k < (point ? 1 : 2); ++k) {  // an end of the wall inside i: n = n_e(i)
    const EdgeDistance d = nearest_edge(pi, ends[k]);
    if (d.s < 0.0) out.push_back({1, k, ends[k], d.normal, -d.s});
  }
}

void polygon_disk_hits(const std::vector<Vec2>& pi, Vec2 q, double r, std::vector<CornerHit>& out) {
  const EdgeDistance d = nearest_edge(pi, q);
  if (d.s <= 0.0) {  // the centre inside: pushed out through the nearest edge
    out.push_back({1, 0, q - d.normal * r, d.normal, r - d.s});
    return;
  }
  // outside: the nearest point of the outline (an edge or a corner)
  const std::size_t n = pi.size();
  double best = std::numeric_limits<double>::infinity();
  Vec2 nearest{};
  for (std::size_t e = 0; e < n; ++e) {
    const Vec2 a = pi[e], ab = pi[(e + 1) % n] - a;
    double t = dot(q - a, ab) / dot(ab, ab);
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    const Vec2 p = a + ab * t;
    const double dist = norm(q - p);
    if (dist < best) best = dist, nearest = p;
  }
  if (best >= r || best == 0.0) return;
  const Vec2 nrm = (q - nearest) * (1.0 / best);
  out.push_back({1, 0, q - nrm * r, nrm, r - best});
}

}  // namespace dem
