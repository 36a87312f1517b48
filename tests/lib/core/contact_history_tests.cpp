// Contact history across neighbour-list rebuilds (docs/style.md §10: history keyed by a stable pair id).
// A run with a small Verlet skin rebuilds its candidate list many times; a run with a huge skin never
// does. Both must give the same trajectory and forces to round-off: a history lost or mixed up at a
// rebuild would reset an accumulated shear (or a bond) and show at once.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("history: sliding contacts keep their elastic shear force across many rebuilds", "[history]") {
  const auto path = test::case_dir() / "history_sliding.toml";
  const auto small = dem::read_case(path);
  const auto huge = dem::read_case(path, {"numerics.skin=10 m"});
  REQUIRE(small.model.numerics.skin == 5e-4);
  REQUIRE(huge.model.numerics.skin == 10.0);
  dem::check_case(small);
  dem::Simulation a(small.model), b(huge.model);
  const double mu = 0.1;
  const auto& ea = a.model().elements;
  const auto& eb = b.model().elements;
  double prev_drum = 0.0, prev_incline = 0.0;
  for (int k = 0; k < 1000; ++k) {
    a.step();
    b.step();
    const auto drum_a = a.contact(0, 1, false), drum_b = b.contact(0, 1, false);
    const auto inc_a = a.contact(2, 0, true), inc_b = b.contact(2, 0, true);
    CAPTURE(k, a.rebuilds());
    // both contacts last the whole run (from the first steps: the elements start touching to
    // round-off, so a contact may form one step late)
    if (k >= 3) {
      REQUIRE(drum_a.links == 1);
      REQUIRE(inc_a.links == 1);
    }
    // identical to the run without rebuilds
    REQUIRE_THAT(drum_a.fs, WithinAbs(drum_b.fs, 1e-12 * std::abs(drum_b.fn)));
    REQUIRE_THAT(drum_a.fn, WithinAbs(drum_b.fn, 1e-12 * std::abs(drum_b.fn)));
    REQUIRE_THAT(inc_a.fs, WithinAbs(inc_b.fs, 1e-12 * std::abs(inc_b.fn)));
    for (std::size_t i = 0; i < 3; ++i) {
      REQUIRE_THAT(ea.x[i], WithinAbs(eb.x[i], 1e-14));
      REQUIRE_THAT(ea.y[i], WithinAbs(eb.y[i], 1e-14));
      REQUIRE_THAT(ea.phi[i], WithinAbs(eb.phi[i], 1e-12));
    }
    // continuous shear: once the landing transient has decayed, it changes by under 2 % a step
    if (k > 200) {
      REQUIRE(std::abs(drum_a.fs - prev_drum) < 0.02 * std::abs(prev_drum));
      REQUIRE(std::abs(inc_a.fs - prev_incline) < 0.02 * std::abs(prev_incline));
    }
    prev_drum = drum_a.fs;
    prev_incline = inc_a.fs;
  }
  CHECK(a.rebuilds() > 20);
  CHECK(b.rebuilds() == 1);
  // still sliding at the end: the shear is at the Coulomb limit μ e_n (f_n differs from e_n by the
  // normal dashpot, a few per cent on the drum where the normal force keeps falling), the contact
  // points slip, and the elements travelled many skins
  const auto drum = a.contact(0, 1, false), inc = a.contact(2, 0, true);
  CHECK_THAT(std::abs(drum.fs), WithinRel(mu * drum.fn, 0.05));
  CHECK_THAT(std::abs(inc.fs), WithinRel(mu * inc.fn, 0.05));
  // slip increment of the last step (K5): −u_x n_y + u_y n_x + r Δφ with u the relative increment
  const double slip_drum = ea.dx[1] * drum.ny - ea.dy[1] * drum.nx + 0.01 * ea.dphi[1];
  const double slip_incline = -ea.dx[2] * inc.ny + ea.dy[2] * inc.nx + 0.01 * ea.dphi[2];
  CHECK(std::abs(slip_drum) > 0.2 * std::hypot(ea.dx[1], ea.dy[1]));
  CHECK(std::abs(slip_incline) > 0.2 * std::hypot(ea.dx[2], ea.dy[2]));
  CHECK(std::hypot(ea.x[2] - small.model.elements.x[2], ea.y[2] - small.model.elements.y[2]) > 20 * 5e-4);
  CHECK(std::hypot(ea.x[1] - small.model.elements.x[1], ea.y[1] - small.model.elements.y[1]) > 20 * 5e-4);
}

namespace {

// Two bonded PRE contacts that are stretched (in tension) well beyond the Verlet skin: element 1
// pulled away from the fixed element 0, element 2 pulled up from a floor. N = 2, undamped, strengths
// never reached: each is an undamped oscillator of ω = √(N K_n/m).
dem::Model bonded_model(double skin) {
  auto m = test::make_model({{"pre", 2650.0}, {"wall", 0.0}}, 1e-5);
  dem::PairLaw law = test::bonded_face_law(2, 1e6, 4e5, 0.0);  // h_n = 0.0
  test::set_law(m, 0, 0, law);
  test::set_law(m, 0, 1, law);
  const double r = 0.01;
  dem::add_element(m, dem::Shape::pre, 0, r, {0.0, 0.0});
  dem::add_element(m, dem::Shape::pre, 0, r, {2 * r, 0.0}, {0.01, 0.0});
  dem::add_element(m, dem::Shape::pre, 0, r, {1.0, r}, {0.0, 0.01});
  m.elements.motion[0] = dem::Motion::fixed;
  m.walls.push_back(test::segment_wall({0.5, 0.0}, {1.5, 0.0}, 1, "floor"));
  m.numerics.skin = skin;
  return m;
}

}  // namespace

TEST_CASE("history: a bonded face stretched beyond the skin keeps its history (must_keep)", "[history][face]") {
  const double skin = 1e-7;
  dem::Simulation a(bonded_model(skin)), b(bonded_model(10.0));
  const auto& e = a.model().elements;
  const auto& eb = b.model().elements;
  const double r = 0.01, omega = std::sqrt(2 * 1e6 / e.mass[1]), amplitude = 0.01 / omega;
  int stretched_rebuilds = 0;
  double max_gap_pair = 0.0, max_gap_wall = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const auto before = a.rebuilds();
    const double gap_pair = e.x[1] - e.x[0] - 2 * r, gap_wall = e.y[2] - r;
    a.step();
    b.step();
    if (a.rebuilds() > before && gap_pair > skin && gap_wall > skin) ++stretched_rebuilds;
    max_gap_pair = std::max(max_gap_pair, gap_pair);
    max_gap_wall = std::max(max_gap_wall, gap_wall);
    const auto pair = a.contact(0, 1, false), wall = a.contact(2, 0, true);
    CAPTURE(k, gap_pair, gap_wall);
    REQUIRE(pair.links == 2);
    REQUIRE(wall.links == 2);
    // the linearised normal law keeps P = N K_n × (overlap): tension while stretched
    REQUIRE_THAT(pair.fn, WithinAbs(-2e6 * gap_pair, 1e-9 * 2e6 * amplitude));
    REQUIRE_THAT(wall.fn, WithinAbs(-2e6 * gap_wall, 1e-9 * 2e6 * amplitude));
    REQUIRE_THAT(e.x[1], WithinAbs(eb.x[1], 1e-15));
    REQUIRE_THAT(e.y[2], WithinAbs(eb.y[2], 1e-15));
  }
  CHECK(stretched_rebuilds > 10);
  CHECK(b.rebuilds() == 1);
  // undamped oscillation with the amplitude v0/ω (K18's amplitude error is O(ωΔt) = 1.4 %)
  CHECK_THAT(max_gap_pair, WithinRel(amplitude, 0.02));
  CHECK_THAT(max_gap_wall, WithinRel(amplitude, 0.02));
  CHECK(max_gap_pair > 50 * skin);
}
