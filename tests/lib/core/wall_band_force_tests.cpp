// The wall force per band along a wall (the silo's wall-force depth profile, refs §6.1):
// <wall>.fn(s0,s1), <wall>.fs(s0,s1) and walls.fx / walls.fy (quantities.hpp).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/quantities.hpp"
#include "../test_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// Two fixed disks (r = 1 cm) overlapping the wall "floor" from (0,0) to (1 m,0): e0 over its interior
// at x = 0.3 m, overlap 1 mm; e1 below-left of its end a = (0,0), centre (−6 mm, −6 mm), overlap
// r − 6√2 mm. Fixed elements do not move, so after one step every contact carries exactly K × overlap.
const char* kCase = R"([case]
title = "bands"
[physics]
gravity = ["0 m/s^2", "-9.80665 m/s^2"]
[[material]]
name = "sand"
density = "2.65 g/cm^3"
[[material]]
name = "wall"
[[contact]]
between = ["sand", "sand"]
law = "linear"
kn = "1e6 N/m"
ks = "2.5e5 N/m"
friction = 0.3
[[contact]]
between = ["sand", "wall"]
law = "linear"
kn = "1e6 N/m"
ks = "2.5e5 N/m"
friction = 0.3
[[element]]
material = "sand"
radius = "1 cm"
position = ["0.3 m", "9 mm"]
motion = "fixed"
[[element]]
material = "sand"
radius = "1 cm"
position = ["-6 mm", "-6 mm"]
motion = "fixed"
[[wall]]
name = "floor"
from = ["0 m", "0 m"]
to = ["1 m", "0 m"]
material = "wall"
[numerics]
dt = "1e-5 s"
duration = "1 ms"
)";

double q(const std::string& name, const dem::Simulation& s) { return dem::compile_quantity(name, s.model())(s); }

}  // namespace

TEST_CASE("Wall force per band along a wall sums the contacts whose contact point lies in the band", "[silo][quantities]") {
  const dem::Case c = dem::read_case(test::write_temp("bands.toml", kCase), {});
  dem::Simulation sim(c.model);
  sim.step();
  const double k = 1e6, f0 = k * 1e-3, d1 = 6e-3 * std::sqrt(2.0), f1 = k * (1e-2 - d1);
  // e0: a normal force f0 at s = 0.3 m, no tangential part (the normal is perpendicular to the wall)
  CHECK_THAT(q("floor.fn(0.2,0.4)", sim), WithinRel(f0, 1e-12));
  CHECK_THAT(q("floor.fs(0.2,0.4)", sim), WithinAbs(0.0, 1e-12 * f0));
  CHECK_THAT(q("floor.fn(0.3001,1)", sim), WithinAbs(0.0, 0.0));  // nothing beyond e0
  CHECK_THAT(q("floor.fn(0.3,0.31)", sim), WithinRel(f0, 1e-12)); // s0 is inside the band
  CHECK_THAT(q("floor.fn(0.29,0.3)", sim), WithinAbs(0.0, 0.0));  // s1 is not
  // e1 touches the end a: the normal points from its centre to a, at 45°; the force on the wall f1 n has
  // the part f1 cos 45° along a→b
  CHECK_THAT(q("floor.fn(0,0.1)", sim), WithinRel(f1, 1e-9));
  CHECK_THAT(q("floor.fs(0,0.1)", sim), WithinRel(f1 / std::sqrt(2.0), 1e-9));
  // bands that cover the wall add up to the wall's force
  const double fy_wall = sim.model().walls[0].force.y, fx_wall = sim.model().walls[0].force.x;
  CHECK_THAT(q("floor.fs(0,1)", sim), WithinRel(fx_wall, 1e-12));
  CHECK_THAT(-q("floor.fn(0,1)", sim), !WithinRel(fy_wall, 1e-3));  // e1's normal is not vertical: it
  CHECK_THAT(-f0 + f1 / std::sqrt(2.0), WithinRel(fy_wall, 1e-9));  // pushes the wall up by f1 sin 45°
  CHECK_THAT(q("walls.fy", sim), WithinRel(fy_wall, 1e-15));
  CHECK_THAT(q("walls.fx", sim), WithinRel(fx_wall, 1e-15));
}

TEST_CASE("Wall band quantities refuse a malformed band or an unknown wall", "[silo][quantities]") {
  const dem::Case c = dem::read_case(test::write_temp("bands_bad.toml", kCase), {});
  const dem::Model& m = c.model;
  CHECK_THROWS_WITH(dem::compile_quantity("floor.fn(0.4)", m), Contains("s0 < s1"));
  CHECK_THROWS_WITH(dem::compile_quantity("floor.fn(0.5,0.2)", m), Contains("s0 < s1"));
  CHECK_THROWS_WITH(dem::compile_quantity("floor.fs(a,0.2)", m), Contains("in metres"));
  CHECK_THROWS(dem::compile_quantity("roof.fn(0,1)", m));
  CHECK_NOTHROW(dem::compile_quantity("floor.fs(0,1)", m));
}
