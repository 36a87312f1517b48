// Per-unit-thickness inputs with a thickness other than 1 m (lib/README.md, "2D thickness"): a stiffness in
// Pa and a damping coefficient in Pa·s (Kiyama's per-unit-thickness values) are multiplied by l, values in
// N/m and N·s/m are taken as they are, and masses are ρ·area·l. l = 0.25 m tells a factor l from 1/l and
// from 1.
#include <catch2/catch.hpp>

#include <numbers>

#include "dem/cases/case_file.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

namespace {

const char* kCase = R"([case]
title = "thickness"
[physics]
thickness = "25 cm"
gravity = [0.0, -9.81]
[[material]]
name = "d"
density = 2000.0
[[material]]
name = "w"
[[contact]]
between = ["d", "d"]
kn = "2e6 Pa"
ks = "5e5 Pa"
eta_n = "40 Pa*s"
eta_s = "12 Pa*s"
[[contact]]
between = ["d", "w"]
kn = "3e5 N/m"
ks = "1e5 N/m"
eta_n = "7 N*s/m"
eta_s = "3 N*s/m"
[[element]]
material = "d"
radius = "1 cm"
position = [0.0, 0.5]
[[element]]
material = "d"
shape = "pre"
radius = "1 cm"
position = [0.1, 0.5]
[numerics]
dt = 1e-6
duration = 1e-5
[output]
vtk = false
)";

}  // namespace

TEST_CASE("thickness: per-unit-thickness stiffness and damping are scaled by l and absolute ones are not", "[case][units]") {
  const double l = 0.25;
  const auto path = test::write_temp("thickness_quarter.toml", kCase);
  const dem::Case c = dem::read_case(path, {});
  const dem::Model& m = c.model;
  REQUIRE(m.thickness == l);
  const auto& dd = m.laws[static_cast<std::size_t>(m.law_index(0, 0))];
  CHECK_THAT(dd.linear.kn, WithinRel(2e6 * l, 1e-15));
  CHECK_THAT(dd.linear.ks, WithinRel(5e5 * l, 1e-15));
  CHECK_THAT(dd.eta_n, WithinRel(40.0 * l, 1e-15));
  CHECK_THAT(dd.eta_s, WithinRel(12.0 * l, 1e-15));
  const auto& dw = m.laws[static_cast<std::size_t>(m.law_index(0, 1))];
  CHECK(dw.linear.kn == 3e5);
  CHECK(dw.linear.ks == 1e5);
  CHECK(dw.eta_n == 7.0);
  CHECK(dw.eta_s == 3.0);
  // masses: a disk ρπr²l, a PRE (square mass, M17) 4r²lρ
  CHECK_THAT(m.elements.mass[0], WithinRel(2000.0 * std::numbers::pi * 1e-4 * l, 1e-14));
  CHECK_THAT(m.elements.mass[1], WithinRel(2000.0 * 4.0 * 1e-4 * l, 1e-14));
}
