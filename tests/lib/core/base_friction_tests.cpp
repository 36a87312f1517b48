// Base friction (M21, docs/model.md §2; docs/references.md §3.1, §3.7): the law on one element (bound,
// direction, moment law), its regularisation below v_ε, the motion of a free element dragged by the
// plate against the closed form, the case keys and the quantities (plate travel, corner slide M23–M24).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/core/base_friction.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/quantities.hpp"
#include "../test_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double kMu = 0.42, kG = 9.80665, kEps = 1e-4;  // μ_B, g_B [m/s²], v_ε [m/s]
constexpr double kMass = 0.0671, kRadius = 0.0125;        // M-C's PRE

/// One free PRE (square mass, M17) on a plate moving at v_plate; no contacts, no gravity in the plane.
dem::Model element_on_plate(dem::Vec2 v_plate, double dt, dem::Vec2 v0 = {}, double omega0 = 0.0) {
  auto m = test::make_model({{"block", 1000.0}}, dt);
  const std::size_t i = dem::add_element(m, dem::Shape::pre, 0, kRadius, {0.0, 0.0}, v0, omega0,
                                         dem::PreMass::square, kMass);
  (void)i;
  m.base_plate.enabled = true;
  m.base_plate.velocity = v_plate;
  m.base_plate.normal_gravity = kG;
  m.base_plate.regularisation_speed = kEps;
  m.base_plate.friction = {kMu};
  return m;
}

const std::string kCase = R"(
[case]
title = "base friction"
[physics]
thickness = "40 mm"
[[material]]
name = "block"
density = "2700 kg/m^3"
base_friction = 0.42
[[element]]
shape = "pre"
material = "block"
radius = "12.5 mm"
mass = "67.1 g"
position = [0.0, 0.0]
[base_friction]
plate_velocity = { magnitude = "5 mm/s", direction = "-120 deg" }
regularisation_speed = "0.1 mm/s"
[numerics]
dt = "1e-5 s"
duration = "1 ms"
)";

std::string case_error(const std::string& text, const std::vector<std::string>& sets = {}) {
  const auto path = test::write_temp("base_friction.toml", text);
  return test::message_of<dem::CaseError>([&] { dem::read_case(path, sets); });
}

/// kCase with its plate_velocity line replaced.
std::string with_plate_line(const std::string& line) {
  std::string text = kCase;
  const auto from = text.find("plate_velocity");
  text.replace(from, text.find('\n', from) - from, line);
  return text;
}

}  // namespace

TEST_CASE("M21 never exceeds mu_B m g_B and opposes the relative motion, above and below v_eps", "[base_friction]") {
  const double mg = kMu * kMass * kG;
  // relative velocities [m/s] and spins [rad/s], from far below to far above v_ε
  const double ux = GENERATE(0.0, 3e-6, -4e-5, 2e-4, -5e-3, 0.3);
  const double uy = GENERATE(0.0, -2e-6, 7e-5, -5e-3);
  const double omega = GENERATE(0.0, 1e-3, -0.05, 2.0);
  CAPTURE(ux, uy, omega);
  const auto f = dem::base_friction_force(kMu, kMass, kRadius, kG, kEps, {ux, uy}, omega);
  const double speed = std::hypot(ux, uy), spin = kRadius * omega;
  const double v = std::sqrt(speed * speed + spin * spin);
  // bound: the translational force, and the whole generalised force (B, B_θ) of M21
  CHECK(std::hypot(f.fx, f.fy) <= mg * (1.0 + 1e-12));
  CHECK(std::hypot(std::hypot(f.fx, f.fy), f.moment / kRadius * 1.5) <= mg * (1.0 + 1e-12));
  // direction: anti-parallel to u, moment against θ̇
  CHECK(f.fx * ux + f.fy * uy <= 0.0);
  CHECK_THAT(f.fx * uy - f.fy * ux, WithinAbs(0.0, 1e-15));
  CHECK(f.moment * omega <= 0.0);
  if (speed > 0.0) CHECK(f.fx * ux + f.fy * uy < 0.0);
  // above v_ε it is M21 itself: |B| = μ m g |u|/V
  if (v >= kEps) CHECK_THAT(std::hypot(f.fx, f.fy), WithinRel(mg * speed / v, 1e-12));
  // below v_ε a dashpot of rate μ g / v_ε per unit mass
  if (v < kEps) CHECK_THAT(std::hypot(f.fx, f.fy), WithinAbs(kMass * dem::base_friction_rate(kMu, kG, kEps) * speed, 1e-15));
  // at V = 0 nothing
  if (v == 0.0) CHECK((f.fx == 0.0 && f.fy == 0.0 && f.moment == 0.0));
}

TEST_CASE("M21 moment law: B_theta = -(r thetadot / V)(2/3) mu_B m g, moment r B_theta", "[base_friction]") {
  const dem::Vec2 u{3e-3, -4e-3};  // |u| = 5 mm/s
  const double omega = 0.24;       // rθ̇ = 3 mm/s, V = √34 mm/s
  const auto f = dem::base_friction_force(kMu, kMass, kRadius, kG, kEps, u, omega);
  const double v = std::sqrt(34.0) * 1e-3, mg = kMu * kMass * kG;
  const double b_theta = -(kRadius * omega / v) * (2.0 / 3.0) * mg;
  CHECK_THAT(f.moment, WithinRel(kRadius * b_theta, 1e-13));
  CHECK_THAT(f.fx, WithinRel(-(u.x / v) * mg, 1e-13));
  CHECK_THAT(f.fy, WithinRel(-(u.y / v) * mg, 1e-13));
  // The rotational damping rate of the linear range: (2/3) μ m g r² / (v_ε I) = μ g / v_ε for M17.
  const double inertia = (2.0 / 3.0) * kRadius * kRadius * kMass;
  CHECK_THAT(dem::base_friction_rotational_rate(kMu, kG, kEps, kMass, kRadius, inertia),
             WithinRel(dem::base_friction_rate(kMu, kG, kEps), 1e-14));
}

TEST_CASE("An element moving with the plate feels no base friction", "[base_friction]") {
  const dem::Vec2 vb{-3e-3, -4e-3};
  dem::Simulation sim(element_on_plate(vb, 1e-5, vb));
  for (int k = 0; k < 100; ++k) sim.step();
  const auto& e = sim.model().elements;
  CHECK(e.fx[0] == 0.0);
  CHECK(e.fy[0] == 0.0);
  CHECK(e.moment[0] == 0.0);
  CHECK(e.vx[0] == vb.x);
  CHECK(e.vy[0] == vb.y);
  CHECK(e.omega[0] == 0.0);
  // the plate travelled 100 steps at 5 mm/s
  CHECK_THAT(sim.plate_travel().travel, WithinRel(100 * 1e-5 * 5e-3, 1e-12));
  CHECK_THAT(sim.plate_travel().displacement.x, WithinRel(100 * 1e-5 * vb.x, 1e-12));
}

TEST_CASE("A free element is dragged up to the plate velocity: linear above v_eps, exponential below", "[base_friction]") {
  // Element at rest, plate at 5 mm/s along (−0.6, −0.8): the relative speed u falls from 5 mm/s at the
  // constant rate μ g (Coulomb) down to v_ε, then decays as exp(−c t), c = μ g / v_ε (the dashpot).
  const double dt = 2e-7;  // cΔt = 0.0082
  const dem::Vec2 dir{-0.6, -0.8};
  const double vb = 5e-3, a = kMu * kG, c = dem::base_friction_rate(kMu, kG, kEps);
  dem::Simulation sim(element_on_plate(dir * vb, dt));
  const double t_eps = (vb - kEps) / a;  // reaches v_ε (closed form)
  double worst_linear = 0.0, worst_exp = 0.0, crossed = -1.0;
  const auto& e = sim.model().elements;
  const double t_end = t_eps + 5.0 / c;  // down to v_ε e^−5
  while (sim.time() < t_end) {
    sim.step();
    const double t = sim.time();
    const dem::Vec2 u{e.vx[0] - dir.x * vb, e.vy[0] - dir.y * vb};
    const double speed = norm(u);
    CHECK_THAT(cross(u, dir), WithinAbs(0.0, 1e-15));  // stays on the line of the plate velocity
    if (t < t_eps - 2 * dt) {
      worst_linear = std::max(worst_linear, std::abs(speed - (vb - a * t)));
    } else if (t > t_eps + 2 * dt) {
      if (crossed < 0.0) crossed = t;
      const double expected = kEps * std::exp(-c * (t - t_eps));
      worst_exp = std::max(worst_exp, std::abs(speed / expected - 1.0));
    }
  }
  CAPTURE(t_eps, c);
  // Linear: K18 integrates a constant force exactly (round-off only).
  CHECK(worst_linear < 1e-13);
  // Exponential: the explicit step gives (1 − cΔt)^n against exp(−c t), a relative error of about
  // n (cΔt)²/2 = c t cΔt/2 (c t ≤ 5 here: 2 %), plus the crossing, up to a step late (cΔt).
  CHECK(worst_exp < 5.0 * c * dt / 2 + 2 * c * dt);
  CHECK(worst_exp > 0.0);
  // the element ends at the plate velocity
  CHECK_THAT(norm(dem::Vec2{e.vx[0] - dir.x * vb, e.vy[0] - dir.y * vb}), WithinRel(kEps * std::exp(-5.0), 0.05));
}

TEST_CASE("A spinning element on the plate spins down at the constant rate mu g / r above v_eps", "[base_friction]") {
  // Square mass (M17): (2/3) μ m g r / I = μ g / r.
  const double omega0 = 2.0, dt = 1e-6;
  dem::Simulation sim(element_on_plate({}, dt, {}, omega0));
  for (int k = 0; k < 1000; ++k) sim.step();
  CHECK_THAT(sim.model().elements.omega[0], WithinRel(omega0 - kMu * kG / kRadius * 1000 * dt, 1e-12));
  CHECK(sim.model().elements.vx[0] == 0.0);
}

TEST_CASE("Base friction case keys: read in SI, and wrong inputs are refused with file:line: key", "[base_friction][case]") {
  const auto path = test::write_temp("base_friction_ok.toml", kCase);
  const dem::Case c = dem::read_case(path);
  const dem::BasePlate& p = c.model.base_plate;
  CHECK(p.enabled);
  CHECK_THAT(p.velocity.x, WithinAbs(5e-3 * std::cos(-2.0 * std::numbers::pi / 3.0), 1e-15));
  CHECK_THAT(p.velocity.y, WithinAbs(5e-3 * std::sin(-2.0 * std::numbers::pi / 3.0), 1e-15));
  CHECK(p.normal_gravity == 9.80665);
  CHECK_THAT(p.regularisation_speed, WithinRel(1e-4, 1e-14));
  REQUIRE(p.friction.size() == 1);
  CHECK(p.friction[0] == 0.42);

  // μ_B without a plate
  auto no_table = kCase.substr(0, kCase.find("[base_friction]")) + "[numerics]\ndt = \"1e-5 s\"\nduration = \"1 ms\"\n";
  CHECK_THAT(case_error(no_table), Contains(":9: material.base_friction:") && Contains("no [base_friction] table"));
  // v_ε too small for Δt: names its line
  const auto msg = case_error(kCase, {"base_friction.regularisation_speed=\"0.01 mm/s\""});
  CHECK_THAT(msg, Contains("base_friction.regularisation_speed") && Contains("> 1"));
  CHECK_NOTHROW(dem::read_case(path, {"base_friction.regularisation_speed=\"0.01 mm/s\"", "numerics.allow_unstable=true"}));
  CHECK_NOTHROW(dem::read_case(path, {"base_friction.regularisation_speed=\"0.05 mm/s\""}));  // cΔt = 0.82
  // no velocity, both velocity and drive, unknown drive, wrong unit
  CHECK_THAT(case_error(kCase, {"base_friction.plate_drive=belt"}), Contains("exactly one of plate_velocity"));
  CHECK_THAT(case_error(with_plate_line("plate_drive = \"belt\"")), Contains(":17: base_friction.plate_drive: unknown drive"));
  CHECK_THAT(case_error(with_plate_line("normal_gravity = \"9 m/s^2\"")), Contains(":16: base_friction:") && Contains("exactly one of"));
  CHECK_THAT(case_error(kCase, {"base_friction.regularisation_speed=\"0.1 mm\""}), Contains("base_friction.regularisation_speed"));
  CHECK_THAT(case_error(kCase, {"material.0.base_friction=0.0"}), Contains("no [[material]] has base_friction"));
  CHECK_THAT(case_error(kCase, {"base_friction.spead=1"}), Contains("spead"));
}

TEST_CASE("A plate given by a [[drive]] table moves the plate and drags the element", "[base_friction][case]") {
  std::string text = with_plate_line("plate_drive = \"belt\"");
  text += "[[drive]]\nname = \"belt\"\ntimes = [\"0 s\", \"1 ms\"]\nvelocities = [[0, 0], [\"-10 mm/s\", 0]]\n";
  const auto path = test::write_temp("base_friction_drive.toml", text);
  dem::Simulation sim(dem::read_case(path).model);
  for (int k = 0; k < 100; ++k) sim.step();
  // travel ∫|v| dt of a ramp to −10 mm/s in 1 ms: ½ · 10 mm/s · 1 ms = 5 μm (midpoint rule: exact)
  CHECK_THAT(sim.plate_travel().travel, WithinRel(5e-6, 1e-9));
  CHECK_THAT(sim.plate_travel().displacement.x, WithinRel(-5e-6, 1e-9));
  CHECK(sim.model().elements.vx[0] < 0.0);  // dragged along −x
}

TEST_CASE("Quantities: plate travel, and the corner slide of M23-M24", "[base_friction][quantities]") {
  const double alpha = GENERATE(0.0, 30.0, 62.5);
  CAPTURE(alpha);
  const double a = alpha * std::numbers::pi / 180.0;
  auto m = element_on_plate({0.0, -5e-3}, 1e-5);
  m.elements.phi[0] = a;  // the element's sides along a slope inclined at α
  dem::Simulation sim(m);
  const auto slide = dem::compile_quantity(fmt::format("e0.corner_slide({})", alpha), sim.model());
  const auto travel = dem::compile_quantity("plate_travel", sim.model());
  CHECK(slide(sim) == 0.0);
  auto& e = sim.model().elements;
  // slide the element by d down the slope (−(cos α, sin α)): δ = d
  const double d = 1.5e-3;
  e.x[0] -= d * std::cos(a);
  e.y[0] -= d * std::sin(a);
  CHECK_THAT(slide(sim), WithinAbs(d, 1e-15));
  // then rotate it by θ about its lower corner (the pivot): δ unchanged
  const double th = 0.7, s2r = std::sqrt(2.0) * kRadius;
  const dem::Vec2 corner{e.x[0] + s2r * std::cos(1.25 * std::numbers::pi + a), e.y[0] + s2r * std::sin(1.25 * std::numbers::pi + a)};
  e.phi[0] += th;
  e.x[0] = corner.x - s2r * std::cos(1.25 * std::numbers::pi + a + th);
  e.y[0] = corner.y - s2r * std::sin(1.25 * std::numbers::pi + a + th);
  CHECK_THAT(slide(sim), WithinAbs(d, 1e-15));
  // M24 as printed, x_c = x + √2 r cos(5π/4 + α + θ) with θ the rotation since the start
  const double xc = e.x[0] + s2r * std::cos(1.25 * std::numbers::pi + a + th);
  CHECK_THAT(xc, WithinAbs(corner.x, 1e-15));
  // plate travel
  sim.step();
  sim.step();
  CHECK_THAT(travel(sim), WithinRel(2 * 5e-3 * 1e-5, 1e-12));
  CHECK_THROWS_WITH(dem::compile_quantity("e0.corner_slide(abc)", sim.model()), Contains("degrees"));
  CHECK_THROWS_WITH(dem::compile_quantity("e7.corner_slide(30)", sim.model()), Contains("does not exist"));
}

TEST_CASE("The time-step guard counts base friction's dashpot: mu_B g_B / v_eps", "[base_friction][guard]") {
  const auto path = test::write_temp("base_friction_guard.toml", kCase);
  // v_ε = 0.01 mm/s: c = μ_B g_B / v_ε = 4.12e5 1/s, far above the contact rates of kCase
  const dem::Case c = dem::read_case(path, {"base_friction.regularisation_speed=\"0.01 mm/s\"", "numerics.allow_unstable=true"});
  const double rate = 0.42 * 9.80665 / 1e-5;
  const dem::StabilityBound with = dem::Simulation(c.model).stability_bound();
  dem::Model off = c.model;
  off.base_plate.enabled = false;
  const dem::StabilityBound without = dem::Simulation(off).stability_bound();
  CHECK(with.limit < without.limit);
  CHECK(with.limit * rate <= 2.0);  // an explicit dashpot alone is stable only for cΔt < 2
  CHECK_THAT(with.law, Contains("base friction"));
}

// A disk on the plate (issue 40: base friction acted only on PREs in the tests): its inertia m r²/2 makes
// the spin-down rate (2/3) μ m g r / I = (4/3) μ g / r; its centre is dragged at μ g as a PRE's.
// Planted bug that turned this red: base friction applied to PREs only (disks skipped).
TEST_CASE("A disk on the plate spins down at (4/3) mu g / r and is dragged at mu g", "[base_friction]") {
  for (const auto& [omega0, vb] : {std::pair{2.0, 0.0}, std::pair{-3.0, 4e-3}}) {
    CAPTURE(omega0, vb);
    const double dt = 1e-6;
    dem::Model m = element_on_plate({0.0, -vb}, dt);
    m.elements = {};
    dem::add_element(m, dem::Shape::disk, 0, kRadius, {0.0, 0.0}, {}, omega0, dem::PreMass::square, kMass);
    REQUIRE(m.elements.inertia[0] == 0.5 * kMass * kRadius * kRadius);
    dem::Simulation sim(m);
    for (int k = 0; k < 100; ++k) sim.step();
    const double t = 100 * dt, g = kMu * kG;
    // V = √(u² + (rθ̇)²): the friction splits between spin and slide in the ratio rθ̇ : u
    const auto& e = sim.model().elements;
    if (vb == 0.0) {
      CHECK_THAT(e.omega[0], WithinRel(omega0 - (4.0 / 3.0) * g / kRadius * t, 1e-12));
      CHECK(e.vy[0] == 0.0);
    } else {  // the first step as M21 gives it, on the disk's inertia
      dem::Simulation one(m);
      one.step();
      const double v = std::hypot(vb, kRadius * omega0);
      const auto& f = one.model().elements;
      CHECK_THAT(f.vy[0], WithinRel(-(vb / v) * g * dt, 1e-9));
      CHECK_THAT(f.omega[0] - omega0, WithinRel(-(kRadius * omega0 / v) * (2.0 / 3.0) * kMass * g * kRadius /
                                                    (0.5 * kMass * kRadius * kRadius) * dt, 1e-9));
    }
  }
}
