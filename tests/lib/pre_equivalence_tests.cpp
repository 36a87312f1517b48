// Pseudo-rectangle elements in whole runs (model.md §2): the order of the two elements of a pair does
// not matter, the contact forces balance, an undamped bonded pair conserves energy, and a PRE with
// N = 1, segment centres, linearised increments and disk mass reproduces the disk DEM (M18).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "dem/simulation.hpp"
#include "test_support.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

dem::PairLaw face_law(int segments, dem::SegmentPositions pos, bool exact, double h_n) {
  dem::PairLaw law;
  law.kind = dem::LawKind::face;
  law.face.segments = segments;
  law.face.positions = pos;
  law.face.normal = exact ? dem::NormalIncrement::exact : dem::NormalIncrement::linearised;
  law.face.tangential = exact ? dem::TangentialIncrement::exact : dem::TangentialIncrement::linearised;
  law.face.tensile_strength = 1e15;
  law.face.cohesion = 1e15;
  law.face.tan_phi = 0.5;
  law.damping_ratio = h_n;
  return law;
}

struct Body {
  double r;
  dem::Vec2 x, v;
  double omega;
};

/// A bonded pair (same group) of two PREs, in the given order.
dem::Model pair_model(const Body& first, const Body& second, const dem::PairLaw& law, dem::Vec2 gravity, double dt) {
  auto m = test::make_model({{"pre", 2650.0}}, dt);
  test::set_law(m, 0, 0, law);
  m.laws[0].face_kn = 1e5;
  m.laws[0].face_ks = 4e4;
  m.gravity = gravity;
  for (const Body* b : {&first, &second}) {
    const auto i = dem::add_element(m, dem::Shape::pre, 0, b->r, b->x, b->v, b->omega);
    m.elements.group[i] = 0;
  }
  return m;
}

}  // namespace

TEST_CASE("PRE pair: swapping elements 1 and 2 gives the same forces and moments on each element",
          "[face][simulation]") {
  const bool exact = GENERATE(true, false);
  CAPTURE(exact);
  const auto law = face_law(3, dem::SegmentPositions::centres, exact, 0.3);
  // pre-loaded (overlap 0.1 mm), unequal radii, relative rotation and sliding
  const Body a{0.010, {0.0, 0.0}, {0.05, 0.1}, 20.0};
  const double dir = 0.35;  // line of centres at 20° to the x axis, centre distance 21.9 mm
  const Body b{0.012, {0.0219 * std::cos(dir), 0.0219 * std::sin(dir)}, {-0.02, -0.05}, -10.0};
  const dem::Vec2 g{0.0, -9.81};
  dem::Simulation s1(pair_model(a, b, law, g, 1e-5)), s2(pair_model(b, a, law, g, 1e-5));
  const auto& e1 = s1.model().elements;
  const auto& e2 = s2.model().elements;
  const double f_scale = 3 * 1e5 * 1e-4;  // N K_n × overlap [N]
  double max_q = 0.0, max_rot = 0.0;
  for (int k = 0; k < 400; ++k) {
    const dem::Vec2 c0{e1.x[0], e1.y[0]}, c1{e1.x[1], e1.y[1]};  // positions the forces of this step use
    s1.step();
    s2.step();
    CAPTURE(k);
    // element a is 0 in s1 and 1 in s2, element b the other way round
    for (int i = 0; i < 2; ++i) {
      const int j = 1 - i;
      REQUIRE_THAT(e1.fx[i], WithinAbs(e2.fx[j], 1e-10 * f_scale));
      REQUIRE_THAT(e1.fy[i], WithinAbs(e2.fy[j], 1e-10 * f_scale));
      REQUIRE_THAT(e1.moment[i], WithinAbs(e2.moment[j], 1e-10 * f_scale * 0.01));
      REQUIRE_THAT(e1.x[i], WithinAbs(e2.x[j], 1e-15));
      REQUIRE_THAT(e1.phi[i], WithinAbs(e2.phi[j], 1e-12));
    }
    // equal and opposite contact forces (gravity taken out)
    const double f0x = e1.fx[0] - e1.mass[0] * g.x, f0y = e1.fy[0] - e1.mass[0] * g.y;
    const double f1x = e1.fx[1] - e1.mass[1] * g.x, f1y = e1.fy[1] - e1.mass[1] * g.y;
    REQUIRE_THAT(f0x, WithinAbs(-f1x, 1e-12 * f_scale));
    REQUIRE_THAT(f0y, WithinAbs(-f1y, 1e-12 * f_scale));
    // moment balance about the origin: c0 × F0 + c1 × F1 + M0 + M1 = (D − r0 − r1) Q (M12 with the
    // levers r_i of the face, not the distances to a common point: it vanishes only without overlap)
    const auto c = s1.contact(0, 1, false);
    REQUIRE(c.links == 3);
    const double dist = dem::norm(c1 - c0);
    const double torque = dem::cross(c0, {f0x, f0y}) + dem::cross(c1, {f1x, f1y}) + e1.moment[0] + e1.moment[1];
    REQUIRE_THAT(torque, WithinAbs((dist - a.r - b.r) * c.fs, 1e-12 * f_scale * 0.03));
    max_q = std::max(max_q, std::abs(c.fs));
    max_rot = std::max(max_rot, std::abs(e1.phi[0] - e1.phi[1]));
  }
  CHECK(max_q > 0.01 * f_scale);  // the test did exercise shear
  CHECK(max_rot > 1e-3);          // and relative rotation
}

TEST_CASE("PRE pair: an undamped bonded pair conserves energy over 100 periods (K18)", "[face][simulation][energy]") {
  const bool exact = GENERATE(false, true);
  CAPTURE(exact);
  auto law = face_law(2, dem::SegmentPositions::ends, exact, 0.0);
  const double r = 0.01, d = 2 * r;
  auto make = [&](double dt) {
    auto m = test::make_model({{"pre", 2650.0}}, dt);
    test::set_law(m, 0, 0, law);
    m.laws[0].face_kn = 1e6;
    m.laws[0].face_ks = 4e5;
    const double mass = 4 * r * r * 2650.0, inertia = 2.0 / 3.0 * r * r * mass;  // (M17)
    // zero total momentum and angular momentum (the pair does not turn as a whole), all modes excited:
    // L = −D m v_y + I(ω_a + ω_b) = 0
    const double vx = 1e-3, vy = 1e-3, spin = d * mass * vy / (2 * inertia), w_rel = 0.05;
    dem::add_element(m, dem::Shape::pre, 0, r, {-r, 0.0}, {vx, vy}, spin + w_rel);
    dem::add_element(m, dem::Shape::pre, 0, r, {r, 0.0}, {-vx, -vy}, spin - w_rel);
    m.elements.group[0] = m.elements.group[1] = 0;
    return m;
  };
  const double limit = dem::Simulation(make(1.0)).stability_limit();  // ≥ 2/ω_max (K18, ζ = 0)
  const double dt = 5e-4 * limit;                                    // ω_max Δt ≤ 1e-3
  dem::Simulation sim(make(dt));
  const double mass = sim.model().elements.mass[0];
  const double period = 2 * std::numbers::pi / std::sqrt(2e6 / (0.5 * mass));  // normal mode: N K_n on m/2
  const auto steps = static_cast<long>(100 * period / dt);
  sim.step();
  const double e0 = sim.energies().total();
  double drift = 0.0;
  for (long k = 1; k < steps; ++k) {
    sim.step();
    if (k % 16 == 0) drift = std::max(drift, std::abs(sim.energies().total() - e0));
  }
  drift = std::max(drift, std::abs(sim.energies().total() - e0));
  const double rel = drift / e0;
  CAPTURE(steps, dt, rel);
  WARN("energy drift over 100 periods, " << (exact ? "exact" : "linearised") << " increments: " << rel << " (" << steps << " steps)");
  CHECK(sim.contact(0, 1, false).links == 2);
  CHECK(rel < 1e-3);
}
