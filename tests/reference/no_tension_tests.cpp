// Unilateral contacts (ref/no_tension.hpp): the active-set solve against answers known by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "ref/lattice_beam.hpp"
#include "ref/no_tension.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using ref::RigidSpringNetwork;
using ref::SegmentPositions;

namespace {
constexpr double k = 1e6, L = 0.5, P = 100.0;

// A rigid plank (one body at the origin) on three vertical support springs at x = −L, 0, L, a load P
// down at x = e. The support contacts point from the plank down to the ground: tension > 0.
struct Plank {
  RigidSpringNetwork net;
  std::vector<ref::UnilateralContact> supports;
  explicit Plank(double e) {
    const int plank = net.add_body(0.0, 0.0);
    for (double x : {-L, 0.0, L}) supports.push_back({net.add_spring(plank, RigidSpringNetwork::ground, x, 0.0, 0.0, -1.0, k), -1});
    net.add_load(plank, 0.0, -P, -P * e);  // the torque of a downward force at x = e
    net.prescribe(plank, 0, 0.0);          // vertical springs carry no horizontal force
  }
};
}  // namespace

TEST_CASE("No tension: a rigid plank on three supports loaded near one end lifts off the far one", "[no_tension]") {
  const double e = 0.9 * L;
  Plank linear(e);
  const auto u_lin = linear.net.solve();
  // Linear springs (hand): support forces, compression, P/3 + P e x/(2L²): the one at x = −L pulls.
  CHECK_THAT(-linear.net.spring_force(u_lin, 0), WithinRel(P / 3 - P * e / (2 * L), 1e-12));
  REQUIRE(linear.net.spring_force(u_lin, 0) > 0.0);

  Plank plank(e);
  const auto sol = ref::solve_no_tension(plank.net, plank.supports);
  CHECK(sol.open[0]);
  CHECK_FALSE(sol.open[1]);
  CHECK_FALSE(sol.open[2]);
  // Two supports left, statically determinate (hand): P(L − e)/L at x = 0, P e/L at x = L.
  CHECK_THAT(-plank.net.spring_force(sol.u, 1), WithinRel(P * (L - e) / L, 1e-12));
  CHECK_THAT(-plank.net.spring_force(sol.u, 2), WithinRel(P * e / L, 1e-12));
  CHECK(plank.net.spring_force(sol.u, 0) == 0.0);
  // Settlements F/k at 0 and L; the plank's left end rises by (P e/L − 2P(L − e)/L)/k, a gap (no penetration).
  const double w0 = P * (L - e) / L / k, wL = P * e / L / k;
  CHECK_THAT(plank.net.point_displacement(sol.u, 0, 0.0, 0.0, 1), WithinRel(-w0, 1e-12));
  CHECK_THAT(plank.net.point_displacement(sol.u, 0, L, 0.0, 1), WithinRel(-wL, 1e-12));
  CHECK_THAT(plank.net.extension(sol.u, 0), WithinRel(wL - 2 * w0, 1e-12));
  CHECK(plank.net.extension(sol.u, 0) > 0.0);
  CHECK(plank.net.relative_residual(sol.u) < 1e-12);
}

TEST_CASE("No tension: a plank loaded inside its supports keeps all three (the linear answer)", "[no_tension]") {
  const double e = 0.2 * L;  // P/3 − P e/(2L) > 0: no support pulls
  Plank linear(e);
  const auto u_lin = linear.net.solve();
  Plank plank(e);
  const auto sol = ref::solve_no_tension(plank.net, plank.supports);
  CHECK(sol.iterations == 1);
  for (int i = 0; i < 3; ++i) {
    CHECK_FALSE(sol.open[static_cast<std::size_t>(i)]);
    CHECK(plank.net.spring_force(sol.u, i) == linear.net.spring_force(u_lin, i));
  }
}

TEST_CASE("No tension: a bonded plank on three supports loaded on both overhangs lifts off the middle one", "[no_tension]") {
  // 9 bonded squares (r = 5 mm, N = 5) along x; supports under elements 1, 4, 7; P down on 0 and 8.
  // Hogging between the outer supports lifts the middle: linear, it pulls; no tension, it opens and
  // each outer support carries P (statics, symmetric).
  constexpr double r = 0.005;
  auto build = [&](RigidSpringNetwork& net, std::vector<ref::UnilateralContact>& supports) {
    for (int j = 0; j < 9; ++j) net.add_body(2 * r * j, r);
    for (int j = 0; j < 8; ++j) ref::add_bonded_face(net, j, j + 1, r, 0.04, 4300e6, 1720e6, 5, SegmentPositions::centres);
    for (int j : {1, 4, 7}) supports.push_back({net.add_spring(j, RigidSpringNetwork::ground, 2 * r * j, 0.0, 0.0, -1.0, 172e6), -1});
    net.add_load(0, 0.0, -P, 0.0);
    net.add_load(8, 0.0, -P, 0.0);
    net.prescribe(4, 0, 0.0);
  };
  RigidSpringNetwork linear;
  std::vector<ref::UnilateralContact> s_lin;
  build(linear, s_lin);
  const auto u_lin = linear.solve();
  REQUIRE(linear.spring_force(u_lin, s_lin[1].normal) > 0.0);  // the middle support would pull

  RigidSpringNetwork net;
  std::vector<ref::UnilateralContact> supports;
  build(net, supports);
  const auto sol = ref::solve_no_tension(net, supports);
  CHECK(sol.open[1]);
  CHECK_THAT(-net.spring_force(sol.u, supports[0].normal), WithinRel(P, 1e-9));
  CHECK_THAT(-net.spring_force(sol.u, supports[2].normal), WithinRel(P, 1e-9));
  CHECK(net.extension(sol.u, supports[1].normal) > 0.0);  // a gap under the middle
  CHECK(net.relative_residual(sol.u) < 1e-12);
}

TEST_CASE("No tension: a contact without its normal spring is refused", "[no_tension]") {
  Plank plank(0.0);
  CHECK_THROWS_AS(ref::solve_no_tension(plank.net, {{-1, -1}}), std::invalid_argument);
}
