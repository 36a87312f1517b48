// Simulation's polygon elements (docs/model.md §5, P1–P8): their candidate slots at a rebuild, and the sweep of
// a step that finds their contact points (corner_contacts.hpp) and advances each point's linear contact law
// (K6–K14) with the increments of the step at that point. One thread: a model with polygons steps on one
// thread (threads_asked), so its results are the same for every thread count. Called by step() and by the
// reference step alike, after the other contact sweeps (the order of the sums is the same in both).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "dem/core/simulation.hpp"
#include "dem/core/step_loops.hpp"

namespace dem {

using step_detail::key;

namespace {

bool is_polygon(const Elements& e, std::uint32_t i) { return e.shape[i] == Shape::polygon; }

/// Merges fresh slots into the old ones (both sorted by (i, j)): a fresh slot keeps the old one's points.
void merge_slots(std::vector<PolygonSlot>& old, std::vector<PolygonSlot>& fresh) {
  std::size_t o = 0;
  for (PolygonSlot& f : fresh) {
    while (o < old.size() && key(old[o].i, old[o].j) < key(f.i, f.j)) ++o;
    if (o < old.size() && old[o].i == f.i && old[o].j == f.j) f.corners = std::move(old[o].corners);
  }
  old.swap(fresh);
}

}  // namespace

void Simulation::check_polygon_model() {
  const Elements& e = m_.elements;
  polygons_ = std::any_of(e.shape.begin(), e.shape.end(), [](Shape s) { return s == Shape::polygon; });
  if (!polygons_) return;
  if (m_.polygon_of.size() != e.size()) throw std::invalid_argument("Model::polygon_of must name a shape for every element");
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (e.shape[i] == Shape::pre) throw std::invalid_argument("a case with polygon elements cannot hold PREs (not modelled yet)");
    const std::int32_t p = m_.polygon_of[i];
    if ((e.shape[i] == Shape::polygon) != (p >= 0) || p >= static_cast<std::int32_t>(m_.polygons.size()))
      throw std::invalid_argument(fmt::format("element {}: Model::polygon_of does not match its shape", i));
  }
  for (const PairLaw& law : m_.laws) {
    if (law.kind != LawKind::linear) throw std::invalid_argument("a case with polygon elements takes linear contact laws only");
    if (law.rolling.enabled) throw std::invalid_argument("rolling resistance is not modelled for polygon elements");
  }
  if (m_.numerics.reorder_every > 0) throw std::invalid_argument("numerics.reorder_every is not available with polygon elements");
  if (m_.base_plate.enabled)  // M21's force and spin torque are a disk's or a square's (base_friction.hpp), not a polygon's
    throw std::invalid_argument("base friction (M21) is not modelled for polygon elements yet");
}

void Simulation::rebuild_polygons() {
  const Elements& e = m_.elements;
  std::vector<PolygonSlot> fresh;
  for (const CandidatePair& p : candidates_) {
    if (!is_polygon(e, p.i) && !is_polygon(e, p.j)) continue;
    const std::int32_t law = m_.law_index(e.material[p.i], e.material[p.j]);
    if (law < 0) continue;
    PolygonSlot s;
    s.i = p.i, s.j = p.j, s.law = law, s.swapped = !is_polygon(e, p.i);
    fresh.push_back(std::move(s));
  }
  merge_slots(polygon_pairs_, fresh);
  fresh.clear();
  for (std::uint32_t i = 0; i < e.size(); ++i) {
    if (!is_polygon(e, i) || !e.active[i]) continue;
    const Vec2 c{e.x[i], e.y[i]};
    for (std::uint32_t w = 0; w < m_.walls.size(); ++w) {
      const Wall& wall = m_.walls[w];
      const std::int32_t law = m_.law_index(e.material[i], wall.material);
      if (wall.open || law < 0) continue;
      const double cut = e.radius[i] + skin_;
      const Vec2 d = closest_point(wall, c) - c;
      if (dot(d, d) >= cut * cut) continue;
      PolygonSlot s;
      s.i = i, s.j = w, s.law = law;
      fresh.push_back(std::move(s));
    }
  }
  merge_slots(polygon_walls_, fresh);
}

void Simulation::advance_corners(PolygonSlot& s, std::uint32_t a, std::uint32_t b, bool wall, double inv_dt) {
  Elements& e = m_.elements;
  const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
  const Vec2 wall_step = wall ? m_.walls[b].increment : Vec2{};
  corner_scratch_.clear();
  for (const CornerHit& hit : hits_) {
    CornerSlot c;
    const auto old = std::find_if(s.corners.begin(), s.corners.end(),
                                  [&](const CornerSlot& o) { return o.side == hit.side && o.corner == hit.corner; });
    const bool fresh = old == s.corners.end();
    if (!fresh) c = *old;
    c.side = hit.side, c.corner = hit.corner;
    // (P8): the step's displacement of each body's material point at the contact point
    const Vec2 ra = hit.point - Vec2{e.x[a], e.y[a]};
    const Vec2 rb = wall ? Vec2{} : hit.point - Vec2{e.x[b], e.y[b]};
    Vec2 u{e.dx[a] - e.dphi[a] * ra.y, e.dy[a] + e.dphi[a] * ra.x};
    if (wall) u = u - wall_step;
    else u = u - Vec2{e.dx[b] - e.dphi[b] * rb.y, e.dy[b] + e.dphi[b] * rb.x};
    const Vec2 n = hit.normal, t = perp(n);
    const double du_n = dot(u, n), du_s = dot(u, t);  // (K5.a, K5.b) at the point, approach positive
    if (fresh) start_linear(s.law, hit.depth, du_n, du_s, e.mass[a], wall ? 0.0 : e.mass[b], c.eta_n, c.eta_s, c.h);
    const ContactForce f = linear_contact_force(law.linear, c.eta_n, c.eta_s, du_n, du_s, inv_dt, c.h);  // (K6–K14)
    if (f.opened) continue;  // (K8): the point's contact ends
    c.f = f, c.px = hit.point.x, c.py = hit.point.y, c.nx = n.x, c.ny = n.y;
    const Vec2 force = n * (-f.fn) - t * f.fs;  // (K15.a, K15.b) on a; on b (or the wall) the opposite
    e.fx[a] += force.x, e.fy[a] += force.y;
    e.moment[a] += cross(ra, force);  // (P8): the lever of the contact point
    if (wall) {
      m_.walls[b].force = m_.walls[b].force - force;
    } else {
      e.fx[b] -= force.x, e.fy[b] -= force.y;
      e.moment[b] -= cross(rb, force);
    }
    corner_scratch_.push_back(c);
  }
  s.corners.swap(corner_scratch_);
}

void Simulation::sweep_polygons(double inv_dt) {
  if (!polygons_) return;
  const Elements& e = m_.elements;
  // every active polygon's corners once per step (P3), whatever number of slots it is in
  corner_cache_.resize(m_.polygons.size());
  for (std::uint32_t i = 0; i < e.size(); ++i)
    if (is_polygon(e, i) && e.active[i]) element_corners(m_, i, corner_cache_[static_cast<std::size_t>(m_.polygon_of[i])]);
  auto corners = [&](std::uint32_t i) -> const std::vector<Vec2>& {
    return corner_cache_[static_cast<std::size_t>(m_.polygon_of[i])];
  };
  for (PolygonSlot& s : polygon_pairs_) {
    const std::uint32_t a = s.swapped ? s.j : s.i, b = s.swapped ? s.i : s.j;
    hits_.clear();
    if (e.active[a] && e.active[b]) {
      if (is_polygon(e, b)) polygon_pair_hits(corners(a), corners(b), hits_);               // (P5)
      else polygon_disk_hits(corners(a), {e.x[b], e.y[b]}, e.radius[b], hits_);  // (P7)
    }
    advance_corners(s, a, b, false, inv_dt);
  }
  for (PolygonSlot& s : polygon_walls_) {
    const Wall& w = m_.walls[s.j];
    hits_.clear();
    if (e.active[s.i] && !w.open)
      polygon_wall_hits(corners(s.i), {e.x[s.i], e.y[s.i]}, w.a, w.kind == WallKind::point ? w.a : w.b,
                        w.kind == WallKind::point, hits_);  // (P6)
    advance_corners(s, s.i, s.j, true, inv_dt);
  }
}

double Simulation::polygon_elastic_energy() const {
  double sum = 0.0;
  for (const auto* list : {&polygon_pairs_, &polygon_walls_})
    for (const PolygonSlot& s : *list) {
      const LinearSpringDashpot& l = m_.laws[static_cast<std::size_t>(s.law)].linear;
      for (const CornerSlot& c : s.corners) {
        if (l.kn > 0.0) sum += 0.5 * c.h.en * c.h.en / l.kn;
        if (l.ks > 0.0) sum += 0.5 * c.h.es * c.h.es / l.ks;
      }
    }
  return sum;
}

void Simulation::polygon_contacts(std::vector<ContactView>& out) const {
  for (const auto* list : {&polygon_pairs_, &polygon_walls_}) {
    const bool wall = list == &polygon_walls_;
    for (const PolygonSlot& s : *list)
      for (const CornerSlot& c : s.corners) {
        const double sign = s.swapped ? -1.0 : 1.0;  // the normal from the slot's i towards its j
        // (t flips with n: f_s keeps its sign)
        out.push_back({s.i, s.j, wall, sign * c.nx, sign * c.ny, c.f.fn, c.f.fs, 1, 0.0, true, c.px, c.py});
      }
  }
}

const PolygonSlot* Simulation::polygon_slot(std::uint32_t i, std::uint32_t j, bool wall) const {
  const std::vector<PolygonSlot>& list = wall ? polygon_walls_ : polygon_pairs_;
  const auto it = std::lower_bound(list.begin(), list.end(), key(i, j),
                                   [](const PolygonSlot& s, std::uint64_t k) { return key(s.i, s.j) < k; });
  return it != list.end() && it->i == i && it->j == j && !it->corners.empty() ? &*it : nullptr;
}

}  // namespace dem
