// The angular room of a bonded element (docs/model.md G6) and the block bound (G5) that uses it: the
// contacts a bonded element can still form go on the diagonal of the elements with room for one, not on
// every element. Planted bugs that turn these red: room given to every element (the guard falls back to
// the uniform shift), room denied to every element (the guard is then above the limit of a disk that
// does touch an edge element: unsafe), and a separation rule off by a factor.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "dem/core/simulation.hpp"
#include "dem/core/stability_eigen.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

namespace {
constexpr double kn = 1e5, r = 0.01, m_pre = 0.5;
constexpr double inf = std::numeric_limits<double>::infinity();

/// A 3 × 3 square lattice of free PREs (0.5 kg, radius r, touching, bonded by `face_kn`, segments at the
/// ends, K_s = 0, no dashpots), element 4 in the centre, 1 the middle of the top row; and, if `disk_y` is
/// finite, a free disk (material 1, radius r, `disk_mass`) at (0, disk_y) with a linear law `disk_kn`, K18.
dem::Model lattice(double face_kn, double disk_kn, double disk_mass, double disk_y) {
  dem::Model m = test::blocks_and_disk_laws(face_kn, disk_kn);
  for (int row = 0; row < 3; ++row)  // top row first: y = 2r, 0, −2r
    for (int col = 0; col < 3; ++col)
      dem::add_element(m, dem::Shape::pre, 0, r, {2 * r * (col - 1), 2 * r * (1 - row)}, {}, 0.0, dem::PreMass::square, m_pre);
  if (std::isfinite(disk_y)) dem::add_element(m, dem::Shape::disk, 1, r, {0.0, disk_y}, {}, 0.0, dem::PreMass::square, disk_mass);
  return m;
}
}  // namespace

/// The lattice with a wall (material "disk", which has a law with the blocks) moving at 10 m/s for 0.01 s
/// (10 cm of travel: every element within reach of its face), numerics.guard_reach 1 mm.
dem::Model with_moving_wall(dem::Wall w) {
  dem::Model m = lattice(kn, kn, 1.0, inf);
  m.numerics.duration = 0.01;
  m.numerics.guard_reach = 0.001;
  m.drives.push_back(dem::VelocityHistory{{0.0}, {dem::Vec2{0.0, -10.0}}});
  w.drive = 0;
  m.walls.push_back(w);
  return m;
}

TEST_CASE("angular room: four square neighbours leave none for a wall's face or an equal disk", "[stability]") {
  // a long wall above the lattice, its ends 1 m away (out of reach: 10 cm of travel + 1 mm + r)
  const dem::Model walled = with_moving_wall(test::segment_wall({-1.0, 4 * r}, {1.0, 4 * r}, 1));
  const auto wall = dem::angular_room(walled, inf);
  const dem::Model bare = lattice(kn, kn, 1.0, inf);
  const auto equal = dem::angular_room(bare, r);
  for (std::size_t i = 0; i < 9; ++i) {
    CAPTURE(i);
    CHECK(wall[i] == (i != 4));  // the centre, 4, has neighbours every 90°
    CHECK(equal[i] == (i != 4));
  }
  // nothing can come: no room anywhere
  for (auto x : dem::angular_room(bare, inf)) CHECK(x == 0);
  // the same wall static, 1 r above the top row: within reach of the top row only (r + 1 mm)
  dem::Model still = walled;
  still.walls[0].drive = -1;
  still.walls[0].a.y = still.walls[0].b.y = 3.05 * r;
  const auto top = dem::angular_room(still, inf);
  for (std::size_t i = 0; i < 9; ++i) CHECK(top[i] == (i < 3));
}

TEST_CASE("angular room: a wall's end or a point wall within reach fits between two neighbours", "[stability]") {
  // A point needs no angle beside a neighbour: an element with any gap has room for it, the centre too.
  dem::Wall point = test::segment_wall({0.0, 0.08}, {0.0, 0.08}, 1);  // 8 cm above the centre, 10 cm of travel
  point.kind = dem::WallKind::point;
  for (const auto& x : dem::angular_room(with_moving_wall(point), inf)) CHECK(x == 1);
  // a segment whose end comes within reach: its end is such a point
  const auto end = dem::angular_room(with_moving_wall(test::segment_wall({0.0, 0.05}, {0.0, 1.0}, 1)), inf);
  for (const auto& x : end) CHECK(x == 1);
}

TEST_CASE("angular room: a small disk fits the notch between two square neighbours exactly as the geometry says", "[stability]") {
  // Into the notch between the centre's neighbours at 0° and 90° fits a disk touching all three when its
  // radius is at most (√2 − 1) r. With the guard's allowances (each neighbour turned by 1°, overlaps of
  // 1 %) the threshold ρ* solves 2 θ(ρ) = 90° + 2°, θ(ρ) = acos(((2r)² + (r+ρ)² − (0.99(r+ρ))²) / (2·2r(r+ρ))).
  const dem::Model m = lattice(kn, kn, 1.0, inf);
  auto theta = [](double rho) {
    const double d2 = r + rho, d12 = 0.99 * (r + rho);
    return std::acos((4 * r * r + d2 * d2 - d12 * d12) / (4 * r * d2));
  };
  const double target = (90.0 + 2.0) / 360.0 * std::numbers::pi;  // half of 92°
  double lo = 0.1 * r, hi = r;                                    // θ grows with ρ: bisect θ(ρ*) = 46°
  for (int k = 0; k < 100; ++k) (theta(0.5 * (lo + hi)) > target ? hi : lo) = 0.5 * (lo + hi);
  const double rho_star = 0.5 * (lo + hi);
  REQUIRE(rho_star > (std::sqrt(2.0) - 1.0) * r);  // the allowances only widen the notch
  REQUIRE(rho_star < 0.5 * r);
  CHECK(dem::angular_room(m, rho_star * (1 - 1e-6))[4] == 1);
  CHECK(dem::angular_room(m, rho_star * (1 + 1e-6))[4] == 0);
}

TEST_CASE("block bound G5 with room G6: the new contacts sit on the edge elements only", "[stability]") {
  // The lattice and a heavy disk far away (its own row is slow): the block bound is the eigenvalue of the
  // lattice plus, on the 8 edge elements' DOFs, one disk contact's row share w + b, plus the coupling
  // √z·b (z = 6 equal disks around one), as docs/model.md G5 states.
  constexpr double m_disk = 50.0, k_disk = 10 * kn;
  const dem::Model m = lattice(kn, k_disk, m_disk, 1.0);
  const dem::StabilityBound b = dem::Simulation(m).stability_bound();
  REQUIRE(b.eigen);
  const double w = k_disk / m_pre, bb = k_disk / std::sqrt(m_pre * m_disk), coupling = std::sqrt(6.0) * bb;
  const dem::StartNetwork net = dem::start_network(m);
  dem::StartNetwork block = dem::start_network(m, &net.bonded);
  REQUIRE(block.dofs == 27);
  block.diag_k.assign(27, 0.0);
  block.diag_c.assign(27, 0.0);
  for (std::size_t i = 0; i < 9; ++i)
    for (int k = 0; k < 3 && i != 4; ++k) block.diag_k[static_cast<std::size_t>(block.dof[i] + k)] = w + bb;
  const double expected = dem::eigen_limit(block, dem::Integrator::k18, false, coupling, 0.0, inf);
  CHECK_THAT(b.limit_block, WithinRel(expected, 1e-9));
  // every element shifted (the centre too): the bound before G6, which the guard now exceeds
  const dem::StartNetwork plain = dem::start_network(m, &net.bonded);
  const double uniform = dem::eigen_limit(plain, dem::Integrator::k18, false, w + bb + coupling, 0.0, inf);
  CHECK(b.limit_block > uniform * 1.001);
}

TEST_CASE("block bound G5 with room G6: never above the limit once the disk touches an edge element", "[stability]") {
  // The same lattice with the disk far away (the guard) and with the disk resting on the top middle
  // element (its contact present at the start: the exact eigenvalue of the network it claims to cover).
  constexpr double m_disk = 50.0, k_disk = 100 * kn;
  const dem::StabilityBound b = dem::Simulation(lattice(kn, k_disk, m_disk, 1.0)).stability_bound();
  const double guard = b.limit;
  const dem::Model touching = lattice(kn, k_disk, m_disk, 4 * r);
  const dem::StartNetwork net = dem::start_network(touching);
  REQUIRE(net.dofs == 30);
  const double exact = dem::eigen_limit(net, dem::Integrator::k18, false, 0.0, 0.0, inf);
  CHECK(guard <= exact);
  CHECK(b.limit_block <= exact);  // each of the guard's bounds is safe on its own
  CHECK(b.limit_gershgorin <= exact);
  CHECK(guard >= 0.8 * exact);  // and not far below it (measured 0.90)
}

TEST_CASE("guard G4: a fixed element a bonded one can still reach counts on the bonded side", "[stability]") {
  // A fixed stiff disk far above the lattice (no unbonded free element: G5 does not apply, G4 is the bound)
  // and the same disk resting on the top middle element: the guard of the first must not exceed the exact
  // limit of the second (a fixed partner was left out of G4 before this test).
  constexpr double k_disk = 100 * kn;
  auto with_fixed_disk = [&](double y) {
    dem::Model m = lattice(kn, k_disk, 50.0, y);
    m.elements.motion[9] = dem::Motion::fixed;
    return m;
  };
  const double guard = dem::Simulation(with_fixed_disk(1.0)).stability_bound().limit;
  const dem::StartNetwork net = dem::start_network(with_fixed_disk(4 * r));
  REQUIRE(net.dofs == 27);
  const double exact = dem::eigen_limit(net, dem::Integrator::k18, false, 0.0, 0.0, inf);
  CHECK(guard <= exact);
  CHECK(guard >= 0.8 * exact);  // and not far below it
}
