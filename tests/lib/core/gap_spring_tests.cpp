// Gap springs (docs/model.md §6, B1–B5; lib/dem/contact/gap_spring.hpp, lib/dem/core/gap_springs.cpp): the law
// of one bond, which pairs are bonded at the start, step() against the reference step on any thread count,
// the guard's count of the bond, and what a model with gap springs refuses.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/contact/gap_spring.hpp"
#include "dem/core/simulation.hpp"
#include "dem/core/stability.hpp"
#include "dem/run/run.hpp"
#include "../test_support.hpp"

namespace {

const std::filesystem::path kPair = std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/bonds/gap_pair.toml";

// Two rows of five disks (r = 1 cm, 50 μm apart in x and y) bonded by gap springs, dropped 1 mm onto a floor;
// the bonds break in tension at `strength`.
dem::Case two_rows(const std::string& strength) {
  const std::string text = R"(
[case]
title = "two bonded rows"
[physics]
gravity = ["0 m/s^2", "-9.81 m/s^2"]
[[material]]
name = "mortar"
density = "2650 kg/m^3"
[[material]]
name = "floor"
[[contact]]
between = ["mortar", "mortar"]
law = "linear"
kn = "2e5 N/m"
ks_ratio = 0.25
friction = 0.5
damping_ratio = 0.2
gap = { distance = "0.1 mm", kn = "5e5 N/m", ks = "2e5 N/m", damping_ratio = 0.1, tensile_strength = ")" + strength + R"(" }
[[contact]]
between = ["mortar", "floor"]
law = "linear"
kn = "2e5 N/m"
ks_ratio = 0.25
friction = 0.5
damping_ratio = 0.3
[[row]]
material = "mortar"
radius = "1 cm"
start = ["0 m", "11 mm"]
step = ["20.05 mm", "0 m"]
count = 5
[[row]]
material = "mortar"
radius = "1 cm"
start = ["0 m", "31.05 mm"]
step = ["20.05 mm", "0 m"]
count = 5
[[wall]]
name = "floor"
from = ["-1 m", "0 m"]
to = ["1 m", "0 m"]
material = "floor"
[numerics]
dt = "2e-6 s"
duration = "0.1 s"
)";
  return dem::read_case_text(text, "two_rows.toml", {});
}

dem::GapSpringLaw law_of_strengths(double t, double s, double gap) {
  dem::GapSpringLaw g;
  g.enabled = true, g.distance = 1e-4, g.kn = 1e6, g.ks = 4e5, g.tensile_strength = t, g.shear_strength = s, g.break_gap = gap;
  return g;
}

}  // namespace

TEST_CASE("gap spring: tension and compression, dashpots, and the three ways it breaks (B2–B4)", "[gap_spring]") {
  const double inf = std::numeric_limits<double>::infinity();
  dem::GapSpring b;
  b.eta_n = 10.0, b.eta_s = 5.0;
  const dem::GapSpringLaw law = law_of_strengths(3.0, 2.0, 1e-4);
  // pulled apart by 1 μm (du_n = −1e-6): tension e_n = −1 N, and the dashpot −η_n 1e-6/Δt
  dem::GapSpringForce f = dem::gap_spring_force(law, -1e-6, 0.0, 5e-5, 1e3, b);
  CHECK(b.en == -1.0);
  CHECK(f.fn == Approx(-1.0 - 10.0 * 1e-6 * 1e3));
  CHECK_FALSE(f.broke);
  f = dem::gap_spring_force(law, 3e-6, 1e-6, 5e-5, 1e3, b);  // pushed back past the rest length: compression
  CHECK(b.en == Approx(2.0));
  CHECK(b.es == Approx(0.4));
  CHECK(f.fs == Approx(0.4 + 5.0 * 1e-6 * 1e3));
  f = dem::gap_spring_force(law, -5.5e-6, 0.0, 5e-5, 1e3, b);  // tension 3.5 N > 3 N: broken (B4.a)
  CHECK(f.broke);
  CHECK((f.fn == 0.0 && f.fs == 0.0 && b.en == 0.0 && b.es == 0.0 && !b.intact));
  dem::GapSpring s;
  CHECK(dem::gap_spring_force(law, 0.0, 5.1e-6, 5e-5, 1e3, s).broke);  // shear 2.04 N > 2 N (B4.b)
  dem::GapSpring d;
  CHECK_FALSE(dem::gap_spring_force(law, 0.0, 0.0, 1e-4, 1e3, d).broke);  // at the break distance: holds
  CHECK(dem::gap_spring_force(law, 0.0, 0.0, 1.01e-4, 1e3, d).broke);     // past it (B4.c)
  dem::GapSpring never;
  CHECK_FALSE(dem::gap_spring_force(law_of_strengths(inf, inf, inf), -1.0, 1.0, 1.0, 1e3, never).broke);
}

TEST_CASE("gap spring: the pairs within the distance at the start are bonded, the others not (B1)", "[gap_spring]") {
  const dem::Simulation sim(two_rows("1e9 N").model);
  // 4 + 4 along the rows, 5 between them; the diagonals are 8.3 mm apart
  REQUIRE(sim.gap_springs().size() == 13);
  for (const dem::GapSpring& b : sim.gap_springs()) {
    CHECK(b.i < b.j);
    CHECK(b.intact);
    CHECK(b.eta_n > 0.0);
  }
  dem::Case far = dem::read_case(kPair, {"element.1.position=[0.0202, 0]"});  // 0.2 mm apart: not bonded
  CHECK(dem::Simulation(far.model).gap_springs().empty());
}

TEST_CASE("gap spring: step() on 1 and 3 threads and the reference step agree bit for bit, through breaks", "[gap_spring][threads]") {
  dem::Case c = two_rows("3 N");
  dem::Simulation one(c.model), many(c.model), ref(c.model);
  many.set_threads(3, 1);
  for (int k = 0; k < 20000; ++k) one.step(), many.step(), ref.reference_step();
  CHECK(many.threads_used() == 1);
  test::check_same_state(one.model().elements, many.model().elements);
  test::check_same_state(one.model().elements, ref.model().elements);
  // the drop broke some bonds and left others (the test covers both paths)
  CHECK(one.gap_springs_intact() > 0);
  CHECK(one.gap_springs_intact() < one.gap_springs().size());
  CHECK(one.gap_springs_intact() == ref.gap_springs_intact());
}

TEST_CASE("gap spring: the guard counts the bond's springs", "[gap_spring]") {
  dem::Case with = dem::read_case(kPair, {});
  dem::Case without = dem::read_case(kPair, {});
  without.model.laws[0].gap.enabled = false;
  const double a = dem::assembly_stability_bound(with.model, {}).limit, b = dem::assembly_stability_bound(without.model, {}).limit;
  // K_n + k_n = 1.1e6 against K_n = 1e5 alone: the limit falls by about √11
  CHECK(a < b / 3.0);
}

TEST_CASE("gap spring: what a model with gap springs refuses", "[gap_spring]") {
  auto refused = [](dem::Model m) { return test::message_of<std::invalid_argument>([&] { dem::Simulation s(std::move(m)); }); };
  const dem::Model base = dem::read_case(kPair, {}).model;
  {
    dem::Model m = base;
    m.numerics.reorder_every = 5;
    CHECK_THAT(refused(m), Catch::Contains("reorder_every"));
  }
  {
    dem::Model m = base;
    dem::add_element(m, dem::Shape::pre, 0, 0.01, {1.0, 1.0});
    CHECK_THAT(refused(m), Catch::Contains("disks only"));
  }
}

TEST_CASE("gap spring: a free bonded pair keeps its momentum and angular momentum while it swings", "[gap_spring]") {
  // disk 1 set moving across the line of centres and spinning: the bond's shear spring turns both disks
  dem::Case c = dem::read_case(kPair, {"element.0.velocity=[0, 0]", "element.1.velocity=[0, 0.004]",
                                       "element.1.angular_velocity=0.3 rad/s", "numerics.duration=3 ms"});
  dem::Simulation sim(c.model);
  const dem::Elements& e = sim.model().elements;
  auto totals = [&] {
    double px = 0.0, py = 0.0, l = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      px += e.mass[i] * e.vx[i], py += e.mass[i] * e.vy[i];
      l += e.mass[i] * (e.x[i] * e.vy[i] - e.y[i] * e.vx[i]) + e.inertia[i] * e.omega[i];
    }
    return std::array<double, 3>{px, py, l};
  };
  const auto before = totals();
  double turned = 0.0;
  for (int k = 0; k < 3000; ++k) {
    sim.step();
    turned = std::max(turned, std::abs(e.omega[0]));
  }
  const auto after = totals();
  REQUIRE(sim.gap_springs_intact() == 1);
  CHECK(turned > 0.01);  // the shear spring did turn disk 0 (0.047 rad/s at most)
  CHECK(std::abs(after[0] - before[0]) < 1e-15);
  CHECK(std::abs(after[1] - before[1]) < 1e-15);
  // K18 advances x with the new velocity: L about the origin is kept to O(Δt) per step, not to rounding; the
  // bound is 1e-3 of the initial L (a wrong moment sign loses it entirely)
  CHECK(std::abs(after[2] - before[2]) < 1e-3 * std::abs(before[2]));
}

TEST_CASE("gap spring: the case keys are read strictly, at their line", "[gap_spring]") {
  auto refusal = [](const std::string& gap, const std::string& law = "linear") {
    const std::string text = "[case]\ntitle = \"t\"\n[[material]]\nname = \"m\"\ndensity = \"1000 kg/m^3\"\n"
                             "[[contact]]\nbetween = [\"m\", \"m\"]\nlaw = \"" + law + "\"\nkn = \"1e5 N/m\"\n"
                             "gap = " + gap + "\n[numerics]\ndt = \"1e-6 s\"\nduration = \"1 ms\"\n";
    return test::message_of<dem::CaseError>([&] { dem::read_case_text(text, "gap.toml", {}); });
  };
  CHECK_THAT(refusal("{ distance = \"0.1 mm\", ks = \"1 N/m\" }"), Catch::StartsWith("gap.toml:10: contact.0.gap") && Catch::Contains("kn"));
  CHECK_THAT(refusal("{ distance = \"-0.1 mm\", kn = \"1 N/m\", ks = \"1 N/m\" }"), Catch::StartsWith("gap.toml:10: contact.0.gap.distance"));
  CHECK_THAT(refusal("{ distance = \"0.1 mm\", kn = \"1 N/m\", ks = \"1 N/m\", tensile_strength = \"0 N\" }"),
             Catch::StartsWith("gap.toml:10: contact.0.gap.tensile_strength"));
  CHECK_THAT(refusal("{ distance = \"0.1 mm\", kn = \"1 N/m\", ks = \"1 N/m\", strength = \"1 N\" }"),
             Catch::StartsWith("gap.toml:10: contact.0.gap.strength"));
  CHECK_THAT(refusal("{ distance = \"0.1 mm\", kn = \"1 N/m\", ks = \"1 N/m\" }", "face"), Catch::Contains("contact.0.gap") && Catch::Contains("linear law"));
}

TEST_CASE("gap spring: checkpoints of a case with gap springs are refused, and an interrupted run writes none", "[gap_spring]") {
  dem::RunOptions opt;
  opt.checkpoint_at_end = true;
  CHECK_THAT(test::message_of<dem::CaseError>([&] { dem::run_case(dem::read_case(kPair, {}), opt); }),
             Catch::Contains("checkpoints of a case with gap springs"));
  opt = {};
  opt.out_dir = std::filesystem::temp_directory_path() / "dem2d_gap_interrupted";
  opt.interrupt_at_step = 10;
  const dem::RunResult r = dem::run_case(dem::read_case(kPair, {}), opt);
  CHECK(r.status == "interrupted");
  CHECK_FALSE(std::filesystem::exists(opt.out_dir / "checkpoint.bin"));
  CHECK(std::filesystem::exists(opt.out_dir / "summary.json"));
}
