// The discharge rules act on the elements they name and on no other (lib/dem/core/discharge.hpp):
// remove_discharged removes exactly the active disks whose centre lies below the outlet line (a disk on the
// line stays, one a nanometre below it goes), checked by id and position, not only by count; discharged()
// counts exactly those; keystone() picks the disk over the slit nearest its mid-point, never one beside the
// slit or below the line. The line follows g: with g tilted, "below" is along g, not along −y.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "dem/core/discharge.hpp"
#include "dem/core/model.hpp"
#include "../test_support.hpp"

namespace {

constexpr double kDepth = 0.01;  // the outlet line 1 cm below the slit

/// A floor at y = 0 whose middle wall (index 1) is the slit, from x = −2 cm to 2 cm; disks at `centres`
/// (radii 3.1, 3.2, … mm).
dem::Model silo_floor(const std::vector<dem::Vec2>& centres, dem::Vec2 g = {0.0, -9.81}) {
  auto m = test::make_model({{"disk", 2650.0}, {"wall", 0.0}}, 1e-5);
  m.gravity = g;
  m.walls.push_back(test::segment_wall({-0.1, 0.0}, {-0.02, 0.0}, 1, "left"));
  m.walls.push_back(test::segment_wall({-0.02, 0.0}, {0.02, 0.0}, 1, "gate"));
  m.walls.push_back(test::segment_wall({0.02, 0.0}, {0.1, 0.0}, 1, "right"));
  m.discharge.enabled = true;
  m.discharge.slit = 1;
  m.discharge.outlet_depth = kDepth;
  double r = 0.003;  // distinct radii, so distinct masses: the discharged mass names its disks
  for (const auto c : centres) dem::add_element(m, dem::Shape::disk, 0, r += 1e-4, c);
  return m;
}

std::vector<int> inactive(const dem::Model& m) {
  std::vector<int> out;
  for (std::size_t i = 0; i < m.elements.size(); ++i)
    if (!m.elements.active[i]) out.push_back(static_cast<int>(i));
  return out;
}

}  // namespace

TEST_CASE("discharge: exactly the disks below the outlet line are removed and no other", "[discharge]") {
  const std::vector<dem::Vec2> c = {
      {0.0, 0.005},             // 0: over the slit, above the floor
      {0.0, -kDepth},           // 1: exactly on the line: stays
      {0.001, -kDepth - 1e-9},  // 2: a nanometre below it: goes
      {0.05, -0.02},            // 3: below the line, removed before: not counted again
      {-0.05, 0.004},           // 4: on the floor beside the slit: stays
      {0.0, -0.009},            // 5: between the floor and the line: stays
      {0.08, -0.03},            // 6: below the line beside the slit (the line is infinite): goes
  };
  auto m = silo_floor(c);
  m.elements.active[3] = 0;
  REQUIRE(dem::remove_discharged(m) == 2);
  CHECK(inactive(m) == std::vector<int>{2, 3, 6});
  for (std::size_t i = 0; i < c.size(); ++i) {  // nobody moved or was renumbered
    CHECK(m.elements.x[i] == c[i].x);
    CHECK(m.elements.y[i] == c[i].y);
  }
  CHECK(dem::remove_discharged(m) == 0);  // removed exactly once
  const auto d = dem::discharged(m);
  CHECK(d.count == 3);
  CHECK(d.mass == m.elements.mass[2] + m.elements.mass[3] + m.elements.mass[6]);
  CHECK(dem::below_outlet(m, 0.0, -kDepth) == 0.0);
  CHECK(dem::below_outlet(m, 0.3, -0.03) == Approx(0.02));
}

TEST_CASE("discharge: below means along g when g is tilted", "[discharge]") {
  // g along +x: the outlet line is the vertical x = 1 cm; a disk far below the floor but left of it stays
  const std::vector<dem::Vec2> c = {{0.0, -0.5}, {0.011, 0.0}, {0.009, 0.3}};
  auto m = silo_floor(c, {9.81, 0.0});
  CHECK(dem::remove_discharged(m) == 1);
  CHECK(inactive(m) == std::vector<int>{1});
}

TEST_CASE("discharge: the keystone is the disk over the slit nearest its mid-point and no other", "[discharge]") {
  const std::vector<dem::Vec2> c = {
      {0.05, 0.0001},    // 0: nearest to the mid-point's height but beside the slit
      {0.015, 0.004},    // 1: over the slit, off centre
      {0.003, 0.006},    // 2: over the slit, nearest the mid-point: the keystone
      {0.0, -0.011},     // 3: right under the mid-point but below the line
      {-0.019, 0.0039},  // 4: over the slit near its left end
  };
  auto m = silo_floor(c);
  REQUIRE(dem::keystone(m).has_value());
  CHECK(*dem::keystone(m) == 2);
  m.elements.active[2] = 0;
  CHECK(*dem::keystone(m) == 1);  // then the next nearest over the slit (1 is nearer than 4)
  m.elements.active[1] = 0;
  CHECK(*dem::keystone(m) == 4);
}

TEST_CASE("discharge: of two keystones at the same distance the lower id is taken whatever the index", "[discharge]") {
  auto m = silo_floor({{-0.005, 0.004}, {0.005, 0.004}});  // mirror images: the same distance, bit for bit
  for (const bool swap : {false, true}) {
    m.elements.id = swap ? std::vector<std::uint32_t>{7, 3} : std::vector<std::uint32_t>{3, 7};
    CHECK(*dem::keystone(m) == (swap ? 1u : 0u));
  }
}

TEST_CASE("discharge: the slit's ends are exact - a disk over an end is a keystone - one a nanometre beyond is not", "[discharge]") {
  // The slit runs from x = −2 cm to 2 cm (s = 0 … 1 along it); the disks sit 4 mm above the floor.
  CHECK(!dem::keystone(silo_floor({{0.02 + 1e-9, 0.004}, {-0.02 - 1e-9, 0.004}, {0.05, 0.004}})).has_value());
  CHECK(*dem::keystone(silo_floor({{0.05, 0.004}, {0.02, 0.004}})) == 1);
  CHECK(*dem::keystone(silo_floor({{-0.02, 0.004}, {-0.05, 0.004}})) == 0);
}
