// The exact linear-elastic PRE lattice (ref/lattice_beam.hpp) against hand formulas and refs §4.3.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <stdexcept>

#include "ref/beam.hpp"
#include "ref/lattice_beam.hpp"
#include "ref/registry.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using ref::RigidSpringNetwork;
using ref::SegmentPositions;

namespace {
constexpr double kn = 4300e6, ks = 1720e6, ell = 0.04, r = 0.005;

// A 1 × (n + 1) chain along x, body 0 clamped.
RigidSpringNetwork chain(int n, int segments, SegmentPositions where) {
  RigidSpringNetwork net;
  for (int j = 0; j <= n; ++j) net.add_body(2 * r * j, 0.0);
  for (int j = 0; j < n; ++j) ref::add_bonded_face(net, j, j + 1, r, ell, kn, ks, segments, where);
  for (int c = 0; c < 3; ++c) net.prescribe(0, c, 0.0);
  return net;
}

// Rotational stiffness of one face: Σ K_n (rξ_i)², K_n = k_n ℓ/N (M6.3).
double face_rotational_stiffness(int segments, SegmentPositions where) {
  double sum = 0.0;
  for (int i = 1; i <= segments; ++i) {
    const double xi = where == SegmentPositions::centres ? double(2 * i - 1 - segments) / segments : 2.0 * i - 3.0;
    sum += kn * ell / segments * (r * xi) * (r * xi);
  }
  return sum;
}

ref::LatticeBeamModel md_beam(int rows, bool friction) {
  ref::LatticeBeamModel m;
  m.rows = rows;
  m.columns = 4 * rows;
  m.radius = 0.020 / rows;
  m.thickness = 0.040;
  m.kn = kn;
  m.ks = ks;
  m.segments = 5;
  m.span = 0.100;
  m.support_radius = m.load_radius = 0.005;
  m.contact_kn = 172e6;
  m.contact_kt = friction ? 0.4 * 172e6 : 0.0;
  m.platen_kt = friction ? 0.4 * 1720e6 : 0.0;
  return m;
}
}  // namespace

TEST_CASE("Lattice: a 1 x n chain under a tip force is a chain of hinged shear springs (hand formula)", "[lattice_beam]") {
  for (const auto where : {SegmentPositions::centres, SegmentPositions::face_ends}) {
    for (int N : {1, 2, 3, 5}) {
      if (where == SegmentPositions::face_ends && N != 2) continue;
      if (N == 1) continue;  // no face rotational stiffness: a mechanism under a tip force
      const int n = 6;
      auto net = chain(n, N, where);
      const double F = 1000.0;
      net.add_load(n, 0.0, F, 0.0);
      const auto u = net.solve();
      // Element j turns about its face with j − 1 by φ_j = M_j/K_θ and slips along it by F/(k_s ℓ);
      // M_j = F d_j with d_j = (2n − 2j + 1) r the lever from the face to the tip centre.
      const double Kt = face_rotational_stiffness(N, where);
      double tip = 0.0, turn = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double d = (2.0 * n - 2.0 * j + 1.0) * r;
        tip += F / (ks * ell) + F * d * d / Kt;
        turn += F * d / Kt;
      }
      CHECK_THAT(u[3 * n + 1], WithinRel(tip, 1e-10));
      CHECK_THAT(u[3 * n + 2], WithinRel(turn, 1e-10));
      CHECK_THAT(u[3 * n], WithinAbs(0.0, 1e-12 * tip));  // no axial force, no axial motion
      CHECK(net.relative_residual(u) < 1e-12);
    }
  }
}

TEST_CASE("Lattice: pure bending of a chain gives k_n I_eff with refs 4.3's I_eff", "[lattice_beam]") {
  for (const auto where : {SegmentPositions::centres, SegmentPositions::face_ends}) {
    for (int N : {2, 3, 4, 5}) {
      if (where == SegmentPositions::face_ends && N != 2) continue;
      const int n = 5;
      auto net = chain(n, N, where);
      const double M = 7.0;
      net.add_load(n, 0.0, 0.0, M);
      const auto u = net.solve();
      // One row of depth 2r: I = ℓ(2r)³/12, I_eff = I · lattice_bending_factor(1, N); each face of
      // length 2r turns by M·2r/(k_n I_eff) (refs §4.3).
      const double I_eff = ell * std::pow(2 * r, 3) / 12.0 * ref::lattice_bending_factor(1, N, where);
      CHECK_THAT(u[3 * n + 2], WithinRel(n * M * 2 * r / (kn * I_eff), 1e-10));
      CHECK_THAT(u[3 * n], WithinAbs(0.0, 1e-12));
    }
  }
}

TEST_CASE("Lattice: uniform strain patches give C11 = kn, C12 = 0, C66 = ks/2 with rigid-body rotations (refs 4.3)",
          "[lattice_beam]") {
  // A 5 × 4 block; the boundary elements follow an affine field and its rigid rotation (a boundary
  // element lacks a face, so left free it would turn under shear), the 6 interior elements are free.
  const int nx = 5, ny = 4;
  struct Field {
    double exx, eyy, uy_dx, ux_dy;  // u_x = exx x + ux_dy y, u_y = uy_dx x + eyy y
  };
  const double g = 1e-4;
  for (const Field f : {Field{g, 0, 0, 0}, Field{0, g, 0, 0}, Field{0, 0, g / 2, g / 2}, Field{0, 0, 0, g},
                        Field{g, -g / 3, g / 4, 0}}) {
    RigidSpringNetwork net;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) net.add_body(2 * r * i, 2 * r * j);
    int x_faces = 0, y_faces = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (i + 1 < nx) ref::add_bonded_face(net, j * nx + i, j * nx + i + 1, r, ell, kn, ks, 3, SegmentPositions::centres), ++x_faces;
        if (j + 1 < ny) ref::add_bonded_face(net, j * nx + i, (j + 1) * nx + i, r, ell, kn, ks, 3, SegmentPositions::centres), ++y_faces;
      }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (i == 0 || j == 0 || i == nx - 1 || j == ny - 1) {
          const double x = 2 * r * i, y = 2 * r * j;
          net.prescribe(j * nx + i, 0, f.exx * x + f.ux_dy * y);
          net.prescribe(j * nx + i, 1, f.uy_dx * x + f.eyy * y);
          net.prescribe(j * nx + i, 2, 0.5 * (f.uy_dx - f.ux_dy));
        }
    const auto u = net.solve();
    const double gamma = f.uy_dx + f.ux_dy, omega = 0.5 * (f.uy_dx - f.ux_dy);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int b = j * nx + i;
        const double x = 2 * r * i, y = 2 * r * j;
        CHECK_THAT(u[3 * b], WithinAbs(f.exx * x + f.ux_dy * y, 1e-12));
        CHECK_THAT(u[3 * b + 1], WithinAbs(f.uy_dx * x + f.eyy * y, 1e-12));
        CHECK_THAT(u[3 * b + 2], WithinAbs(omega, 1e-12));  // elements turn with the rigid-body rotation
      }
    // A face's springs, of total stiffness k_n ℓ and k_s ℓ, stretch by 2r ε_n and slip by 2r·γ/2, so it
    // stores 4r²ℓ [½k_n ε_n² + ⅛k_s γ²]; an element owns one x- and one y-face, hence per unit volume
    // ½k_n(ε_xx² + ε_yy²) + ¼k_s γ² = ½C11ε_xx² + ½C22ε_yy² + C12ε_xxε_yy + ½C66γ² with C66 = k_s/2.
    const double V = 4 * r * r * ell;
    const double expected = x_faces * V * (0.5 * kn * f.exx * f.exx + 0.125 * ks * gamma * gamma) +
                            y_faces * V * (0.5 * kn * f.eyy * f.eyy + 0.125 * ks * gamma * gamma);
    CHECK_THAT(net.energy(u), WithinRel(expected, 1e-10));
  }
}

TEST_CASE("Lattice: the stiffness matrix is symmetric (Maxwell-Betti reciprocity)", "[lattice_beam]") {
  auto make = [] {
    RigidSpringNetwork net;
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) net.add_body(2 * r * i, 2 * r * j);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) {
        if (i + 1 < 4) ref::add_bonded_face(net, j * 4 + i, j * 4 + i + 1, r, ell, kn, ks, 4, SegmentPositions::centres);
        if (j + 1 < 3) ref::add_bonded_face(net, j * 4 + i, (j + 1) * 4 + i, r, ell, kn, ks, 4, SegmentPositions::centres);
      }
    for (int c = 0; c < 3; ++c) net.prescribe(0, c, 0.0);
    net.add_spring(RigidSpringNetwork::ground, 3, 4 * r * 3, -r, 0.6, 0.8, 5e7);  // an oblique contact
    return net;
  };
  auto a = make(), b = make();
  a.add_load(11, 0.0, 1.0, 0.0);  // a force at body 11 → θ at body 5
  b.add_load(5, 0.0, 0.0, 1.0);   // a torque at body 5 → u_y at body 11
  CHECK_THAT(a.solve()[3 * 5 + 2], WithinRel(b.solve()[3 * 11 + 1], 1e-9));
}

TEST_CASE("Lattice: the M-D beam, frictionless, against beam theory and the first-crack estimate", "[lattice_beam]") {
  const ref::BeamSection prism{0.040, 0.040, 0.100};
  // Computed by this solver (regression values): P/δ in kN/mm and the first crack over P_max.
  struct Row {
    int rows;
    double stiffness_kN_mm, first_crack_ratio;
  };
  for (const Row row : {Row{2, 27.897, 1.3247}, Row{6, 22.507, 1.0332}, Row{10, 21.474, 0.9824}}) {
    const auto out = ref::solve_lattice_beam(md_beam(row.rows, false), 5.6e6);
    CHECK_THAT(out.stiffness / 1e6, WithinRel(row.stiffness_kN_mm, 1e-4));
    CHECK_THAT(out.first_crack_load / ref::flexural_peak_load(prism, 5.6e6), WithinRel(row.first_crack_ratio, 1e-4));
    CHECK(out.residual < 1e-12);
    // The first link to break is the outermost bottom spring of the mid-span face (x = 0, y = r/N).
    CHECK_THAT(out.max_tension_x, WithinAbs(0.0, 1e-12));
    CHECK_THAT(out.max_tension_y, WithinRel(0.020 / row.rows / 5, 1e-9));
    CHECK(out.max_contact_tension < 0.0);  // every disk contact stays in compression
    // Vertical supports: the support core settles by P/(2 k_c) exactly.
    CHECK_THAT(out.support_settlement, WithinRel(1.0 / (2 * 172e6), 1e-9));
  }
  // 6 × 24 (independent): the first crack meets refs §4.4's beam-theory estimate 1 + 1/(n_h N).
  CHECK_THAT(ref::solve_lattice_beam(md_beam(6, false), 5.6e6).first_crack_load / ref::flexural_peak_load(prism, 5.6e6),
             WithinRel(ref::lattice_first_crack_ratio(6, 5, SegmentPositions::centres), 1e-3));
}

TEST_CASE("Lattice: with sticking friction the contacts would need |Q|/P above tan 5 deg, so they slip", "[lattice_beam]") {
  for (int rows : {2, 6, 10}) {
    const auto out = ref::solve_lattice_beam(md_beam(rows, true));
    CHECK(out.max_contact_friction > std::tan(5.0 * M_PI / 180.0));
  }
}

TEST_CASE("Lattice: bad input fails", "[lattice_beam]") {
  auto m = md_beam(2, false);
  m.columns = 7;
  CHECK_THROWS_AS(ref::solve_lattice_beam(m), std::invalid_argument);
  m = md_beam(2, false);
  m.where = SegmentPositions::face_ends;  // N = 5 at the face ends
  CHECK_THROWS_AS(ref::solve_lattice_beam(m), std::invalid_argument);
  RigidSpringNetwork net;
  net.add_body(0, 0);
  net.add_body(2 * r, 0);
  ref::add_bonded_face(net, 0, 1, r, ell, kn, ks, 2, SegmentPositions::centres);
  net.add_load(1, 1.0, 0.0, 0.0);
  CHECK_THROWS_AS(net.solve(), std::invalid_argument);  // free rigid-body motion: singular
  CHECK_THROWS_AS(net.add_spring(0, 0, 0, 0, 1, 0, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(net.add_spring(0, 1, 0, 0, 1, 1, 1.0), std::invalid_argument);  // not a unit vector
}

TEST_CASE("Lattice: the registry entries equal the direct calls", "[lattice_beam]") {
  const std::map<std::string, double> args{{"b", 0.04},   {"h", 0.04},  {"L", 0.1},     {"kn", kn},       {"ks", ks},
                                           {"n_h", 6},    {"n_l", 24},  {"N", 5},       {"ends", 0},      {"k_c", 172e6},
                                           {"k_t", 0.0},  {"k_pt", 0.0}, {"R_s", 0.005}, {"R_l", 0.005}};
  const auto direct = ref::solve_lattice_beam(md_beam(6, false), 5.6e6);
  CHECK(ref::evaluate("beam.lattice_exact_stiffness", args) == direct.stiffness);
  auto with_strength = args;
  with_strength["sigma_t"] = 5.6e6;
  CHECK(ref::evaluate("beam.lattice_exact_first_crack_load", with_strength) == direct.first_crack_load);
  auto odd = args;
  odd["n_l"] = 23;
  CHECK_THROWS_AS(ref::evaluate("beam.lattice_exact_stiffness", odd), std::invalid_argument);
}

TEST_CASE("Lattice: with N = 1 the lattice has a zero-energy mode (alternating rotations)", "[lattice_beam]") {
  // One spring per face has no moment lever, and the shear spring sees r(θ₁ + θ₂): elements turning
  // by ±θ in a checkerboard strain nothing. The static problem is singular.
  auto m = md_beam(2, false);
  m.segments = 1;
  CHECK_THROWS_AS(ref::solve_lattice_beam(m), std::invalid_argument);
  m.segments = 2;
  CHECK_NOTHROW(ref::solve_lattice_beam(m));
}

TEST_CASE("Lattice: supports in a groove lift off their outer core under load (no-tension reference)", "[lattice_beam]") {
  // 4 × 16 and 8 × 32 (r = 5, 2.5 mm): x = ±50 mm lies between two bottom cores, so each support
  // touches two cores. Frictionless and linear, the outer contact of each support pulls and the beam
  // comes out too stiff; the no-tension solve opens it (the DEM carries 0 N there). Then each support
  // carries P/2 through its inner contact alone, inclined by asin(r/(r + R)) to the vertical, and
  // the load disk's two contacts P/2 each likewise (statics, hand): F = (P/2)/cos.
  struct Row {
    int rows;
    double excess_min, excess_max;  // linear/no-tension − 1, measured 0.45 % and 0.53 %
  };
  for (const Row row : {Row{4, 0.004, 0.005}, Row{8, 0.005, 0.006}}) {
    auto m = md_beam(row.rows, false);
    m.no_tension = false;
    const auto linear = ref::solve_lattice_beam(m);
    REQUIRE(linear.contact_forces.size() == 6);  // left outer, left inner, right inner, right outer, load ×2
    CHECK(linear.contact_forces[0] > 0.02);      // the outer contacts pull
    CHECK(linear.contact_forces[3] > 0.02);
    m.no_tension = true;
    const auto out = ref::solve_lattice_beam(m);
    CHECK(out.open_contacts >= 1);               // the second outer one then carries 0 (degenerate)
    CHECK(out.max_contact_tension < 1e-12);
    CHECK(std::abs(out.contact_forces[0]) < 1e-12);
    CHECK(std::abs(out.contact_forces[3]) < 1e-12);
    const double r_e = 0.020 / row.rows, R = 0.005;
    const double support = 0.5 / std::sqrt(1.0 - std::pow(r_e / (r_e + R), 2));  // inner core: dx = r_e
    const double load = 0.5 / std::sqrt(1.0 - std::pow(r_e / (r_e + R), 2));
    CHECK_THAT(-out.contact_forces[1], WithinRel(support, 1e-9));
    CHECK_THAT(-out.contact_forces[2], WithinRel(support, 1e-9));
    CHECK_THAT(-out.contact_forces[4], WithinRel(load, 1e-9));
    CHECK(out.residual < 1e-12);
    const double excess = linear.stiffness / out.stiffness - 1.0;
    CHECK(excess > row.excess_min);
    CHECK(excess < row.excess_max);
    // With sticking friction no contact pulls: the no-tension answer is the linear one.
    auto f = md_beam(row.rows, true);
    f.no_tension = false;
    const double linear_friction = ref::solve_lattice_beam(f).stiffness;
    f.no_tension = true;
    CHECK(ref::solve_lattice_beam(f).stiffness == linear_friction);
  }
}
