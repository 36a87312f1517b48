// Walls (docs/model.md §1 "Walls"): a point wall contacts in every direction; a wall moving with a
// prescribed velocity history carries what rests on it; driven elements follow their drive.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

dem::Model disk_and_walls(double mu) {
  auto m = test::make_model({{"disk", 1000.0}, {"wall", 0.0}}, 1e-5);
  dem::PairLaw law = test::linear_law(1e6, 2.5e5, mu, 0.0, 0.0);
  law.damping_from_ratio = true;
  law.damping_ratio = 0.7;
  test::set_law(m, 0, 1, law);
  test::set_law(m, 0, 0, law);
  return m;
}

}  // namespace

TEST_CASE("A point wall pushes along the line from the point to the centre, in every direction", "[walls]") {
  const double angle = GENERATE(0.0, 0.7, 2.0, 3.5, 5.1);
  CAPTURE(angle);
  auto m = disk_and_walls(0.0);
  dem::Wall p;
  p.name = "corner";
  p.kind = dem::WallKind::point;
  p.a = p.b = {0.0, 0.0};
  p.material = 1;
  m.walls.push_back(p);
  // A disk of radius 1 cm overlapping the point by 1e-5 m in direction `angle`, at rest, no gravity.
  const double r = 0.01, d = r - 1e-5;
  const std::size_t i = dem::add_element(m, dem::Shape::disk, 0, r, {d * std::cos(angle), d * std::sin(angle)});
  m.elements.mass[i] = 1.0;
  m.elements.inv_mass[i] = 1.0;
  dem::Simulation sim(m);
  sim.step();
  const auto& e = sim.model().elements;
  // Force on the disk: K δ = 10 N away from the point, no shear, no moment.
  CHECK_THAT(e.fx[i], WithinAbs(10.0 * std::cos(angle), 1e-9));
  CHECK_THAT(e.fy[i], WithinAbs(10.0 * std::sin(angle), 1e-9));
  CHECK_THAT(e.moment[i], WithinAbs(0.0, 1e-12));
  // The wall feels the opposite force.
  CHECK_THAT(sim.model().walls[0].force.x, WithinAbs(-10.0 * std::cos(angle), 1e-9));
  CHECK_THAT(sim.model().walls[0].force.y, WithinAbs(-10.0 * std::sin(angle), 1e-9));
}

TEST_CASE("A moving wall carries a disk resting on it by friction", "[walls]") {
  auto m = disk_and_walls(0.5);
  m.gravity = {0.0, -9.81};
  dem::VelocityHistory belt;
  belt.t = {0.0, 0.05};
  belt.v = {{0.0, 0.0}, {0.2, 0.0}};  // ramps to 0.2 m/s within 50 ms, then constant
  m.drives.push_back(belt);
  dem::Wall w = test::segment_wall({-1.0, 0.0}, {1.0, 0.0}, 1, "belt");
  w.drive = 0;
  m.walls.push_back(w);
  dem::add_element(m, dem::Shape::disk, 0, 0.01, {0.0, 0.01});
  dem::Simulation sim(m);
  while (sim.time() < 0.3) sim.step();
  const auto& e = sim.model().elements;
  // A disk on a belt accelerating at 4 m/s² < μg rolls without slipping; friction accelerates the
  // centre at a/3 (solid disk, I = ½mr²) during the ramp, then the disk rolls at the belt's speed
  // less r ω, both constant after the ramp: v = a t/3 at the end of the ramp = 0.0667 m/s.
  CHECK_THAT(e.vx[0], WithinAbs(0.2 / 3.0, 2e-3));
  // The contact point (below the centre) moves with the belt: v + r ω = 0.2 m/s (rolling without slip,
  // ω counter-clockwise positive).
  CHECK_THAT(e.vx[0] + 0.01 * e.omega[0], WithinAbs(0.2, 2e-3));
  // The wall itself moved by the integral of its velocity: 0.05·0.2/2 + 0.25·0.2 = 0.055 m.
  CHECK_THAT(sim.model().walls[0].a.x, WithinAbs(-1.0 + 0.055, 1e-4));
}

TEST_CASE("A driven element follows its drive and does not rotate", "[walls]") {
  auto m = disk_and_walls(0.3);
  m.gravity = {0.0, -9.81};
  dem::VelocityHistory drive;
  drive.t = {0.0};
  drive.v = {{0.1, -0.05}};
  m.drives.push_back(drive);
  const std::size_t i = dem::add_element(m, dem::Shape::disk, 0, 0.01, {0.0, 0.5});
  m.elements.motion[i] = dem::Motion::driven;
  m.elements.drive[i] = 0;
  dem::Simulation sim(m);
  for (int k = 0; k < 1000; ++k) sim.step();
  const auto& e = sim.model().elements;
  CHECK_THAT(e.x[i], WithinAbs(0.1 * 0.01, 1e-12));  // 1000 steps of 1e-5 s
  CHECK_THAT(e.y[i], WithinAbs(0.5 - 0.05 * 0.01, 1e-12));
  CHECK(e.phi[i] == 0.0);
}

TEST_CASE("A velocity table in a case file drives a wall, and a wrong entry is a located error", "[walls][case]") {
  const auto path = std::string(DEM2D_SOURCE_DIR) + "/tests/lib/fixtures/drive_table.toml";
  dem::Case c = dem::read_case(path);
  dem::Simulation sim(c.model);
  while (sim.time() < 0.02 - 1e-12) sim.step();
  // Displacement: the ramp's 0.005 m plus 10 ms at 1 m/s.
  CHECK_THAT(sim.model().walls[0].a.x, WithinAbs(-1.0 + 0.015, 1e-9));
  try {
    dem::read_case(path, {"drive.0.times=[0.0, true]"});
    FAIL("a boolean time was accepted");
  } catch (const dem::CaseError& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("drive.0.times") && Catch::Matchers::Contains("expected time"));
  }
}
