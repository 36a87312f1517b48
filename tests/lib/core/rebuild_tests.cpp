// The neighbour list is rebuilt in time: elements (and a moving wall) that start several skins apart
// and then collide give exactly the run with a skin so large that the list never needs a rebuild.
#include <catch2/catch.hpp>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

namespace {

constexpr double r = 0.01;

/// Two disks closing on each other, or a wall closing on a disk at rest (separate models: a moving
/// wall triggers rebuilds that would hide a late rebuild for the pair).
dem::Model approach(double skin, bool wall) {
  auto m = test::make_model({{"disk", 2650.0}, {"wall", 0.0}}, 1e-5);
  m.numerics.skin = skin;  // 0: a quarter of the smallest radius, 2.5 mm
  dem::PairLaw law;
  law.kind = dem::LawKind::linear;
  law.linear.kn = 1e5;
  law.linear.ks = 5e4;
  law.linear.mu = 0.4;
  law.damping_ratio = 0.1;
  test::set_law(m, 0, 0, law);
  test::set_law(m, 0, 1, law);
  if (!wall) {
    // Two disks 9.85 mm (3.9 skins) apart closing at 2 m/s, slightly off-centre. With rebuilds after a
    // whole skin (not half) they would first be candidates 4 steps after touching.
    dem::add_element(m, dem::Shape::disk, 0, r, {0.0, 1.0}, {1.0, 0.0}, 0.0);
    dem::add_element(m, dem::Shape::disk, 0, r, {0.0297, 1.003}, {-1.0, 0.0}, 0.0);
    return m;
  }
  // A disk at rest and a wall 9.9 mm (≈ 4 skins) below it, moving up at 1 m/s.
  dem::add_element(m, dem::Shape::disk, 0, r, {0.5, 0.0});
  dem::VelocityHistory up;
  up.t = {0.0};
  up.v = {{0.0, 1.0}};
  m.drives.push_back(up);
  dem::Wall w = test::segment_wall({0.3, -0.0199}, {0.7, -0.0199}, 1, "piston");
  w.drive = 0;
  m.walls.push_back(w);
  return m;
}

}  // namespace

TEST_CASE("Contacts between elements that start more than a skin apart are found in time", "[neighbours]") {
  const bool wall = GENERATE(false, true);
  CAPTURE(wall);
  dem::Simulation a(approach(0.0, wall)), b(approach(1.0, wall));
  std::size_t most = 0;
  for (int k = 0; k < 2000; ++k) {
    a.step();
    b.step();
    most = std::max(most, a.contact_count());
    REQUIRE(a.contact_count() == b.contact_count());
  }
  CHECK(most == 1);             // the pair, or the wall contact
  CHECK(a.rebuilds() > 3);      // the default skin needed rebuilds
  CHECK(b.rebuilds() == 1);     // the huge skin did not
  const auto& ea = a.model().elements;
  const auto& eb = b.model().elements;
  test::check_same_state(ea, eb);
  if (!wall) CHECK(ea.vx[0] < 0.0);  // the pair bounced
  if (wall) CHECK(ea.vy[0] > 0.5);   // the piston pushed the resting disk
}
