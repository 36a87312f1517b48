#include "dem/run/vtk_writer.hpp"

#include <iterator>
#include <string_view>

#include <fmt/format.h>

#include "dem/run/output_files.hpp"

namespace dem {

namespace {

/// The file's text, built in memory and written whole (write_file_atomic: checked, renamed into place).
struct Text {
  fmt::memory_buffer buf;
  template <class... Args>
  void print(fmt::format_string<Args...> f, Args&&... args) {
    fmt::format_to(std::back_inserter(buf), f, std::forward<Args>(args)...);
  }
  std::string_view view() const { return {buf.data(), buf.size()}; }
};

}  // namespace

void write_vtp(const std::filesystem::path& file, const Simulation& sim) {
  const Elements& e = sim.model().elements;
  const auto contacts = sim.contacts();
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i]) ids.push_back(i);
  // Points: active element centres, then one point per wall contact (the contact point on the wall).
  std::vector<std::size_t> point_of(e.size(), 0);
  for (std::size_t k = 0; k < ids.size(); ++k) point_of[ids[k]] = k;
  std::size_t wall_points = 0;
  for (const auto& c : contacts) wall_points += c.wall;
  Text out;
  out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n");
  out.print("<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\">\n", ids.size() + wall_points,
            ids.size(), contacts.size());
  out.print("<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (std::size_t i : ids) out.print("{:.17g} {:.17g} 0\n", e.x[i], e.y[i]);
  for (const auto& c : contacts)
    if (c.wall) {
      const double r = e.radius[c.i];
      out.print("{:.17g} {:.17g} 0\n", e.x[c.i] + r * c.nx, e.y[c.i] + r * c.ny);
    }
  out.print("</DataArray></Points>\n<PointData Scalars=\"radius\">\n");
  auto scalar = [&](const char* name, auto get) {
    out.print("<DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", name);
    for (std::size_t i : ids) out.print("{:.9g}\n", get(i));
    for (std::size_t k = 0; k < wall_points; ++k) out.print("0\n");
    out.print("</DataArray>\n");
  };
  scalar("radius", [&](std::size_t i) { return e.radius[i]; });
  scalar("rotation", [&](std::size_t i) { return e.phi[i]; });
  scalar("id", [&](std::size_t i) { return static_cast<double>(i); });
  out.print("<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (std::size_t i : ids) out.print("{:.9g} {:.9g} 0\n", e.vx[i], e.vy[i]);
  for (std::size_t k = 0; k < wall_points; ++k) out.print("0 0 0\n");
  out.print("</DataArray>\n</PointData>\n<CellData Scalars=\"normal_force\">\n");
  // Cell data: verts first (no force), then lines.
  for (const char* name : {"normal_force", "shear_force"}) {
    out.print("<DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", name);
    for (std::size_t k = 0; k < ids.size(); ++k) out.print("0\n");
    for (const auto& c : contacts) out.print("{:.9g}\n", name[0] == 'n' ? c.fn : c.fs);
    out.print("</DataArray>\n");
  }
  // Linked segments of each contact (M8: a broken segment is unlinked; 1 for a linear contact): a
  // crack shows as faces with fewer links, and a face whose links all broke and whose cores parted
  // is no contact any more (its line is gone).
  out.print("<DataArray type=\"Int32\" Name=\"links\" format=\"ascii\">\n");
  for (std::size_t k = 0; k < ids.size(); ++k) out.print("0\n");
  for (const auto& c : contacts) out.print("{}\n", c.links);
  out.print("</DataArray>\n");
  out.print("</CellData>\n<Verts><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (std::size_t k = 0; k < ids.size(); ++k) out.print("{}\n", k);
  out.print("</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (std::size_t k = 0; k < ids.size(); ++k) out.print("{}\n", k + 1);
  out.print("</DataArray></Verts>\n<Lines><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  std::size_t wp = ids.size();
  for (const auto& c : contacts) {
    if (c.wall) out.print("{} {}\n", point_of[c.i], wp++);
    else out.print("{} {}\n", point_of[c.i], point_of[c.j]);
  }
  out.print("</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (std::size_t k = 0; k < contacts.size(); ++k) out.print("{}\n", 2 * (k + 1));
  out.print("</DataArray></Lines>\n</Piece>\n</PolyData>\n</VTKFile>\n");
  write_file_atomic(file, out.view(), false);
}

void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& snapshots) {
  Text out;
  out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
  for (const auto& [t, name] : snapshots) out.print("<DataSet timestep=\"{:.9g}\" file=\"{}\"/>\n", t, name);
  out.print("</Collection>\n</VTKFile>\n");
  write_file_atomic(file, out.view(), false);
}

}  // namespace dem
