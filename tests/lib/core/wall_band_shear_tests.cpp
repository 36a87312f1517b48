// The shear force per wall band and its sign (<wall>.fs(s0,s1), quantities.hpp; Simulation::wall_band_force):
// a disk driven along a wall, pressed into it by a fixed overlap δ, slides once its shear spring reaches
// μ K_n δ (K-law Coulomb limit, no dashpots). The friction on the wall then drags it along the disk's
// motion: fs = +μ fn when the disk moves along a→b, −μ fn against it or with a and b swapped, and only in
// the band that holds the contact point. Planted bug that turned this red: the band's tangential part
// taken along b→a (the sign of the projection flipped).
#include <catch2/catch.hpp>

#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/quantities.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

std::string sliding_disk(double vx, bool reversed) {
  const std::string from = reversed ? "[\"1 m\", \"0 m\"]" : "[\"0 m\", \"0 m\"]";
  const std::string to = reversed ? "[\"0 m\", \"0 m\"]" : "[\"1 m\", \"0 m\"]";
  return R"([case]
title = "band shear"
[[material]]
name = "sand"
density = "2.65 g/cm^3"
[[material]]
name = "wall"
[[contact]]
between = ["sand", "wall"]
law = "linear"
kn = "1e6 N/m"
ks = "2.5e5 N/m"
friction = 0.3
[[drive]]
name = "slide"
velocity = [)" + std::to_string(vx) + R"(, 0.0]
[[element]]
material = "sand"
radius = "1 cm"
position = ["0.5 m", "9 mm"]
motion = "driven"
drive = "slide"
[[wall]]
name = "floor"
from = )" + from + R"(
to = )" + to + R"(
material = "wall"
[numerics]
dt = "1e-5 s"
duration = "10 ms"
)";
}

double q(const std::string& name, const dem::Simulation& s) { return dem::compile_quantity(name, s.model())(s); }

}  // namespace

TEST_CASE("The shear force per wall band is mu fn along the sliding disk's motion", "[silo][quantities]") {
  const double fn = 1e6 * 1e-3, slide = 0.3 * fn;  // K_n δ, μ K_n δ [N]
  for (const auto& [vx, reversed] : {std::pair{0.1, false}, std::pair{-0.1, false}, std::pair{0.1, true}, std::pair{-0.05, true}}) {
    CAPTURE(vx, reversed);
    dem::Simulation sim(dem::read_case(test::write_temp("band_shear.toml", sliding_disk(vx, reversed)), {}).model);
    for (int k = 0; k < 3000; ++k) sim.step();  // slides after μ K_n δ / K_s = 1.2 mm: 1200 steps at 0.1 m/s
    const double x = sim.model().elements.x[0];
    const double s = reversed ? 1.0 - x : x;  // the contact point's distance from a
    const double along = (vx > 0) == !reversed ? 1.0 : -1.0;  // the disk moves along a→b
    CHECK_THAT(q("floor.fn(0,1)", sim), WithinRel(fn, 1e-9));
    CHECK_THAT(q("floor.fs(0,1)", sim), WithinRel(along * slide, 1e-9));
    const std::string band = "(" + std::to_string(s - 0.01) + "," + std::to_string(s + 0.01) + ")";
    CHECK_THAT(q("floor.fs" + band, sim), WithinRel(along * slide, 1e-9));
    CHECK_THAT(q("floor.fs(0," + std::to_string(s - 0.01) + ")", sim), WithinAbs(0.0, 0.0));
    // the wall's resultant: the friction along x with the disk's motion
    CHECK_THAT(sim.model().walls[0].force.x, WithinRel((vx > 0 ? 1.0 : -1.0) * slide, 1e-9));
  }
}
