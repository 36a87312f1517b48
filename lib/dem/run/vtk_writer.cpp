#include "dem/run/vtk_writer.hpp"

#include "dem/core/spatial_order.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <string_view>

#include <fmt/format.h>

#include "dem/run/output_files.hpp"

namespace dem {

static_assert(std::endian::native == std::endian::little, "the snapshots declare byte_order=\"LittleEndian\"");

namespace {

/// The XML part of the file, built in memory.
struct Text {
  fmt::memory_buffer buf;
  template <class... Args>
  void print(fmt::format_string<Args...> f, Args&&... args) {
    fmt::format_to(std::back_inserter(buf), f, std::forward<Args>(args)...);
  }
  std::string_view view() const { return {buf.data(), buf.size()}; }
};

template <class T>
constexpr const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  else if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  else return "Int32";
}

/// Arrays in VTK's appended raw encoding: each block is its byte count (UInt64) followed by the values;
/// the XML names each array's offset into the block after the '_' marker.
struct Appended {
  Text& xml;
  std::string data;
  template <class T>
  void array(const char* name, int components, const std::vector<T>& values) {
    xml.print("<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" NumberOfTuples=\"{}\" format=\"appended\" "
              "offset=\"{}\"/>\n",
              vtk_type<T>(), name, components, values.size() / static_cast<std::size_t>(components), data.size());
    const std::uint64_t bytes = values.size() * sizeof(T);
    data.append(reinterpret_cast<const char*>(&bytes), sizeof bytes);
    data.append(reinterpret_cast<const char*>(values.data()), bytes);
  }
};

/// The outline of a PRE (the square of side 2r turned by φ) or a polygon (its corners, P3), counter-clockwise.
std::vector<Vec2> outline(const Model& m, std::size_t i) {
  const Elements& e = m.elements;
  if (e.shape[i] == Shape::polygon) return element_corners(m, i);
  const double cs = std::cos(e.phi[i]), sn = std::sin(e.phi[i]), r = e.radius[i];
  std::vector<Vec2> out;
  for (const auto& [u, v] : {std::pair{r, -r}, std::pair{r, r}, std::pair{-r, r}, std::pair{-r, -r}})
    out.push_back({e.x[i] + cs * u - sn * v, e.y[i] + sn * u + cs * v});
  return out;
}

}  // namespace

void write_vtp(const std::filesystem::path& file, const Simulation& sim) {
  const Elements& e = sim.model().elements;
  const std::vector<Wall>& walls = sim.model().walls;
  const auto contacts = contacts_in_id_order(sim);  // as without spatial reordering (spatial_order.hpp)
  std::vector<std::size_t> ids, pres;  // active elements; active PREs and polygons (indices, in the order of their ids)
  for (std::size_t id = 0; id < e.size(); ++id)
    if (const std::size_t i = sim.index_of(static_cast<std::uint32_t>(id)); e.active[i]) {
      ids.push_back(i);
      if (e.shape[i] != Shape::disk) pres.push_back(i);
    }
  std::vector<std::int64_t> point_of(e.size(), -1);
  for (std::size_t k = 0; k < ids.size(); ++k) point_of[ids[k]] = static_cast<std::int64_t>(k);
  std::vector<std::size_t> point_walls, segment_walls;
  for (std::size_t w = 0; w < walls.size(); ++w) (walls[w].kind == WallKind::point ? point_walls : segment_walls).push_back(w);
  std::vector<const ContactView*> shown;  // contacts between active elements
  for (const auto& c : contacts)
    if (e.active[c.i] && (c.wall || e.active[c.j])) shown.push_back(&c);

  // Points: element centres | PRE corners (4 each), polygon corners | wall points (segment: a, b; point: a) | the contact
  // point r·n of each wall contact. Point data per point kind; zero (or −1 for ids) where it means nothing.
  std::vector<double> xyz, radius, disk_radius, rotation, velocity, force, moment;
  std::vector<std::int64_t> point_element;
  auto point = [&](double x, double y, std::int64_t el, bool centre = false) {
    xyz.insert(xyz.end(), {x, y, 0.0});
    const std::size_t i = el >= 0 ? static_cast<std::size_t>(el) : 0;
    radius.push_back(centre ? e.radius[i] : 0.0);
    disk_radius.push_back(centre && e.shape[i] == Shape::disk ? e.radius[i] : 0.0);
    rotation.push_back(el >= 0 ? e.phi[i] : 0.0);
    velocity.insert(velocity.end(), {centre ? e.vx[i] : 0.0, centre ? e.vy[i] : 0.0, 0.0});
    force.insert(force.end(), {centre ? e.fx[i] : 0.0, centre ? e.fy[i] : 0.0, 0.0});
    moment.push_back(centre ? e.moment[i] : 0.0);
    point_element.push_back(el >= 0 ? static_cast<std::int64_t>(sim.id_of(i)) : el);  // ids, not indices
  };
  for (std::size_t i : ids) point(e.x[i], e.y[i], static_cast<std::int64_t>(i), true);
  std::vector<std::size_t> corner_first;  // per outlined element: its first corner point
  for (std::size_t i : pres) {
    corner_first.push_back(xyz.size() / 3);
    for (const Vec2& q : outline(sim.model(), i)) point(q.x, q.y, static_cast<std::int64_t>(i));
  }
  corner_first.push_back(xyz.size() / 3);
  std::vector<std::size_t> wall_point(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) {
    wall_point[w] = xyz.size() / 3;
    point(walls[w].a.x, walls[w].a.y, -1);
    if (walls[w].kind == WallKind::segment) point(walls[w].b.x, walls[w].b.y, -1);
  }
  std::vector<std::int64_t> contact_a, contact_b;
  for (const ContactView* c : shown) {
    contact_a.push_back(point_of[c->i]);
    if (c->wall) {
      contact_b.push_back(static_cast<std::int64_t>(xyz.size() / 3));
      const double r = e.radius[c->i];
      if (c->at_point) point(c->px, c->py, -1);  // a polygon's contact point
      else point(e.x[c->i] + r * c->nx, e.y[c->i] + r * c->ny, -1);
    } else {
      contact_b.push_back(point_of[c->j]);
    }
  }
  const std::size_t n_points = xyz.size() / 3;

  // Cells in VTK's order: verts (elements, point walls), lines (segment walls, contacts), polys (PREs, polygons).
  std::vector<std::int64_t> vert_conn, vert_off, line_conn, line_off, poly_conn, poly_off;
  std::vector<std::int32_t> kind, links;
  std::vector<std::int64_t> cell_element, cell_other, cell_wall;
  std::vector<double> fn, fs, cell_force;
  auto cell = [&](int k, std::int64_t el, std::int64_t other, std::int64_t wall, double n, double s, double fx, double fy,
                  int l) {
    auto id = [&](std::int64_t i) { return i >= 0 ? static_cast<std::int64_t>(sim.id_of(static_cast<std::size_t>(i))) : i; };
    kind.push_back(k), cell_element.push_back(id(el)), cell_other.push_back(id(other)), cell_wall.push_back(wall);
    fn.push_back(n), fs.push_back(s), cell_force.insert(cell_force.end(), {fx, fy, 0.0}), links.push_back(l);
  };
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::size_t i = ids[k];
    vert_conn.push_back(static_cast<std::int64_t>(k)), vert_off.push_back(static_cast<std::int64_t>(vert_conn.size()));
    cell(0, static_cast<std::int64_t>(i), -1, -1, 0.0, 0.0, e.fx[i], e.fy[i], 0);
  }
  for (std::size_t w : point_walls) {
    vert_conn.push_back(static_cast<std::int64_t>(wall_point[w])), vert_off.push_back(static_cast<std::int64_t>(vert_conn.size()));
    cell(1, -1, -1, static_cast<std::int64_t>(w), 0.0, 0.0, walls[w].force.x, walls[w].force.y, 0);
  }
  for (std::size_t w : segment_walls) {
    line_conn.insert(line_conn.end(), {static_cast<std::int64_t>(wall_point[w]), static_cast<std::int64_t>(wall_point[w] + 1)});
    line_off.push_back(static_cast<std::int64_t>(line_conn.size()));
    cell(2, -1, -1, static_cast<std::int64_t>(w), 0.0, 0.0, walls[w].force.x, walls[w].force.y, 0);
  }
  for (std::size_t k = 0; k < shown.size(); ++k) {
    const ContactView& c = *shown[k];
    line_conn.insert(line_conn.end(), {contact_a[k], contact_b[k]});
    line_off.push_back(static_cast<std::int64_t>(line_conn.size()));
    // the force of i on j (or on the wall): f_n n + f_s t, t = n turned by +90°
    cell(3, c.i, c.wall ? -1 : static_cast<std::int64_t>(c.j), c.wall ? static_cast<std::int64_t>(c.j) : -1, c.fn, c.fs,
         c.fn * c.nx - c.fs * c.ny, c.fn * c.ny + c.fs * c.nx, c.links);
  }
  for (std::size_t k = 0; k < pres.size(); ++k) {
    const std::size_t i = pres[k];
    for (std::size_t q = corner_first[k]; q < corner_first[k + 1]; ++q) poly_conn.push_back(static_cast<std::int64_t>(q));
    poly_off.push_back(static_cast<std::int64_t>(poly_conn.size()));
    cell(4, static_cast<std::int64_t>(i), -1, -1, 0.0, 0.0, e.fx[i], e.fy[i], 0);
  }

  Text out;
  Appended app{out, {}};
  out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
            "header_type=\"UInt64\">\n<PolyData>\n<FieldData>\n");
  app.array("TimeValue", 1, std::vector<double>{sim.time()});
  app.array("step", 1, std::vector<std::int64_t>{sim.steps()});
  out.print("</FieldData>\n");
  out.print("<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
            n_points, vert_off.size(), line_off.size(), poly_off.size());
  out.print("<Points>\n");
  app.array("Points", 3, xyz);
  out.print("</Points>\n<PointData Scalars=\"radius\" Vectors=\"velocity\">\n");
  app.array("radius", 1, radius);
  app.array("disk_radius", 1, disk_radius);
  app.array("rotation", 1, rotation);
  app.array("velocity", 3, velocity);
  app.array("force", 3, force);
  app.array("moment", 1, moment);
  app.array("element_id", 1, point_element);
  out.print("</PointData>\n<CellData Scalars=\"normal_force\" Vectors=\"force\">\n");
  app.array("kind", 1, kind);
  app.array("element_id", 1, cell_element);
  app.array("other_element_id", 1, cell_other);
  app.array("wall_id", 1, cell_wall);
  app.array("normal_force", 1, fn);
  app.array("shear_force", 1, fs);
  app.array("force", 3, cell_force);
  // Linked segments of each contact (M8: a broken segment is unlinked; 1 for a linear contact): a
  // crack shows as faces with fewer links, and a face whose links all broke and whose cores parted
  // is no contact any more (its line is gone).
  app.array("links", 1, links);
  out.print("</CellData>\n");
  for (const auto& [tag, conn, off] : {std::tuple{"Verts", &vert_conn, &vert_off}, std::tuple{"Lines", &line_conn, &line_off},
                                       std::tuple{"Polys", &poly_conn, &poly_off}}) {
    out.print("<{}>\n", tag);
    app.array("connectivity", 1, *conn);
    app.array("offsets", 1, *off);
    out.print("</{}>\n", tag);
  }
  out.print("</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_");
  std::string content(out.view());
  content += app.data;
  content += "\n</AppendedData>\n</VTKFile>\n";
  write_file_atomic(file, content, false);
}

void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& snapshots) {
  Text out;
  out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
  for (const auto& [t, name] : snapshots) out.print("<DataSet timestep=\"{:.17g}\" file=\"{}\"/>\n", t, name);
  out.print("</Collection>\n</VTKFile>\n");
  write_file_atomic(file, out.view(), false);
}

}  // namespace dem
