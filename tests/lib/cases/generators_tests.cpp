// Kiyama's silo inputs: K_n from E, ν, q by K23 in a case file (refs §5.2, Table 1), the (s−1)/s
// ordered arrangements (refs §6.1 table) and the reproducible random fill (generators.hpp).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/cases/generators.hpp"
#include "../test_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

const double kRhoG = 2650.0 * 9.80665;  // ρg of Kiyama's sand [N/m³]

std::string law_case(const std::string& law_lines) {
  return R"([case]
title = "k23"
[physics]
gravity = ["0 m/s^2", "-9.80665 m/s^2"]
[[material]]
name = "sand"
density = "2.65 g/cm^3"
[[material]]
name = "wall"
[[contact]]
between = ["sand", "wall"]
law = "linear"
)" + law_lines + R"(
ks_ratio = 0.25
friction = 0.2
[[element]]
material = "sand"
radius = "1 cm"
position = ["0 m", "2 cm"]
[[wall]]
name = "floor"
from = ["-1 m", "0 m"]
to = ["1 m", "0 m"]
material = "wall"
[numerics]
dt = "1e-5 s"
duration = "1 ms"
)";
}

}  // namespace

TEST_CASE("kn_from_elastic reproduces Table 1 of Kiyama (K_n over rho g = 3.637e4 cm at E = 750 kgf/cm2)", "[silo][k23]") {
  const auto path = test::write_temp("k23.toml", law_case(
      R"(kn_from_elastic = { E = "750 kgf/cm^2", nu = 0.3, q = "0.068 kgf/cm", radius = "1 cm", c = 1.5 })"));
  const dem::Case c = dem::read_case(path, {});
  const double kn_over_rhog_cm = c.model.laws[0].linear.kn / kRhoG * 100.0;  // l = 1 m
  CHECK_THAT(kn_over_rhog_cm, WithinRel(3.637e4, 1e-3));  // refs §5.2
  CHECK_THAT(c.model.laws[0].linear.ks, WithinRel(0.25 * c.model.laws[0].linear.kn, 1e-12));
  // the other columns of Table 1 (refs §5.2: 4.747e4, 4.065e5, 3.554e6, 3.158e7 cm with q = 0.068)
  const char* es[] = {"1e3 kgf/cm^2", "1e4 kgf/cm^2", "1e5 kgf/cm^2", "1e6 kgf/cm^2"};
  const double want[] = {4.747e4, 4.065e5, 3.554e6, 3.158e7};
  for (int k = 0; k < 4; ++k) {
    const dem::Case ck = dem::read_case(path, {std::string("contact.0.kn_from_elastic.E=") + es[k]});
    CHECK_THAT(ck.model.laws[0].linear.kn / kRhoG * 100.0, WithinRel(want[k], 1.5e-3));
  }
  // Kiyama's wall: factor 2 (Table 2: 7.28e4 cm); c = 2/3 (K22.a) gives a stiffer spring
  const dem::Case cw = dem::read_case(path, {"contact.0.kn_from_elastic.factor=2"});
  CHECK_THAT(cw.model.laws[0].linear.kn / kRhoG * 100.0, WithinRel(7.274e4, 1e-3));
  const dem::Case c23 = dem::read_case(path, {"contact.0.kn_from_elastic.c=0.6666666666666666"});
  CHECK(c23.model.laws[0].linear.kn > 1.05 * c.model.laws[0].linear.kn);
  // a thickness of 1 cm scales the spring (Pa × l)
  const dem::Case cl = dem::read_case(path, {"physics.thickness=0.01"});
  CHECK_THAT(cl.model.laws[0].linear.kn, WithinRel(0.01 * c.model.laws[0].linear.kn, 1e-12));
}

TEST_CASE("kn_from_elastic refuses bad input with the key", "[silo][k23]") {
  const std::string good = R"(kn_from_elastic = { E = "750 kgf/cm^2", nu = 0.3, q = "0.068 kgf/cm", radius = "1 cm" })";
  auto fails = [&](const std::string& lines, const std::string& what) {
    const auto path = test::write_temp("k23_bad.toml", law_case(lines));
    CHECK_THROWS_WITH(dem::read_case(path, {}), Contains(what));
  };
  fails(good + "\nkn = \"1e5 N/m\"", "give exactly one of kn or kn_from_elastic");
  fails(R"(kn_from_elastic = { E = "750 kgf/cm^2", nu = 0.6, q = "0.068 kgf/cm", radius = "1 cm" })", "kn_from_elastic.nu");
  fails(R"(kn_from_elastic = { E = "750 kgf/cm^2", nu = 0.3, q = "0.068 kgf/cm^2", radius = "1 cm" })", "kn_from_elastic.q");
  fails(R"(kn_from_elastic = { E = "750 kgf/cm^2", nu = 0.3, q = "0.068 kgf/cm" })", "kn_from_elastic.radius");
  fails(R"(kn_from_elastic = { E = "750 kgf/cm^2", nu = 0.3, q = "0.068 kgf/cm", radius = "1 cm", nuu = 1 })", "nuu");
}

TEST_CASE("ordered (s-1)/s arrangements match the table of refs 6.1", "[silo][generators]") {
  struct Row { int s; double dx, dy, k_geom; int rows; long count; double height; };
  const Row table[] = {{12, 3.4545, 1.0082, 2.935, 30, 345, 31.24}, {13, 3.1667, 1.2219, 1.679, 28, 350, 34.99},
                       {14, 2.9231, 1.3652, 1.146, 26, 351, 36.13}, {15, 2.7143, 1.4691, 0.853, 24, 348, 35.79},
                       {16, 2.5333, 1.5478, 0.670, 23, 357, 36.05}, {17, 2.3750, 1.6093, 0.545, 21, 347, 34.19},
                       {18, 2.2353, 1.6586, 0.454, 20, 350, 33.51}, {19, 2.1111, 1.6988, 0.386, 19, 352, 32.58}};
  for (const Row& row : table) {
    INFO("s = " << row.s);
    const int rows = dem::rows_nearest_count(row.s, 350);
    CHECK(rows == row.rows);
    const auto a = dem::ordered_arrangement(row.s, rows, 0.40, 0.01, 0.0);
    CHECK_THAT(a.dx * 100.0, WithinAbs(row.dx, 6e-5));
    CHECK_THAT(a.dy * 100.0, WithinAbs(row.dy, 6e-5));
    CHECK_THAT(a.k_geom, WithinAbs(row.k_geom, 6e-4));
    CHECK(a.count == row.count);
    CHECK_THAT(a.height * 100.0, WithinAbs(row.height, 6e-3));
    const auto p = dem::ordered_positions(a, 0.0, 0.0, 0.01, 0.0);
    REQUIRE(static_cast<long>(p.size()) == row.count);
    CHECK_THAT(p.front().x, WithinAbs(0.01, 1e-15));       // the row of s touches the left wall
    CHECK_THAT(p[static_cast<std::size_t>(row.s - 1)].x, WithinAbs(0.39, 1e-12));  // and the right wall
  }
  CHECK_THROWS_WITH(dem::ordered_arrangement(21, 10, 0.40, 0.01, 0.0), Contains("overlap"));  // d_x = 1.9 cm < 2r
  CHECK_THROWS_WITH(dem::ordered_arrangement(19, 10, 0.40, 0.01, 0.12e-2), Contains("overlap"));  // d_x < 2r + gap
  CHECK_THROWS_WITH(dem::ordered_arrangement(5, 10, 0.40, 0.01, 0.0), Contains("cannot rest"));
}

TEST_CASE("an ordered arrangement with a gap leaves every pair and wall at least the gap apart", "[silo][generators]") {
  for (int s : {12, 18}) {
    const double gap = s == 12 ? 3e-4 : 4e-5, r = 0.01;
    const auto a = dem::ordered_arrangement(s, dem::rows_nearest_count(s, 350), 0.40, r, gap);
    const auto p = dem::ordered_positions(a, 0.0, 0.0, r, gap);
    double min_pair = 1.0, min_wall = 1.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      min_wall = std::min({min_wall, p[i].x - r, 0.40 - p[i].x - r, p[i].y - r});
      for (std::size_t j = i + 1; j < p.size(); ++j) min_pair = std::min(min_pair, dem::norm(p[i] - p[j]) - 2.0 * r);
    }
    CHECK_THAT(min_pair, WithinAbs(gap, 1e-12));  // the diagonal neighbours sit exactly at the gap
    CHECK_THAT(min_wall, WithinAbs(gap, 1e-12));
    CHECK_THAT(a.min_gap, WithinAbs(std::min(min_pair, min_wall), 1e-12));
  }
}

TEST_CASE("the silo case files generate Kiyama's 350 and 345 disks", "[silo][generators]") {
  const dem::Case c = dem::read_case(std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/silo/static_17_18.toml", {});
  CHECK(c.model.elements.size() == 350);
  const dem::Case c12 = dem::read_case(std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/silo/static_11_12.toml", {});
  CHECK(c12.model.elements.size() == 345);
  CHECK_THAT(c.model.laws[0].linear.kn / kRhoG * 100.0, WithinRel(3.637e4, 1e-3));
  CHECK_THAT(c.model.laws[1].linear.kn / kRhoG * 100.0, WithinRel(7.274e4, 1e-3));
  CHECK_THROWS_WITH(dem::read_case(std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/silo/static_17_18.toml",
                                   {"arrangement.0.s=21"}),
                    Contains("arrangement.0.s"));
  CHECK_THROWS_WITH(dem::read_case(std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/silo/static_17_18.toml",
                                   {"arrangement.0.rows=20"}),
                    Contains("exactly one of rows or count_near"));
}

TEST_CASE("random fill is reproducible from its seed and places no overlaps", "[silo][generators]") {
  dem::RadiusDistribution bi;
  bi.radii = {0.01, 0.007};
  bi.fractions = {0.5, 0.5};
  const auto a = dem::random_fill({0.0, 0.0}, {0.4, 0.4}, 300, bi, 42, 1e-4);
  const auto b = dem::random_fill({0.0, 0.0}, {0.4, 0.4}, 300, bi, 42, 1e-4);
  const auto c = dem::random_fill({0.0, 0.0}, {0.4, 0.4}, 300, bi, 43, 1e-4);
  REQUIRE(a.size() == 300);
  bool same = true, differs = false;
  int small = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    same = same && a[i].centre == b[i].centre && a[i].radius == b[i].radius;
    differs = differs || !(a[i].centre == c[i].centre);
    small += a[i].radius == 0.007;
    CHECK(a[i].centre.x - a[i].radius >= 0.0);
    CHECK(a[i].centre.x + a[i].radius <= 0.4);
    CHECK(a[i].centre.y - a[i].radius >= 0.0);
    CHECK(a[i].centre.y + a[i].radius <= 0.4);
    for (std::size_t j = 0; j < i; ++j) REQUIRE(dem::norm(a[i].centre - a[j].centre) >= a[i].radius + a[j].radius + 1e-4);
  }
  CHECK(same);
  CHECK(differs);
  CHECK(small > 120);  // binomial(300, 1/2): 150 ± 8.7
  CHECK(small < 180);
  dem::RadiusDistribution uni;
  uni.min = 0.005;
  uni.max = 0.01;
  const auto u = dem::random_fill({0.0, 0.0}, {0.4, 0.4}, 200, uni, 7, 0.0);
  double lo = 1.0, hi = 0.0;
  for (const auto& d : u) lo = std::min(lo, d.radius), hi = std::max(hi, d.radius);
  CHECK(lo >= 0.005);
  CHECK(hi <= 0.01);
  CHECK(hi - lo > 0.004);
  // too full: 500 disks of r = 1 cm (area fraction 1.0) cannot fit
  CHECK_THROWS_WITH(dem::random_fill({0.0, 0.0}, {0.4, 0.4}, 500, uni, 7, 0.0, 2000), Contains("could not place"));
}

TEST_CASE("random arrangement in a case file", "[silo][generators]") {
  const std::string text = R"([case]
title = "random"
[physics]
gravity = ["0 m/s^2", "-9.80665 m/s^2"]
[[material]]
name = "sand"
density = "2.65 g/cm^3"
[[contact]]
between = ["sand", "sand"]
kn = "1e6 N/m"
[[arrangement]]
kind = "random"
material = "sand"
radii = ["1 cm", "0.8 cm"]
fractions = [0.7, 0.3]
region = [["0 cm", "0 cm"], ["40 cm", "40 cm"]]
count = 100
seed = 5
[numerics]
dt = "1e-5 s"
duration = "1 ms"
)";
  const auto path = test::write_temp("random_fill.toml", text);
  const dem::Case c = dem::read_case(path, {});
  CHECK(c.model.elements.size() == 100);
  const dem::Case c2 = dem::read_case(path, {});
  CHECK(c2.model.elements.x == c.model.elements.x);
  CHECK_THROWS_WITH(dem::read_case(path, {"arrangement.0.fractions=[0.7, 0.4]"}), Contains("must sum to 1"));
  CHECK_THROWS_WITH(dem::read_case(path, {"arrangement.0.radius=1 cm"}), Contains("exactly one of radius"));
  CHECK_THROWS_WITH(dem::read_case(path, {"arrangement.0.count=2000"}), Contains("arrangement.0.count"));
  CHECK_THROWS_WITH(dem::read_case(path, {"arrangement.0.kind=hex"}), Contains("arrangement.0.kind"));
}
