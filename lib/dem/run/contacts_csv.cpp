#include "dem/run/contacts_csv.hpp"

#include <cmath>
#include <cstdint>
#include <iterator>

#include <fmt/format.h>

#include "dem/cases/text.hpp"
#include "dem/core/spatial_order.hpp"

namespace dem {

std::string contacts_csv_header() {
  return "step,t [s],i,j,wall,law,x [m],y [m],nx,ny,fn [N],fs [N],links,segments,mr [N*m]\n";
}

std::string segment_letters(const Simulation::FaceSegments& f, bool reversed) {
  std::string out;
  for (int k = 0; k < f.n; ++k) {
    const SegmentState& s = f.seg[static_cast<std::size_t>(reversed ? f.n - 1 - k : k)];
    out += s.linked ? (s.intact ? 'B' : 'L') : (s.intact ? 'o' : 'x');
  }
  return out;
}

std::string contacts_csv_rows(const Simulation& sim) {
  const Elements& e = sim.model().elements;
  const std::vector<Wall>& walls = sim.model().walls;
  fmt::memory_buffer out;
  auto to = std::back_inserter(out);
  for (const ContactView& c : contacts_in_id_order(sim)) {  // as the snapshots show them (vtk_writer.cpp)
    if (!e.active[c.i] || (!c.wall && !e.active[c.j])) continue;
    const Vec2 ci{e.x[c.i], e.y[c.i]}, n{c.nx, c.ny};
    // contacts_in_id_order may have turned an element pair round (i > j as indices): then ξ runs the other way
    const Simulation::FaceSegments face = sim.face_segments(c.i, c.j, c.wall);
    Vec2 point;
    if (c.wall) {
      point = closest_point(walls[c.j], ci);
    } else if (face.n > 0) {  // the face centre
      const Vec2 cj{e.x[c.j], e.y[c.j]};
      point = ci + (cj - ci) * (e.radius[c.i] / (e.radius[c.i] + e.radius[c.j]));
    } else {  // the middle of the overlap δ = r_i + r_j − d: r_i − δ/2 from i along n
      const double d = std::hypot(e.x[c.j] - ci.x, e.y[c.j] - ci.y);
      point = ci + n * (0.5 * (d + e.radius[c.i] - e.radius[c.j]));
    }
    fmt::format_to(to, "{},{:.17g},{},{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{},{},{:.17g}\n", sim.steps(),
                   sim.time(), sim.id_of(c.i), c.wall ? std::int64_t{-1} : std::int64_t{sim.id_of(c.j)},
                   c.wall ? csv_field(walls[c.j].name) : std::string(), face.n > 0 ? "face" : "linear", point.x, point.y,
                   c.nx, c.ny, c.fn, c.fs, c.links, segment_letters(face, !c.wall && c.i > c.j), c.mr);
  }
  return {out.data(), out.size()};
}

}  // namespace dem
