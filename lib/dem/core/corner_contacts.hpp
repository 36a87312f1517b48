#pragma once
// Where two convex polygons, a polygon and a wall, or a polygon and a disk touch (docs/model.md §5, P4–P7):
// the contact points of the corner–edge model of Cundall's block codes (UDEC). Pure geometry on corners in
// the world frame (counter-clockwise); the law at each point is the linear contact law (K6–K14).
#include <cstdint>
#include <vector>

#include "dem/core/vec2.hpp"

namespace dem {

/// One contact point. Its identity from step to step (the history it keeps) is (side, corner): a corner
/// of element i (side 0) pressed into the partner, or a corner of the partner (side 1: a corner of polygon
/// j, a point wall, the centre of a disk j) pressed into i.
struct CornerHit {
  std::uint8_t side = 0;
  std::uint16_t corner = 0;
  Vec2 point;       // the contact point [m]: the corner (for a disk: its surface point nearest the polygon)
  Vec2 normal;      // unit normal from i towards j (towards the wall)
  double depth = 0.0;  // penetration along the normal [m], ≥ 0
};

/// The edge of a convex polygon (corners `poly`, counter-clockwise) that point p lies deepest behind: the
/// largest signed distance s_e = n_e·(p − v_e) over the edges (n_e: the outward unit normal of edge e), and
/// e. p is inside (or on) the polygon iff that largest s ≤ 0 (P4). With window > 0, of the edges whose s is
/// within `window` of the largest (p near a corner) the one whose normal points most along `prefer`.
struct EdgeDistance {
  double s = 0.0;
  std::uint16_t edge = 0;
  Vec2 normal;  // n_e
};
EdgeDistance nearest_edge(const std::vector<Vec2>& poly, Vec2 p, Vec2 prefer = {}, double window = 0.0);

/// The window of nearest_edge for two polygons, as a fraction of their shortest edge (P5).
inline constexpr double kCornerWindow = 0.01;

/// Corner–edge contacts of polygon i with polygon j (P5): every corner of i inside j, then every corner of
/// j inside i, in corner order; an edge-to-edge contact gives its two end corners. A corner of j that lies on
/// a corner of i already found (within twice their depths: corner on corner, as in a stack of equal blocks)
/// adds no second point. Appended to `out`.
void polygon_pair_hits(const std::vector<Vec2>& pi, const std::vector<Vec2>& pj, std::vector<CornerHit>& out);

/// Contacts of polygon i (centroid c) with a segment wall a–b (P6): every corner of i that lies on the far
/// side of the wall's line, seen from c, and within the segment's length; or (side 1, corner 0 and 1) an end
/// of the segment inside i. With a point wall (a == b, `point`) only the latter.
void polygon_wall_hits(const std::vector<Vec2>& pi, Vec2 c, Vec2 a, Vec2 b, bool point, std::vector<CornerHit>& out);

/// The contact of polygon i with a disk j of centre q and radius r (P7): the disk's surface point nearest
/// the polygon, one point (side 1, corner 0), if the disk reaches into the polygon.
void polygon_disk_hits(const std::vector<Vec2>& pi, Vec2 q, double r, std::vector<CornerHit>& out);

}  // namespace dem
