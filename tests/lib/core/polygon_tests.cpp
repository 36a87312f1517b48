// Rigid convex polygon elements (docs/model.md §5, P1–P9): the shape's area, centroid and inertia, the refused
// outlines, the corner–edge contact points with polygons, walls and disks, the conservation of momentum,
// angular momentum and (without dissipation) energy in a collision, what a model with polygons refuses, the
// time-step guard's bound and the case file's polygon keys.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/core/corner_contacts.hpp"
#include "dem/core/polygon.hpp"
#include "dem/core/simulation.hpp"
#include "dem/core/stability.hpp"
#include "dem/run/quantities.hpp"
#include "dem/run/run.hpp"
#include "../test_support.hpp"

using dem::Vec2;

namespace {

dem::Case read_text(const std::string& text, const std::vector<std::string>& sets = {}) {
  return dem::read_case_text(text, "polygon_test.toml", sets);
}

// A 50 × 50 mm block at the origin above a floor, one law, no gravity unless given.
const char* kBlockCase = R"(
[case]
title = "polygon"
[physics]
thickness = "10 mm"
[[material]]
name = "block"
density = "2000 kg/m^3"
[[material]]
name = "floor"
[[contact]]
between = ["block", "floor"]
law = "linear"
kn = "1e6 N/m"
ks_ratio = 0.5
friction = 0.5
[[contact]]
between = ["block", "block"]
law = "linear"
kn = "1e6 N/m"
[[element]]
shape = "polygon"
material = "block"
size = ["50 mm", "50 mm"]
position = ["0 m", "0.025 m"]
[[wall]]
name = "floor"
from = ["-1 m", "0 m"]
to = ["1 m", "0 m"]
material = "floor"
[numerics]
dt = "1e-6 s"
duration = "1e-3 s"
)";

}  // namespace

TEST_CASE("polygon: area, centroid and second moment of a rectangle and a triangle (P1, P2)", "[polygon]") {
  const auto rect = dem::polygon_properties(dem::rectangle_vertices(0.3, 0.2));
  CHECK(rect.area == Approx(0.06).epsilon(1e-14));
  CHECK(std::abs(rect.centroid.x) < 1e-16);
  CHECK(std::abs(rect.centroid.y) < 1e-16);
  CHECK(rect.polar == Approx(0.06 * (0.09 + 0.04) / 12.0).epsilon(1e-13));
  CHECK(rect.circumradius == Approx(std::hypot(0.15, 0.1)).epsilon(1e-15));
  // a right triangle with legs 1 far from the origin: A = 1/2, centroid at a third, J_c = 1/36 + 1/36
  const Vec2 o{1e3, -2e3};
  const auto tri = dem::polygon_properties({o, o + Vec2{1.0, 0.0}, o + Vec2{0.0, 1.0}});
  CHECK(tri.area == Approx(0.5).epsilon(1e-12));
  CHECK(tri.centroid.x == Approx(o.x + 1.0 / 3.0).epsilon(1e-14));
  CHECK(tri.centroid.y == Approx(o.y + 1.0 / 3.0).epsilon(1e-14));
  CHECK(tri.polar == Approx(1.0 / 18.0).epsilon(1e-11));
  // the element: centre at the centroid, m = ρ A l, I = ρ l J_c, or the given mass with the same radius of gyration
  dem::Model m = test::make_model({{"rock", 2500.0}}, 1e-6);
  m.thickness = 0.1;
  const std::size_t i = dem::add_polygon(m, 0, {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}, {2.0, 3.0});
  CHECK(m.elements.x[i] == Approx(2.0 + 1.0 / 3.0));
  CHECK(m.elements.mass[i] == Approx(2500.0 * 0.5 * 0.1));
  CHECK(m.elements.inertia[i] == Approx(2500.0 * 0.1 / 18.0));
  CHECK(m.elements.radius[i] == Approx(std::hypot(2.0 / 3.0, 1.0 / 3.0)));
  const std::size_t k = dem::add_polygon(m, 0, dem::rectangle_vertices(2.0, 1.0), {}, {}, 0.0, 7.0);
  CHECK(m.elements.mass[k] == 7.0);
  CHECK(m.elements.inertia[k] == Approx(7.0 * (4.0 + 1.0) / 12.0));
  CHECK(m.polygon_of == std::vector<std::int32_t>{0, 1});
  dem::add_element(m, dem::Shape::disk, 0, 0.1, {5.0, 5.0});
  CHECK(m.polygon_of == std::vector<std::int32_t>{0, 1, -1});
}

TEST_CASE("polygon: outlines that are not a convex polygon listed counter-clockwise are refused", "[polygon]") {
  CHECK(dem::polygon_problem(dem::rectangle_vertices(1.0, 1.0)).empty());
  CHECK_THAT(dem::polygon_problem({{0, 0}, {1, 0}}), Catch::Contains("three or more"));
  CHECK_THAT(dem::polygon_problem({{0, 0}, {0, 1}, {1, 1}, {1, 0}}), Catch::Contains("counter-clockwise"));
  CHECK_THAT(dem::polygon_problem({{0, 0}, {1, 0}, {2, 0}, {1, 1}}), Catch::Contains("line of its neighbours"));
  CHECK_THAT(dem::polygon_problem({{0, 0}, {1, 0}, {1, 0}, {0, 1}}), Catch::Contains("coincide"));
  CHECK_THAT(dem::polygon_problem({{0, 0}, {2, 0}, {1, 0.2}, {2, 2}, {0, 2}}), Catch::Contains("clockwise"));  // reflex
  // a pentagram: every turn to the left, but it goes round twice
  std::vector<Vec2> star;
  for (int k = 0; k < 5; ++k) {
    const double a = 4.0 * std::numbers::pi * k / 5.0;
    star.push_back({std::cos(a), std::sin(a)});
  }
  CHECK_THAT(dem::polygon_problem(star), Catch::Contains("more than once"));
  CHECK_THROWS_AS(dem::add_polygon(*std::make_unique<dem::Model>(test::make_model({{"r", 1.0}}, 1e-6)), 0, star, {}),
                  std::invalid_argument);
}

TEST_CASE("polygon: corner–edge contact points with a polygon, a wall and a disk (P4–P7)", "[polygon]") {
  const auto square = [](Vec2 c, double half, double turn) {
    std::vector<Vec2> v;
    for (const Vec2& q : dem::rectangle_vertices(2 * half, 2 * half))
      v.push_back(c + Vec2{std::cos(turn) * q.x - std::sin(turn) * q.y, std::sin(turn) * q.x + std::cos(turn) * q.y});
    return v;
  };
  std::vector<dem::CornerHit> hits;
  SECTION("edge to edge: two corners, the normal across the faces") {
    dem::polygon_pair_hits(square({0, 0}, 1.0, 0.0), square({1.999, 0.5}, 1.0, 0.0), hits);
    REQUIRE(hits.size() == 2);
    // i's upper right corner (2) lies in j, j's lower left corner (0) in i; both pushed apart along x
    CHECK(hits[0].side == 0);
    CHECK(hits[0].corner == 2);
    CHECK(hits[0].normal.x == Approx(1.0));
    CHECK(hits[0].depth == Approx(1e-3).epsilon(1e-9));
    CHECK(hits[1].side == 1);
    CHECK(hits[1].corner == 0);
    CHECK(hits[1].normal.x == Approx(1.0));
    CHECK(hits[1].depth == Approx(1e-3).epsilon(1e-9));
  }
  SECTION("corner first: one point, the normal of the struck edge") {
    dem::polygon_pair_hits(square({0, 0}, 1.0, 0.0), square({1.0 + std::sqrt(2.0) - 0.01, 0.2}, 1.0, std::numbers::pi / 4), hits);
    REQUIRE(hits.size() == 1);
    CHECK(hits[0].side == 1);
    CHECK(hits[0].normal.x == Approx(1.0));
    CHECK(hits[0].normal.y == Approx(0.0).margin(1e-15));
    CHECK(hits[0].depth == Approx(0.01).epsilon(1e-9));
    CHECK(hits[0].point.y == Approx(0.2));
  }
  SECTION("corner on corner (equal blocks stacked): two points, not four") {
    dem::polygon_pair_hits(square({0, 0}, 1.0, 0.0), square({0, 2.0 - 1e-6}, 1.0, 0.0), hits);
    REQUIRE(hits.size() == 2);
    CHECK(hits[0].side == 0);
    CHECK(hits[1].side == 0);
    CHECK(hits[0].normal.y == Approx(1.0));
    CHECK(hits[0].depth == Approx(1e-6).epsilon(1e-6));
    hits.clear();  // offset by a quarter: two corners again, one of each
    dem::polygon_pair_hits(square({0, 0}, 1.0, 0.0), square({0.5, 2.0 - 1e-6}, 1.0, 0.0), hits);
    REQUIRE(hits.size() == 2);
    CHECK(hits[0].side == 0);
    CHECK(hits[1].side == 1);
  }
  SECTION("apart: nothing") {
    dem::polygon_pair_hits(square({0, 0}, 1.0, 0.0), square({2.001, 0}, 1.0, 0.0), hits);
    CHECK(hits.empty());
  }
  SECTION("a wall: the corners below its line, within its length; its end inside the polygon") {
    const auto block = square({0, 1.0 - 2e-6}, 1.0, 0.0);
    dem::polygon_wall_hits(block, {0, 1}, {-5, 0}, {5, 0}, false, hits);
    REQUIRE(hits.size() == 2);
    CHECK(hits[0].normal.y == Approx(-1.0));
    CHECK(hits[0].depth == Approx(2e-6).epsilon(1e-6));
    hits.clear();
    dem::polygon_wall_hits(block, {0, 1}, {-5, 0}, {0.5, 0}, false, hits);  // the right corner beyond the end,
    REQUIRE(hits.size() == 2);                                              // the end b pressed into the base
    CHECK(hits[0].side == 0);
    CHECK(hits[1].side == 1);
    CHECK(hits[1].corner == 1);
    CHECK(hits[1].normal.y == Approx(-1.0));
    CHECK(hits[1].depth == Approx(2e-6).epsilon(1e-6));
    hits.clear();
    // the end a inside (a thin wall crossing the right edge: the corner (1, 1) lies beyond its line, within its
    // length, and counts too: a wall is two-sided, and which side is "behind" is the centroid's)
    dem::polygon_wall_hits(square({0, 0}, 1.0, 0.0), {0, 0}, {0.9, 0.2}, {3, 0.2}, false, hits);
    REQUIRE(hits.size() == 2);
    CHECK(hits[1].side == 1);
    CHECK(hits[1].corner == 0);
    CHECK(hits[1].normal.x == Approx(1.0));
    CHECK(hits[1].depth == Approx(0.1));
    hits.clear();
    dem::polygon_wall_hits(square({0, 0}, 1.0, 0.0), {0, 0}, {0.95, -0.3}, {0.95, -0.3}, true, hits);  // a point wall
    REQUIRE(hits.size() == 1);
    CHECK(hits[0].depth == Approx(0.05));
  }
  SECTION("a disk: at an edge, at a corner, with its centre inside") {
    dem::polygon_disk_hits(square({0, 0}, 1.0, 0.0), {1.4, 0.3}, 0.5, hits);
    REQUIRE(hits.size() == 1);
    CHECK(hits[0].normal.x == Approx(1.0));
    CHECK(hits[0].depth == Approx(0.1));
    CHECK(hits[0].point.x == Approx(0.9));
    hits.clear();
    dem::polygon_disk_hits(square({0, 0}, 1.0, 0.0), {1.3, 1.4}, 0.6, hits);  // nearest the corner (1, 1)
    REQUIRE(hits.size() == 1);
    CHECK(hits[0].normal.x == Approx(0.6));
    CHECK(hits[0].normal.y == Approx(0.8));
    CHECK(hits[0].depth == Approx(0.1));
    hits.clear();
    dem::polygon_disk_hits(square({0, 0}, 1.0, 0.0), {0.9, 0.0}, 0.5, hits);  // the centre inside
    REQUIRE(hits.size() == 1);
    CHECK(hits[0].normal.x == Approx(1.0));
    CHECK(hits[0].depth == Approx(0.6));
    hits.clear();
    dem::polygon_disk_hits(square({0, 0}, 1.0, 0.0), {1.6, 0.0}, 0.5, hits);
    CHECK(hits.empty());
  }
}

TEST_CASE("polygon: a collision keeps momentum and angular momentum, and without dissipation the energy (P8)",
          "[polygon]") {
  for (const bool corner : {false, true}) {
    CAPTURE(corner);
    std::vector<std::string> sets = {"contact.0.friction=0.3"};
    if (corner) sets = {"element.1.rotation=30 deg", "element.1.position=[\"70 mm\", \"5 mm\"]"};
    dem::Case c = dem::read_case(std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/polygon/collision.toml", sets);
    dem::Simulation sim(std::move(c.model));
    auto totals = [&] {
      const dem::Elements& e = sim.model().elements;
      double px = 0.0, py = 0.0, L = 0.0;
      for (std::size_t i = 0; i < e.size(); ++i) {
        px += e.mass[i] * e.vx[i], py += e.mass[i] * e.vy[i];
        L += e.mass[i] * (e.x[i] * e.vy[i] - e.y[i] * e.vx[i]) + e.inertia[i] * e.omega[i];
      }
      return std::array<double, 3>{px, py, L};
    };
    // K18 stores v_{k−1} and x_k = x_{k−1} + v Δt: the angular momentum of the pairs (x_{k−1}, v) is kept, so
    // the moments are taken with the positions before each step's increment
    auto angular = [&] {
      const dem::Elements& e = sim.model().elements;
      double L = 0.0;
      for (std::size_t i = 0; i < e.size(); ++i)
        L += e.mass[i] * ((e.x[i] - e.dx[i]) * e.vy[i] - (e.y[i] - e.dy[i]) * e.vx[i]) + e.inertia[i] * e.omega[i];
      return L;
    };
    const auto before = totals();
    const double L0 = angular();
    const double k0 = sim.energies().kinetic;
    int touched = 0;
    while (sim.time() < 0.03) {
      sim.step();
      touched += sim.contact_count() > 0 ? 1 : 0;
    }
    REQUIRE(touched > 100);  // the blocks did collide
    const auto after = totals();
    const double scale = before[0];  // m v of the striker
    CHECK(std::abs(after[0] - before[0]) < 1e-13 * scale);
    CHECK(std::abs(after[1] - before[1]) < 1e-13 * scale);
    CHECK(std::abs(angular() - L0) < 1e-12 * std::abs(scale) * 0.05);
    CHECK(sim.model().elements.omega[1] != 0.0);  // the off-centre blow turned the target
    if (corner) CHECK(sim.energies().kinetic == Approx(k0).epsilon(1e-6));  // no friction, no dashpot
    else CHECK(sim.energies().kinetic < 0.99 * k0);                        // friction dissipates
  }
}

TEST_CASE("polygon: a model with polygons steps on one thread, with the reference step's results", "[polygon]") {
  dem::Case c = dem::read_case(std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/polygon/collision.toml",
                               {"element.1.rotation=30 deg", "element.1.position=[\"60 mm\", \"5 mm\"]", "contact.0.friction=0.4",
                                "contact.0.damping_ratio=0.1"});
  dem::Simulation one(c.model), many(c.model), ref(c.model);
  many.set_threads(4, 1);
  int touching = 0;
  for (int k = 0; k < 15000; ++k) {
    one.step(), many.step(), ref.reference_step();
    touching += one.contact_count() > 0 ? 1 : 0;
  }
  CHECK(many.threads_used() == 1);
  test::check_same_state(one.model().elements, many.model().elements);
  test::check_same_state(one.model().elements, ref.model().elements);
  CHECK(touching > 1000);  // the collision (from about 0.85 ms) is inside the compared steps
}

TEST_CASE("polygon: what a model with polygons refuses", "[polygon]") {
  const auto base = read_text(kBlockCase).model;
  auto refused = [](dem::Model m) { return test::message_of<std::invalid_argument>([&] { dem::Simulation s(std::move(m)); }); };
  {
    dem::Model m = base;
    dem::add_element(m, dem::Shape::pre, 0, 0.01, {1.0, 1.0});
    CHECK_THAT(refused(m), Catch::Contains("PREs"));
  }
  {
    dem::Model m = base;
    m.laws[0].kind = dem::LawKind::face;
    CHECK_THAT(refused(m), Catch::Contains("linear contact laws only"));
  }
  {
    dem::Model m = base;
    m.laws[0].rolling.enabled = true;
    CHECK_THAT(refused(m), Catch::Contains("rolling resistance"));
  }
  {
    dem::Model m = base;
    m.numerics.reorder_every = 1;
    CHECK_THAT(refused(m), Catch::Contains("reorder_every"));
  }
  {
    dem::Model m = base;
    m.base_plate.enabled = true;
    m.base_plate.friction.assign(m.materials.size(), 0.4);
    CHECK_THAT(refused(m), Catch::Contains("base friction"));
  }
}

TEST_CASE("polygon: the time-step guard counts every contact point with the largest lever (P9)", "[polygon]") {
  const dem::Model m = read_text(kBlockCase).model;
  const dem::StabilityBound b = dem::assembly_stability_bound(m, {});
  // one square on a segment wall: V + 2 = 6 points, a² = 1/m + R²/I = 4/m, no dashpot: K18's Δt < 2/√λ
  const double mass = 2000.0 * 0.05 * 0.05 * 0.01, lambda = 6.0 * 1e6 * 4.0 / mass;
  CHECK(b.wall_contacts == 6);
  CHECK(b.element_contacts == 0);
  CHECK(b.stiffness_rate == Approx(lambda).epsilon(1e-12));
  CHECK(b.limit == Approx(2.0 / std::sqrt(lambda)).epsilon(1e-12));
  CHECK(b.limit_sticking == Approx(2.0 / std::sqrt(lambda * 1.5)).epsilon(1e-12));  // K_s = K_n/2 added
  // a second square within reach: V + V' = 8 more points, coupled to the partner's a
  const dem::Model two = read_text(std::string(kBlockCase) + R"(
[[element]]
shape = "polygon"
material = "block"
size = ["50 mm", "50 mm"]
position = ["0.05 m", "0.025 m"]
)").model;
  const dem::StabilityBound b2 = dem::assembly_stability_bound(two, {});
  CHECK(b2.element_contacts == 8);
  CHECK(b2.stiffness_rate == Approx(lambda + 8.0 * 1e6 * (4.0 / mass + 4.0 / mass)).epsilon(1e-12));
  // the run refuses a Δt above it, naming the limit
  CHECK_THAT(test::message_of<dem::CaseError>([&] { dem::check_case(read_text(kBlockCase, {"numerics.dt=1e-3"})); }),
             Catch::Contains("stability limit"));
}

TEST_CASE("polygon: a resting block settles on its two corners to m g / (2 K_n) each", "[polygon]") {
  dem::Case c = read_text(kBlockCase, {"physics.gravity=[0, -9.81]", "numerics.dt=1e-5 s", "contact.0.damping_ratio=0.7"});
  dem::Simulation sim(std::move(c.model));
  while (sim.time() < 0.2) sim.step();
  const double mass = 2000.0 * 0.05 * 0.05 * 0.01;
  const auto v = sim.contact(0, 0, true);
  CHECK(v.links == 2);
  CHECK(v.fn == Approx(mass * 9.81).epsilon(1e-9));
  CHECK(sim.model().elements.y[0] == Approx(0.025 - mass * 9.81 / 2e6).epsilon(1e-12));
  CHECK(std::abs(sim.model().elements.phi[0]) < 1e-12);
  CHECK(sim.energies().elastic == Approx(2 * 0.5 * std::pow(mass * 9.81 / 2, 2) / 1e6).epsilon(1e-9));
  const auto walls = sim.wall_band_force(0, 0.0, 2.0);  // s along the wall from its end a at x = −1 m
  CHECK(walls.contacts == 2);
  CHECK(walls.normal == Approx(mass * 9.81).epsilon(1e-9));
}

TEST_CASE("polygon: a disk resting on a fixed polygon", "[polygon]") {
  dem::Case c = read_text(std::string(kBlockCase) + R"(
[[material]]
name = "sand"
density = "2650 kg/m^3"
[[contact]]
between = ["block", "sand"]
law = "linear"
kn = "1e5 N/m"
damping_ratio = 0.7
onset = "overlap"
[[contact]]
between = ["sand", "floor"]
law = "linear"
kn = "1e5 N/m"
[[element]]
material = "sand"
radius = "5 mm"
position = ["0.01 m", "0.0551 m"]
)",
                          {"physics.gravity=[0, -9.81]", "numerics.dt=1e-5 s", "element.0.motion=fixed"});
  dem::Simulation sim(std::move(c.model));
  while (sim.time() < 0.2) sim.step();
  const dem::Elements& e = sim.model().elements;
  const double m = e.mass[1];
  CHECK(e.y[1] == Approx(0.05 + 0.005 - m * 9.81 / 1e5).epsilon(1e-9));
  CHECK(sim.contact(0, 1, false).fn == Approx(m * 9.81).epsilon(1e-9));
  CHECK(sim.contact(0, 1, false).ny == Approx(1.0));  // from the polygon (i) towards the disk
}

TEST_CASE("polygon: the case file's polygon keys are read strictly", "[polygon][case]") {
  const std::string head = std::string(kBlockCase).substr(0, std::string(kBlockCase).find("[[element]]"));
  const std::string tail = std::string(kBlockCase).substr(std::string(kBlockCase).find("[[wall]]"));
  auto element = [&](const std::string& body) { return head + "[[element]]\nshape = \"polygon\"\nmaterial = \"block\"\n" + body + tail; };
  auto error = [&](const std::string& body) { return test::message_of<dem::CaseError>([&] { read_text(element(body)); }); };
  const dem::Case ok = read_text(element("vertices = [[\"0 mm\", \"0 mm\"], [\"50 mm\", \"0 mm\"], [\"0 mm\", \"50 mm\"]]\nposition = [\"0 m\", \"0.001 m\"]\n"));
  CHECK(ok.model.elements.x[0] == Approx(0.05 / 3.0));
  CHECK(ok.model.polygons.at(0).vertices.size() == 3);
  CHECK_THAT(error("vertices = [[\"0 mm\", \"0 mm\"], [\"0 mm\", \"50 mm\"], [\"50 mm\", \"0 mm\"]]\nposition = [\"0 m\", \"0.1 m\"]\n"),
             Catch::Contains("polygon_test.toml:") && Catch::Contains("vertices") && Catch::Contains("counter-clockwise"));
  CHECK_THAT(error("position = [\"0 m\", \"0.1 m\"]\n"), Catch::Contains("exactly one of vertices"));
  CHECK_THAT(error("size = [\"50 mm\", \"50 mm\"]\nvertices = [[0, 0], [1, 0], [0, 1]]\nposition = [\"0 m\", \"0.1 m\"]\n"),
             Catch::Contains("exactly one of vertices"));
  CHECK_THAT(error("size = [\"50 mm\", \"-5 mm\"]\nposition = [\"0 m\", \"0.1 m\"]\n"), Catch::Contains("size"));
  CHECK_THAT(error("size = [\"50 mm\", \"50 mm\"]\nradius = \"1 mm\"\nposition = [\"0 m\", \"0.1 m\"]\n"),
             Catch::Contains("radius") && Catch::Contains("vertices"));
  CHECK_THAT(error("vertices = [[\"0 mm\", \"0 mm\"], [\"50 mm\"], [\"0 mm\", \"50 mm\"]]\nposition = [\"0 m\", \"0.1 m\"]\n"),
             Catch::Contains("[x, y] corners"));
  CHECK_THAT(test::message_of<dem::CaseError>([&] {  // 15 mm into the floor
               dem::check_case(read_text(element("size = [\"50 mm\", \"50 mm\"]\nposition = [\"0 m\", \"0.01 m\"]\n")));
             }),
             Catch::Contains("overlaps wall \"floor\""));
  // [[lattice]] shape = "polygon": a block of columns × rows rectangles side by side, not bonded
  const std::string lattice = head + "[[lattice]]\nshape = \"polygon\"\nmaterial = \"block\"\nsize = [\"50 mm\", \"25 mm\"]\n"
                              "origin = [\"0 m\", \"0.0125 m\"]\ncolumns = 2\nrows = 3\nbonded = false\n" + tail;
  const dem::Case block = read_text(lattice);
  REQUIRE(block.model.elements.size() == 6);
  CHECK(block.model.elements.x[5] == Approx(0.05));
  CHECK(block.model.elements.y[5] == Approx(0.0625));
  CHECK(block.model.elements.mass[5] == Approx(2000.0 * 0.05 * 0.025 * 0.01));
  CHECK_THAT(test::message_of<dem::CaseError>([&] {
               read_text(head + "[[lattice]]\nshape = \"polygon\"\nmaterial = \"block\"\nsize = [0.05, 0.025]\norigin = [0, 1]\ncolumns = 1\nrows = 1\n" + tail);
             }),
             Catch::Contains("bonded = false"));
  CHECK_THAT(test::message_of<dem::CaseError>([&] {
               read_text(head + "[[row]]\nshape = \"polygon\"\nmaterial = \"block\"\nradius = \"1 mm\"\nstart = [0, 1]\nstep = [0.01, 0]\ncount = 2\n" + tail);
             }),
             Catch::Contains("[[element]]"));
}

TEST_CASE("polygon: checkpoints of a case with polygons are refused, and an interrupted run writes none", "[polygon]") {
  dem::RunOptions opt;
  opt.checkpoint_every = 100;
  CHECK_THAT(test::message_of<dem::CaseError>([&] { dem::run_case(read_text(kBlockCase), opt); }),
             Catch::Contains("checkpoints of a case with polygon elements"));
  opt = {};
  opt.restart = "nowhere.bin";
  CHECK_THROWS_AS(dem::run_case(read_text(kBlockCase), opt), dem::CaseError);
  opt = {};
  opt.out_dir = std::filesystem::temp_directory_path() / "dem2d_polygon_interrupted";
  opt.interrupt_at_step = 10;
  const dem::RunResult r = dem::run_case(read_text(kBlockCase), opt);
  CHECK(r.status == "interrupted");
  CHECK_FALSE(std::filesystem::exists(opt.out_dir / "checkpoint.bin"));
  CHECK(std::filesystem::exists(opt.out_dir / "summary.json"));
}

TEST_CASE("polygon: e<i>.gap is refused for a polygon, its forces and contact points are not", "[polygon]") {
  const dem::Model m = read_text(kBlockCase).model;
  CHECK_THAT(test::message_of<std::invalid_argument>([&] { dem::compile_quantity("e0.gap.floor", m); }),
             Catch::Contains("not defined for a polygon"));
  CHECK_NOTHROW(dem::compile_quantity("e0.fn.floor", m));
  CHECK_NOTHROW(dem::compile_quantity("e0.links.floor", m));
}
