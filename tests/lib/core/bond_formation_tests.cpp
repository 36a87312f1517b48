// Which faces are bonded at the start (face_geometry.hpp, docs/model.md M8–M10): a face touching at
// t = 0 is bonded iff its two PREs belong to the same bonded [[lattice]] (one group each), or its
// contact law says `bonded = true` (then every touching face, walls included). Two touching lattices
// are two groups: no bond between them; a lattice with `bonded = false` and a lone [[element]] belong
// to no group. Checked pair by pair, the elements found by position (not by their index). A loose PRE
// pair with a tensile strength carries no tension: pulled apart it opens; a bonded pair holds.
// Planted bugs that turned this red: any two grouped PREs bonded (group[i] >= 0 && group[j] >= 0, the
// equality dropped); the law's `bonded` ignored for walls.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/core/stability_eigen.hpp"

#include "../test_support.hpp"

namespace {

// Lattice A: (0,0), (20,0) mm; lattice B: (40,0), (60,0) mm (touches A between 20 and 40); lattice C
// (bonded = false): (0,20), (20,20) mm on top of A, read between A and B (so that A's last element
// touches C's last, the index after it); a lone element at (79.9,0) mm (overlapping B by 0.1 mm); a floor under A and B.
std::string blocks(bool law_bonded, double vx_lone) {
  const std::string b = law_bonded ? "true" : "false";
  return R"(
[case]
title = "bond formation"
[[material]]
name = "block"
density = 2000.0
[[material]]
name = "floor"
[[contact]]
between = ["block", "block"]
law = "face"
segments = 2
kn = 1e6
friction = 0.5
tensile_strength = "1 GPa"
cohesion = "1 GPa"
bonded = )" + b + R"(
[[contact]]
between = ["block", "floor"]
law = "face"
segments = 2
positions = "ends"
kn = 1e6
friction = 0.5
tensile_strength = "1 GPa"
bonded = )" + b + R"(
[[lattice]]
shape = "pre"
material = "block"
radius = 0.01
origin = [0.0, 0.0]
columns = 2
rows = 1
[[lattice]]
shape = "pre"
material = "block"
radius = 0.01
origin = [0.0, 0.02]
columns = 2
rows = 1
bonded = false
[[lattice]]
shape = "pre"
material = "block"
radius = 0.01
origin = [0.04, 0.0]
columns = 2
rows = 1
[[element]]
shape = "pre"
material = "block"
radius = 0.01
position = [0.0799, 0.0]
velocity = [)" + std::to_string(vx_lone) + R"(, 0.0]
[[wall]]
name = "floor"
from = [-0.01, -0.01]
to = [0.07, -0.01]
material = "floor"
[numerics]
dt = 1e-6
duration = 1e-3
)";
}

std::uint32_t at(const dem::Simulation& s, double x_mm, double y_mm) {
  const dem::Elements& e = s.model().elements;
  for (std::uint32_t i = 0; i < e.size(); ++i)
    if (std::abs(e.x[i] - x_mm * 1e-3) < 1e-4 && std::abs(e.y[i] - y_mm * 1e-3) < 1e-4) return i;
  FAIL("no element at (" << x_mm << ", " << y_mm << ") mm");
  return 0;
}

/// -1: no face contact; 1: every segment linked and bonded; 0: every segment linked, none bonded.
int bonded(const dem::Simulation& s, std::uint32_t i, std::uint32_t j, bool wall = false) {
  const dem::Simulation::FaceSegments f = s.face_segments(i, j, wall);
  if (f.n == 0) return -1;
  int intact = 0, linked = 0;
  for (int k = 0; k < f.n; ++k) intact += f.seg[k].intact, linked += f.seg[k].linked;
  REQUIRE(linked == f.n);
  REQUIRE((intact == 0 || intact == f.n));
  return intact == f.n ? 1 : 0;
}

}  // namespace

TEST_CASE("Bonds at the start: within one bonded lattice only unless the law bonds every face", "[face][bonds]") {
  for (bool law_bonded : {false, true}) {
    CAPTURE(law_bonded);
    dem::Simulation s(dem::read_case(test::write_temp("bond_formation.toml", blocks(law_bonded, 0.0))).model);
    s.step();
    const std::uint32_t a0 = at(s, 0, 0), a1 = at(s, 20, 0), b0 = at(s, 40, 0), b1 = at(s, 60, 0);
    const std::uint32_t c0 = at(s, 0, 20), c1 = at(s, 20, 20), lone = at(s, 79.9, 0);
    const int across = law_bonded ? 1 : 0;
    CHECK(bonded(s, a0, a1) == 1);       // lattice A
    CHECK(bonded(s, b0, b1) == 1);       // lattice B
    CHECK(bonded(s, a1, b0) == across);  // A–B: two groups
    CHECK(bonded(s, c0, c1) == across);  // lattice C: bonded = false
    CHECK(bonded(s, a0, c0) == across);  // A–C
    CHECK(bonded(s, a1, c1) == across);
    CHECK(bonded(s, b1, lone) == across);  // a lone element
    CHECK(bonded(s, a0, c1) == -1);        // diagonal neighbours do not touch
    CHECK(bonded(s, a0, 0, true) == across);  // the floor: only by the law
    CHECK(bonded(s, b1, 0, true) == across);
  }
}

TEST_CASE("A loose PRE with a tensile strength carries no tension - a bonded one holds", "[face][bonds]") {
  for (bool law_bonded : {false, true}) {
    CAPTURE(law_bonded);
    // the lone element leaves B's last element at 0.05 m/s: 50 um in 1 ms, far beyond the springs' reach
    dem::Simulation s(dem::read_case(test::write_temp("bond_loose.toml", blocks(law_bonded, 0.05))).model);
    const std::uint32_t b1 = at(s, 60, 0), lone = at(s, 79.9, 0);
    double most_tension = 0.0;
    for (int k = 0; k < 1000; ++k) {
      s.step();
      most_tension = std::min(most_tension, s.contact(b1, lone, false).fn);
    }
    if (law_bonded) {
      CHECK(s.face_segments(b1, lone, false).n == 2);  // still joined
      CHECK(most_tension < -1.0);                     // [N]: the bond pulls back
    } else {
      CHECK(s.face_segments(b1, lone, false).n == 0);  // opened at once
      CHECK(most_tension == 0.0);
    }
  }
}

// The time-step guard's start network (stability_eigen.hpp, G1) must see the bonds the step makes: the
// elements of the two bonded lattices, and every touching element when the law bonds. Planted bug that
// turned this red (mutant g578749-017): the group of element i + 1 compared instead of i's.
TEST_CASE("The eigen guard sees the bonds the first step makes", "[face][bonds][stability]") {
  for (bool law_bonded : {false, true}) {
    CAPTURE(law_bonded);
    const dem::Model m = dem::read_case(test::write_temp("bond_guard.toml", blocks(law_bonded, 0.0))).model;
    const dem::StartNetwork net = dem::start_network(m);
    dem::Simulation s(m);
    const double places[7][2] = {{0, 0}, {20, 0}, {40, 0}, {60, 0}, {0, 20}, {20, 20}, {79.9, 0}};
    for (const auto& p : places) {
      const double x = p[0], y = p[1];
      CAPTURE(x, y);
      const bool in_lattice = y == 0.0 && x < 70.0;
      CHECK(net.bonded.at(at(s, x, y)) == ((law_bonded || in_lattice) ? 1 : 0));
    }
    CHECK(net.any_bond);
  }
}

// A structure bonded by its lattices alone (no law says bonded) is a bonded structure for the time-step
// guard (stability.cpp, start_network_if_bonded): its start network is assembled and its λ_max found.
// Planted bug that turned this red (g578749-015): the scan over the elements' groups never ran.
TEST_CASE("The guard assembles the start network of a structure bonded by its lattices alone", "[face][bonds][stability]") {
  const dem::Model m = dem::read_case(test::write_temp("bond_guard_groups.toml", blocks(false, 0.0))).model;
  const dem::StabilityBound b = dem::Simulation(m).stability_bound();
  CHECK(b.lambda_max > 0.0);
  CHECK(b.lambda_max == dem::network_eigenvalue(dem::start_network(m), false, false));
}
