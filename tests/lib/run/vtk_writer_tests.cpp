// The binary ParaView snapshots (lib/dem/run/vtk_writer.hpp) read back without VTK: cells in VTK's order
// with their kinds, the contact force vector, ids that tell elements from walls, PRE squares. (VTK's
// own reader checks the same files in `ctest -L tools`.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "dem/cases/case_file.hpp"
#include "dem/run/vtk_writer.hpp"
#include "dem/core/simulation.hpp"

#include "../test_support.hpp"
#include "../vtp_reader.hpp"

namespace fs = std::filesystem;

TEST_CASE("vtk: a disk on a floor gives its centre, the wall as a line and the contact force vector", "[vtk]") {
  dem::Case c = dem::read_case(test::source("cases/basic/rest_on_wall.toml"));
  dem::Simulation sim(c.model);
  for (int k = 0; k < 100; ++k) sim.step();
  const auto out = test::fresh_dir("dem2d_unit_vtk", "rest");
  fs::create_directories(out);
  write_vtp(out / "s.vtp", sim);
  const std::string v = test::slurp(out / "s.vtp");
  CHECK(v.find("format=\"ascii\"") == std::string::npos);
  CHECK(v.find("NumberOfPoints=\"4\" NumberOfVerts=\"1\" NumberOfLines=\"2\" NumberOfStrips=\"0\" NumberOfPolys=\"0\"") !=
        std::string::npos);
  CHECK(test::vtp_array<std::int32_t>(v, "kind") == std::vector<std::int32_t>{0, 2, 3});
  CHECK(test::vtp_array<std::int64_t>(v, "wall_id") == std::vector<std::int64_t>{-1, 0, 0});
  CHECK(test::vtp_array<std::int64_t>(v, "other_element_id") == std::vector<std::int64_t>{-1, -1, -1});
  const auto contact = sim.contact(0, 0, true);
  REQUIRE(contact.fn > 0.0);
  const auto fn = test::vtp_array<double>(v, "normal_force");
  REQUIRE(fn.size() == 3);
  CHECK(fn[2] == contact.fn);
  // The contact's force vector (the disk's force on the floor, f_n n, n downwards) and the element's
  // resultant (gravity plus the contact) in the cell data.
  const auto cell_force = test::vtp_array<double>(v, "force", "<CellData");
  REQUIRE(cell_force.size() == 9);
  CHECK(cell_force[6] == Approx(0.0).margin(1e-9));
  CHECK(cell_force[7] == -contact.fn);
  CHECK(cell_force[1] == sim.model().elements.fy[0]);
  CHECK(test::vtp_array<double>(v, "force")[1] == sim.model().elements.fy[0]);  // point data: the same
  const auto points = test::vtp_array<double>(v, "Points");
  REQUIRE(points.size() == 12);
  CHECK(points[9] == Approx(sim.model().elements.x[0]).margin(1e-12));
  CHECK(points[10] == Approx(sim.model().elements.y[0] - 0.01).margin(1e-12));  // the contact point r n below
  const auto conn = test::vtp_array<std::int64_t>(v, "connectivity");
  CHECK(conn == std::vector<std::int64_t>{0});  // verts: the element's centre
}

TEST_CASE("vtk: a PRE is drawn as its turned square", "[vtk]") {
  dem::Case c = dem::read_case(test::source("cases/pre/block_mode.toml"));
  dem::Simulation sim(c.model);
  sim.step();
  const auto out = test::fresh_dir("dem2d_unit_vtk", "pre");
  fs::create_directories(out);
  write_vtp(out / "s.vtp", sim);
  const std::string v = test::slurp(out / "s.vtp");
  CHECK(v.find("NumberOfPolys=\"3\"") != std::string::npos);
  const auto pts = test::vtp_array<double>(v, "Points");
  const dem::Elements& e = sim.model().elements;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t q = 0; q < 4; ++q) {
      const std::size_t p = 3 + 4 * i + q;
      CHECK(std::hypot(pts[3 * p] - e.x[i], pts[3 * p + 1] - e.y[i]) == Approx(e.radius[i] * std::sqrt(2.0)));
    }
  const auto kind = test::vtp_array<std::int32_t>(v, "kind");
  CHECK(std::count(kind.begin(), kind.end(), 4) == 3);
  CHECK(kind.back() == 4);
}

namespace {
/// A disk (r = 1 cm) touching a wall inclined at 45° below it on the right (overlap 0.1 mm), no gravity;
/// the wall contact's normal n = (1, −1)/√2.
dem::Model disk_on_inclined_wall() {
  dem::Model m = test::make_model({{"d", 2650.0}, {"w", 0.0}}, 1e-6);
  test::set_law(m, 0, 1, test::linear_law(1e5, 0.0, 0.5, 0.0, 0.0));
  dem::add_element(m, dem::Shape::disk, 0, 0.01, {0.0, 0.0}, {}, 0.0, dem::PreMass::square, 0.1);
  const double s = std::sqrt(0.5), d = 0.0099;
  const dem::Vec2 foot{d * s, -d * s}, t{s, s};
  m.walls.push_back(test::segment_wall(foot - t * 0.05, foot + t * 0.05, 1, "slope"));
  return m;
}

/// Three disks in a row, each touching the next (overlap 0.1 mm), no gravity, no walls.
dem::Model three_in_a_row() {
  dem::Model m = test::make_model({{"d", 2650.0}}, 1e-6);
  test::set_law(m, 0, 0, test::linear_law(1e5, 0.0, 0.5, 0.0, 0.0));
  for (int k = 0; k < 3; ++k)
    dem::add_element(m, dem::Shape::disk, 0, 0.01, {0.0199 * k, 0.0}, {}, 0.0, dem::PreMass::square, 0.1);
  return m;
}
}  // namespace

TEST_CASE("vtk: a wall contact's point is r n from the centre on an inclined wall too", "[vtk]") {
  dem::Simulation sim(disk_on_inclined_wall());
  sim.step();
  const auto contact = sim.contact(0, 0, true);
  REQUIRE(contact.fn > 0.0);
  REQUIRE(contact.nx == Approx(std::sqrt(0.5)).epsilon(1e-6));
  REQUIRE(contact.ny == Approx(-std::sqrt(0.5)).epsilon(1e-6));
  const auto out = test::fresh_dir("dem2d_unit_vtk", "inclined");
  fs::create_directories(out);
  write_vtp(out / "s.vtp", sim);
  const auto points = test::vtp_array<double>(test::slurp(out / "s.vtp"), "Points");
  REQUIRE(points.size() == 12);  // the centre, the wall's two ends, the contact point
  const dem::Elements& e = sim.model().elements;
  CHECK(points[9] == Approx(e.x[0] + 0.01 * contact.nx).margin(1e-12));
  CHECK(points[10] == Approx(e.y[0] + 0.01 * contact.ny).margin(1e-12));
}

TEST_CASE("vtk: the contacts of an element removed after a step are not written", "[vtk]") {
  // The slots of a step keep the contacts of an element removed after it (a discharged disk, a keystone)
  // until the next step; the snapshot of that step shows neither the element nor its contacts.
  const std::uint32_t removed = GENERATE(0u, 2u);  // the first of its pair or the second
  CAPTURE(removed);
  dem::Simulation sim(three_in_a_row());
  sim.step();
  REQUIRE(sim.contacts().size() == 2);
  sim.model().elements.active[sim.index_of(removed)] = 0;
  const auto out = test::fresh_dir("dem2d_unit_vtk", "removed");
  fs::create_directories(out);
  write_vtp(out / "s.vtp", sim);
  const std::string v = test::slurp(out / "s.vtp");
  CHECK(v.find("NumberOfPoints=\"2\" NumberOfVerts=\"2\" NumberOfLines=\"1\"") != std::string::npos);
  CHECK(test::vtp_array<std::int64_t>(v, "connectivity") == std::vector<std::int64_t>{0, 1});  // verts: the two centres
}
