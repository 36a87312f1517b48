// Matsui & Nishimura's face law (docs/model.md §2, M1–M16) at the level of one contact: segment positions,
// the tension cut-off, the Mohr–Coulomb limit, healing, the sign of the moment, exact against
// linearised increments, and frame objectivity under a rigid rotation of a bonded pair.
//
// Axes (face_contact.hpp): n from element 1 towards element 2, t = n rotated by +90°, the segment at ξ
// sits at r1 n + a ξ t from the centre of element 1. Turning element 1 by a small angle θ about its
// centre moves that point by θ(−aξ, r1) in (n, t), so the approach there is −aξθ and the slip r1θ;
// for a finite θ the point goes to (r1 cos θ − aξ sin θ, r1 sin θ + aξ cos θ), giving
//   u(ξ) = −r1(1 − cos θ) − aξ sin θ,   v(ξ) = r1 sin θ + aξ(cos θ − 1)        (M2 with ξ → −ξ)
// These hand-derived forms are the expectations below.
#include <catch2/catch.hpp>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "dem/contact/face_contact.hpp"
#include "dem/core/vec2.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double tol = 1e-12;
constexpr double kn = 1e6, ks = 4e5;    // discrete springs per segment [N/m]
constexpr double a = 0.01;              // half face length [m]
constexpr double area = 2.0 * a * 0.1;  // A = 2 a l with l = 0.1 m (M1)
constexpr double inv_dt = 1e4;

dem::FaceConstants constants(int n, double eta_n = 0.0, double eta_s = 0.0) {
  dem::FaceConstants c;
  c.kn = kn;
  c.ks = ks;
  c.eta_n = eta_n;
  c.eta_s = eta_s;
  c.half_length = a;
  c.segment_area = area / n;
  return c;
}

dem::FaceLaw face_law(int n, dem::SegmentPositions pos = dem::SegmentPositions::centres) {
  dem::FaceLaw l;
  l.segments = n;
  l.positions = pos;
  l.tensile_strength = 1e15;  // never breaks unless a test says so
  l.cohesion = 1e15;          // never slides unless a test says so
  l.tan_phi = 0.5;
  return l;
}

dem::FaceKinematics normal_step(double du, double r1 = a, double r2 = a) {
  dem::FaceKinematics k;
  k.du_projected = du;
  k.du_exact = du;
  k.r1 = r1;
  k.r2 = r2;
  return k;
}

}  // namespace

TEST_CASE("face: segment positions xi_i = (2i - 1 - N)/N (M13.1) and the face ends (M13.2)", "[face]") {
  using dem::SegmentPositions;
  // written out by hand from (M13.1), i = 1..N
  const std::vector<std::vector<double>> expected = {
      {0.0}, {-0.5, 0.5}, {-2.0 / 3.0, 0.0, 2.0 / 3.0}, {-0.75, -0.25, 0.25, 0.75}, {-0.8, -0.4, 0.0, 0.4, 0.8}};
  for (int n = 1; n <= 5; ++n) {
    CAPTURE(n);
    for (int i = 0; i < n; ++i) {
      CAPTURE(i);
      CHECK_THAT(dem::segment_xi(SegmentPositions::centres, n, i),
                 WithinAbs(expected[static_cast<std::size_t>(n - 1)][static_cast<std::size_t>(i)], 1e-15));
    }
  }
  // (M13.2): ξ_i = 2i − 3, i = 1, 2
  CHECK(dem::segment_xi(SegmentPositions::ends, 2, 0) == -1.0);
  CHECK(dem::segment_xi(SegmentPositions::ends, 2, 1) == 1.0);
}

TEST_CASE("face: the compile-time table of xi_i holds exactly the values segment_xi computes at run time", "[face]") {
  using dem::SegmentPositions;
  // The law reads ξ_i from dem::kSegmentXi; results stay bit for bit only if every entry is the run-time
  // division's double (exact equality, both arrangements, N = 1..kMaxSegments).
  for (int p = 0; p < 2; ++p) {
    const auto pos = static_cast<SegmentPositions>(p);
    for (int n = 1; n <= dem::kMaxSegments; ++n) {
      volatile int n_at_run_time = n;  // keeps the division out of constant folding
      for (int i = 0; i < n; ++i) {
        CAPTURE(p, n, i);
        CHECK(dem::kSegmentXi.xi[p][n][i] == dem::segment_xi(pos, n_at_run_time, i));
      }
    }
  }
  CHECK(dem::kSegmentXi.xi[0][5][0] == -0.8);
  CHECK(dem::kSegmentXi.xi[1][2][0] == -1.0);
}

TEST_CASE("face: a segment breaks exactly when P_e < -sigma_t A/N and then carries nothing (M8, M9)", "[face]") {
  const int n = GENERATE(1, 2, 3, 4, 5);
  CAPTURE(n);
  auto law = face_law(n);
  law.tensile_strength = 2e6;           // σ_t [Pa]
  const double limit = 2e6 * area / n;  // σ_t A/N [N]
  const double d_crit = limit / kn;     // opening at which P_e = −σ_t A/N
  const auto c = constants(n);
  auto k = normal_step(0.0);
  k.dv_translation = 1e-6;  // a shear increment, so that an intact link also carries shear

  SECTION("just below the strength: intact") {
    dem::FaceHistory h;
    dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
    k.du_projected = -d_crit * (1.0 - 1e-9);
    const auto f = dem::face_contact_force(law, c, k, inv_dt, h);
    CHECK(f.links == n);
    CHECK(f.any_tensile);
    CHECK_THAT(f.p, WithinRel(-n * limit * (1.0 - 1e-9), 1e-9));
    CHECK_THAT(f.q, WithinRel(n * ks * 1e-6, 1e-9));
    for (int i = 0; i < n; ++i) CHECK(h.seg[static_cast<std::size_t>(i)].linked == 1);
  }
  SECTION("just above the strength: broken, no normal or shear force") {
    dem::FaceHistory h;
    dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
    k.du_projected = -d_crit * (1.0 + 1e-9);
    const auto f = dem::face_contact_force(law, c, k, inv_dt, h);
    CHECK(f.links == 0);
    CHECK(f.p == 0.0);
    CHECK(f.q == 0.0);
    CHECK(f.p_moment == 0.0);
    for (int i = 0; i < n; ++i) {
      CHECK(h.seg[static_cast<std::size_t>(i)].linked == 0);
      CHECK(h.seg[static_cast<std::size_t>(i)].intact == 0);
      CHECK(h.seg[static_cast<std::size_t>(i)].pe == 0.0);
      CHECK(h.seg[static_cast<std::size_t>(i)].qe == 0.0);
    }
  }
}

TEST_CASE("face: with a rotation only the segments beyond the strength break", "[face]") {
  // N = 4, ξ = −0.75, −0.25, 0.25, 0.75. Opening d_crit plus a turn of element 1 with aΔθ = 0.1 d_crit:
  // u_i = −d_crit(1 + 0.1 ξ_i) → the two segments with ξ > 0 break, the two with ξ < 0 hold.
  const int n = 4;
  auto law = face_law(n);
  law.tensile_strength = 2e6;
  const double limit = 2e6 * area / n, d_crit = limit / kn;
  const auto c = constants(n);
  dem::FaceHistory h;
  dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
  auto k = normal_step(-d_crit);
  k.dphi1 = 0.1 * d_crit / a;
  const auto f = dem::face_contact_force(law, c, k, inv_dt, h);
  CHECK(f.links == 2);
  CHECK(h.seg[0].linked == 1);
  CHECK(h.seg[1].linked == 1);
  CHECK(h.seg[2].linked == 0);
  CHECK(h.seg[3].linked == 0);
  // P = −limit[(1 − 0.075) + (1 − 0.025)] = −1.9 limit;  Σ aξP = a limit(0.75·0.925 + 0.25·0.975)
  CHECK_THAT(f.p, WithinRel(-1.9 * limit, 1e-12));
  CHECK_THAT(f.p_moment, WithinRel(0.9375 * a * limit, 1e-12));
}

TEST_CASE("face: the shear force per segment is capped at (c + sigma tan phi) A/N, without dashpot (M10, M11)",
          "[face]") {
  // N = 2 (ξ = ∓0.5), c = 2 kPa → c A/N = 2 N; tan φ = 0.5; η_n = 100, η_s = 50 N·s/m, 1/Δt = 1e4.
  const int n = 2;
  auto law = face_law(n);
  law.cohesion = 2e3;
  law.tan_phi = 0.5;
  const auto c = constants(n, 100.0, 50.0);
  dem::FaceHistory h;
  dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
  // Step 1: approach 10 µm and a turn aΔθ = 5 µm: u = 10 µm − ξ·5 µm → 12.5 µm, 7.5 µm → P_e = 12.5, 7.5 N.
  // Limits 2 + 0.5 P_e = 8.25 N and 5.75 N; the trial shear 4e5·1e-4 = 40 N is far beyond → sliding.
  auto k = normal_step(1e-5);
  k.dphi1 = 5e-6 / a;
  k.dv_translation = 1e-4 - a * k.dphi1;  // so that Δv = Δv̄ + r1Δφ1 = 1e-4 with r1 = a
  auto f = dem::face_contact_force(law, c, k, inv_dt, h);
  CHECK_THAT(h.seg[0].pe, WithinRel(12.5, tol));
  CHECK_THAT(h.seg[1].pe, WithinRel(7.5, tol));
  CHECK_THAT(h.seg[0].qe, WithinRel(8.25, tol));
  CHECK_THAT(h.seg[1].qe, WithinRel(5.75, tol));
  CHECK_THAT(f.q, WithinRel(14.0, tol));  // no Q_d at the limit
  // P = 20 N + dashpots η_n Δu_i/Δt = 100·(12.5 + 7.5)e-6·1e4 = 20 N
  CHECK_THAT(f.p, WithinRel(40.0, tol));
  // Step 2: back by 1 µm in shear, no normal motion: Q_e = 7.85, 5.35 (below the limits: sticks),
  // Q_d = 50·(−1e-6)·1e4 = −0.5 per segment → Q = 13.2 − 1.0 = 12.2 N
  k = normal_step(0.0);
  k.dv_translation = -1e-6 - a * 0.0;
  f = dem::face_contact_force(law, c, k, inv_dt, h);
  CHECK_THAT(h.seg[0].qe, WithinRel(7.85, tol));
  CHECK_THAT(h.seg[1].qe, WithinRel(5.35, tol));
  CHECK_THAT(f.q, WithinRel(12.2, tol));
  // The sign of the cap follows the shear: a large negative increment caps at −8.25, −5.75
  k.dv_translation = -1e-3;
  f = dem::face_contact_force(law, c, k, inv_dt, h);
  CHECK_THAT(f.q, WithinRel(-14.0, tol));
}

TEST_CASE("face: tau_y < 0 (tension beyond c/tan phi) leaves no shear force (M11)", "[face]") {
  // N = 2 without rotation, c A/N = 2 N, tan φ = 0.5 → τ_y A/N = 2 + 0.5 P_e < 0 for P_e < −4 N.
  const int n = 2;
  auto law = face_law(n);
  law.cohesion = 2e3;
  law.tan_phi = 0.5;
  const auto c = constants(n, 0.0, 50.0);
  dem::FaceHistory h;
  dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
  auto k = normal_step(-1e-5);  // P_e = −10 N per segment, intact (σ_t huge)
  k.dv_translation = 1e-6;      // trial Q_e = 0.4 N, Q_d = 0.5 N
  auto f = dem::face_contact_force(law, c, k, inv_dt, h);
  CHECK(f.links == 2);
  CHECK_THAT(f.p, WithinRel(-20.0, tol));
  CHECK(f.q == 0.0);
  CHECK(h.seg[0].qe == 0.0);
  // Back to P_e = −3 N: τ_y A/N = 0.5 N → Q_e capped at 0.5 per segment (trial 0 + 0.8: the
  // shear was zeroed in the step before); Q_d dropped at the cap
  k = normal_step(7e-6);
  k.dv_translation = 2e-6;
  f = dem::face_contact_force(law, c, k, inv_dt, h);
  CHECK_THAT(h.seg[0].pe, WithinRel(-3.0, 1e-9));
  CHECK_THAT(f.q, WithinRel(1.0, 1e-9));
}

TEST_CASE("face: healing decides whether a re-formed link regains tension and cohesion", "[face]") {
  // N = 1, σ_t = 2 MPa → σ_t A = 4000 N; c = 2 kPa → c A = 4 N; tan φ = 0.5.
  const bool healing = GENERATE(false, true);
  CAPTURE(healing);
  auto law = face_law(1);
  law.tensile_strength = 2e6;
  law.cohesion = 2e3;
  law.tan_phi = 0.5;
  law.healing = healing;
  const auto c = constants(1);
  const double strength = 4000.0, d_crit = strength / kn;
  dem::FaceHistory h;
  dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
  // break it
  auto f = dem::face_contact_force(law, c, normal_step(-2.0 * d_crit), inv_dt, h);
  REQUIRE(f.links == 0);
  // pushed back: u = −2 d_crit + 2 d_crit + 1 µm ≥ 0 → re-forms with P_e = K_n u = 1 N
  f = dem::face_contact_force(law, c, normal_step(2.0 * d_crit + 1e-6), inv_dt, h);
  REQUIRE(f.links == 1);
  CHECK_THAT(f.p, WithinRel(1.0, 1e-9));
  // shear beyond any limit: the cap is τ_y A = c A + P_e tan φ = 4.5 N with healing, 0.5 N without
  auto k = normal_step(0.0);
  k.dv_translation = 1e-3;
  f = dem::face_contact_force(law, c, k, inv_dt, h);
  CHECK_THAT(f.q, WithinRel(healing ? 4.5 : 0.5, 1e-9));
  CHECK(f.any_tensile == healing);
  // a pull to P_e = −σ_t A/2: holds with healing, breaks (σ_t = 0) without
  f = dem::face_contact_force(law, c, normal_step(-1e-6 - 0.5 * d_crit), inv_dt, h);
  CHECK(f.links == (healing ? 1 : 0));
  if (healing)
    CHECK_THAT(f.p, WithinRel(-0.5 * strength, 1e-9));
  else
    CHECK(f.p == 0.0);
}

TEST_CASE("face: an unbonded contact starts without tension and cohesion unless healing", "[face]") {
  const bool healing = GENERATE(false, true);
  auto law = face_law(2);
  law.tensile_strength = 2e6;
  law.healing = healing;
  const auto c = constants(2);
  dem::FaceHistory h;
  dem::start_face(law, c, 0.0, false, /*geometric=*/false, h);
  const auto f = dem::face_contact_force(law, c, normal_step(-1e-6), inv_dt, h);  // P_e = −1 N
  CHECK(f.links == (healing ? 2 : 0));
}

TEST_CASE("face: start_face links an unbonded segment iff u0 >= 0, with P_e = K_n u0", "[face]") {
  auto law = face_law(3);
  const auto c = constants(3);
  dem::FaceHistory h;
  dem::start_face(law, c, 2e-6, false, /*geometric=*/false, h);
  for (int i = 0; i < 3; ++i) {
    CHECK(h.seg[static_cast<std::size_t>(i)].linked == 1);
    CHECK_THAT(h.seg[static_cast<std::size_t>(i)].pe, WithinRel(2.0, tol));
  }
  dem::start_face(law, c, -2e-6, false, /*geometric=*/false, h);
  for (int i = 0; i < 3; ++i) CHECK(h.seg[static_cast<std::size_t>(i)].linked == 0);
  // it links once the approach closes the gap: 1 µm more → still apart, 3 µm more → u = 1 µm
  auto f = dem::face_contact_force(law, c, normal_step(1e-6), inv_dt, h);
  CHECK(f.links == 0);
  f = dem::face_contact_force(law, c, normal_step(2e-6), inv_dt, h);
  CHECK(f.links == 3);
  CHECK_THAT(f.p, WithinRel(3 * 1.0, 1e-9));
}

TEST_CASE("face: a bonded face starts linked and intact, also a hair apart (P_e = K_n u0 < 0)", "[face]") {
  auto law = face_law(2);
  law.tensile_strength = 2e6;  // σ_t A/N = 2000 N
  const auto c = constants(2);
  dem::FaceHistory h;
  dem::start_face(law, c, -2e-6, true, /*geometric=*/false, h);
  for (int i = 0; i < 2; ++i) {
    CHECK(h.seg[static_cast<std::size_t>(i)].linked == 1);
    CHECK(h.seg[static_cast<std::size_t>(i)].intact == 1);
    CHECK_THAT(h.seg[static_cast<std::size_t>(i)].pe, WithinRel(-2.0, tol));
  }
  const auto f = dem::face_contact_force(law, c, normal_step(0.0), inv_dt, h);
  CHECK(f.links == 2);
  CHECK_THAT(f.p, WithinRel(-4.0, tol));
}

TEST_CASE("face: a turn of element 1 gives P_e(i) = -K_n a xi_i dtheta and a restoring moment", "[face]") {
  // Linearised normal law (M15.1): Δu(ξ) = Δū − aξ(Δθ1 − Δθ2) in our axes. With Δū = 0:
  // P_e(i) = −K_n a ξ_i Δθ;  Σ aξ_i P(i) = −K_n a² Δθ Σξ_i²;  Σξ_i² = (N² − 1)/(3N) for centres, 2 for ends.
  // Shear (M15.2): Δv = r1Δθ per segment → Q = N K_s r1 Δθ; M1 = −r1 Q + Σ aξP opposes the turn.
  struct Layout {
    dem::SegmentPositions pos;
    int n;
    double sum_xi2;
  };
  const auto lay =
      GENERATE(Layout{dem::SegmentPositions::centres, 1, 0.0}, Layout{dem::SegmentPositions::centres, 2, 0.5},
               Layout{dem::SegmentPositions::centres, 3, 8.0 / 9.0}, Layout{dem::SegmentPositions::centres, 4, 1.25},
               Layout{dem::SegmentPositions::centres, 5, 1.6}, Layout{dem::SegmentPositions::ends, 2, 2.0});
  CAPTURE(lay.n, static_cast<int>(lay.pos));
  CHECK_THAT(lay.sum_xi2,
             WithinAbs((lay.pos == dem::SegmentPositions::ends) ? 2.0 : (lay.n * lay.n - 1.0) / (3.0 * lay.n), 1e-15));
  const double dth = GENERATE(1e-4, -3e-4);
  auto law = face_law(lay.n, lay.pos);
  const auto c = constants(lay.n);
  const double r1 = 0.012;
  dem::FaceHistory h;
  dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
  auto k = normal_step(0.0, r1, a);
  k.dphi1 = dth;
  const auto f = dem::face_contact_force(law, c, k, inv_dt, h);
  for (int i = 0; i < lay.n; ++i) {
    const double xi = dem::segment_xi(lay.pos, lay.n, i);
    CHECK_THAT(h.seg[static_cast<std::size_t>(i)].pe, WithinAbs(-kn * a * xi * dth, 1e-12 * kn * a * std::abs(dth)));
  }
  CHECK_THAT(f.p, WithinAbs(0.0, 1e-12 * kn * a * std::abs(dth)));
  CHECK_THAT(f.p_moment, WithinAbs(-kn * a * a * dth * lay.sum_xi2, 1e-12 * kn * a * a * std::abs(dth)));
  CHECK_THAT(f.q, WithinRel(lay.n * ks * r1 * dth, 1e-12));
  const double m1 = -r1 * f.q + f.p_moment;
  CHECK(m1 * dth < 0.0);  // restoring
}

namespace {

/// Each segment's springs hold the displacement of element 1 turned by θ1 and element 2 by θ2, centres
/// fixed (M2.1, and M2.2 without v̄; element 2's point at (−r2, aξ) from its centre turns the other way):
///   u(ξ) = −r1(1 − cos θ1) − r2(1 − cos θ2) − aξ(sin θ1 − sin θ2)
///   v(ξ) =  r1 sin θ1 + r2 sin θ2 + aξ(cos θ1 − cos θ2)
void check_finite_rotation(const dem::FaceHistory& h, dem::SegmentPositions positions, int n, double r1, double r2,
                           double t1, double t2) {
  for (int i = 0; i < n; ++i) {
    const double xi = dem::segment_xi(positions, n, i);
    const double u = -r1 * (1 - std::cos(t1)) - r2 * (1 - std::cos(t2)) - a * xi * (std::sin(t1) - std::sin(t2));
    const double v = r1 * std::sin(t1) + r2 * std::sin(t2) + a * xi * (std::cos(t1) - std::cos(t2));
    CAPTURE(i, xi);
    CHECK_THAT(h.seg[static_cast<std::size_t>(i)].pe, WithinAbs(kn * u, 1e-12 * kn * a));
    CHECK_THAT(h.seg[static_cast<std::size_t>(i)].qe, WithinAbs(ks * v, 1e-12 * ks * a));
  }
}

}  // namespace

TEST_CASE("face: the exact increments follow the finite-rotation displacements (M2, M3) path-independently", "[face]") {
  // Element 1 turns by θ in m unequal steps, element 2 turns by −θ/2, the centres stay (frame fixed);
  // expected: check_finite_rotation above.
  const int n = 3;
  auto law = face_law(n);
  law.normal = dem::NormalIncrement::exact;
  law.tangential = dem::TangentialIncrement::exact;
  const auto c = constants(n);
  const double r1 = 0.012, r2 = a, theta = 0.7;
  dem::FaceHistory h;
  dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
  const std::vector<double> parts = {0.1, 0.3, 0.05, 0.25, 0.2, 0.1};  // sums to 1
  for (double p : parts) {
    auto k = normal_step(0.0, r1, r2);
    k.dphi1 = p * theta;
    k.dphi2 = -0.5 * p * theta;
    dem::face_contact_force(law, c, k, inv_dt, h);
  }
  check_finite_rotation(h, law.positions, n, r1, r2, theta, -0.5 * theta);
}

TEST_CASE("face: exact increments tend to the linearised ones as the rotation goes to zero, error O(theta^2)",
          "[face]") {
  // Same motion as above for the exact law (M3.1, M3.2) and the linearised one (M15.1, M15.2), in 10
  // equal steps. The difference of the spring displacements is second order in θ:
  //   u_exact − u_lin = −r1θ1²/2 − r2θ2²/2 + O(θ³),  v_exact − v_lin = −aξ(θ1² − θ2²)/2 + O(θ³).
  const int n = 2;
  const double r1 = 0.012, r2 = a;
  auto run = [&](bool exact, double theta, std::vector<double>& u, std::vector<double>& v) {
    auto law = face_law(n, dem::SegmentPositions::ends);
    law.normal = exact ? dem::NormalIncrement::exact : dem::NormalIncrement::linearised;
    law.tangential = exact ? dem::TangentialIncrement::exact : dem::TangentialIncrement::linearised;
    const auto c = constants(n);
    dem::FaceHistory h;
    dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
    for (int s = 0; s < 10; ++s) {
      auto k = normal_step(0.0, r1, r2);
      k.dphi1 = theta / 10;
      k.dphi2 = -0.5 * theta / 10;
      dem::face_contact_force(law, c, k, inv_dt, h);
    }
    u = {h.seg[0].pe / kn, h.seg[1].pe / kn};
    v = {h.seg[0].qe / ks, h.seg[1].qe / ks};
  };
  std::vector<double> errors;
  for (double theta : {1e-2, 1e-3, 1e-4}) {
    std::vector<double> ue, ve, ul, vl;
    run(true, theta, ue, ve);
    run(false, theta, ul, vl);
    double err = 0.0;
    for (int i = 0; i < n; ++i) {
      const double xi = dem::segment_xi(dem::SegmentPositions::ends, n, i);
      const double t1 = theta, t2 = -0.5 * theta;
      CAPTURE(theta, i);
      // linearised values, by hand: u = −aξ(θ1 − θ2), v = r1θ1 + r2θ2
      CHECK_THAT(ul[static_cast<std::size_t>(i)], WithinAbs(-a * xi * (t1 - t2), 1e-12 * a * theta));
      CHECK_THAT(vl[static_cast<std::size_t>(i)], WithinAbs(r1 * t1 + r2 * t2, 1e-12 * a * theta));
      // leading term of the difference
      CHECK_THAT(ue[static_cast<std::size_t>(i)] - ul[static_cast<std::size_t>(i)],
                 WithinAbs(-0.5 * (r1 * t1 * t1 + r2 * t2 * t2), 0.3 * a * theta * theta * theta + 1e-15));
      CHECK_THAT(ve[static_cast<std::size_t>(i)] - vl[static_cast<std::size_t>(i)],
                 WithinAbs(-0.5 * a * xi * (t1 * t1 - t2 * t2), 0.3 * a * theta * theta * theta + 1e-15));
      err = std::max({err, std::abs(ue[static_cast<std::size_t>(i)] - ul[static_cast<std::size_t>(i)]),
                      std::abs(ve[static_cast<std::size_t>(i)] - vl[static_cast<std::size_t>(i)])});
    }
    errors.push_back(err);
  }
  // observed order 2 per decade of θ
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log10(errors[k - 1] / errors[k]);
    CAPTURE(k, order);
    CHECK(order > 1.95);
    CHECK(order < 2.05);
  }
}

TEST_CASE("face: the literal reading of (M3.2) counts the rotation twice, Hisatake's (M16) ignores translation",
          "[face]") {
  const int n = 2;
  const double r1 = 0.012, r2 = a, t1 = 0.2, t2 = -0.1;
  auto shear = [&](dem::TangentialIncrement tan, double dv_frame) {
    auto law = face_law(n);
    law.normal = dem::NormalIncrement::exact;
    law.tangential = tan;
    const auto c = constants(n);
    dem::FaceHistory h;
    dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
    auto k = normal_step(0.0, r1, r2);
    k.dphi1 = t1;
    k.dphi2 = t2;
    k.dv_frame = dv_frame;
    k.dv_translation = dv_frame;
    dem::face_contact_force(law, c, k, inv_dt, h);
    return std::vector<double>{h.seg[0].qe / ks, h.seg[1].qe / ks};
  };
  const auto exact = shear(dem::TangentialIncrement::exact, 3e-4);
  const auto literal = shear(dem::TangentialIncrement::literal, 3e-4);
  const auto hisatake = shear(dem::TangentialIncrement::hisatake, 3e-4);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK_THAT(literal[i] - exact[i], WithinAbs(r1 * t1 + r2 * t2, 1e-15));  // the extra r θ of (M2.4)
    CHECK_THAT(exact[i] - hisatake[i], WithinAbs(3e-4, 1e-15));              // the translation v̄
  }
}

TEST_CASE("face: Hisatake's increments (M16) summed over a finite path give M2.2 minus the translation v-bar",
          "[face]") {
  // The paper: Hisatake's displacements are M2.1 − rξ² and M2.2 − v̄. The tangential half, over a
  // path of unequal steps that both slides (v₁ − v₂ grows by 2e-4 m) and turns (θ1 = 0.6, θ2 = −0.25),
  // the springs hold check_finite_rotation's v(ξ): M2.2 without v̄, no translation at all.
  // The −rξ² of u does not change in time, so it has no increment: M16's law keeps M3.1 for the normal,
  // u = M2.1 from the start of contact (the constant would only offset the springs' start).
  const int n = 3;
  auto law = face_law(n);
  law.normal = dem::NormalIncrement::exact;
  law.tangential = dem::TangentialIncrement::hisatake;
  const auto c = constants(n);
  const double r1 = 0.012, r2 = a, t1 = 0.6, t2 = -0.25, slide = 2e-4;
  dem::FaceHistory h;
  dem::start_face(law, c, 0.0, true, /*geometric=*/false, h);
  for (double p : {0.2, 0.05, 0.3, 0.15, 0.1, 0.2}) {  // sums to 1
    auto k = normal_step(0.0, r1, r2);
    k.dphi1 = p * t1;
    k.dphi2 = p * t2;
    k.dv_translation = p * slide;
    k.dv_frame = p * slide;
    dem::face_contact_force(law, c, k, inv_dt, h);
  }
  check_finite_rotation(h, law.positions, n, r1, r2, t1, t2);
}

// ---- frame objectivity (docs/model.md §2: "a rigid-body rotation of a bonded pair produces no force") ----

namespace {

/// Kinematics of one step of two centres moving from (c1o, c2o) to (c1, c2), written independently
/// of the simulation: normal and tangent from the new line of centres.
dem::FaceKinematics pair_kinematics(dem::Vec2 c1o, dem::Vec2 c2o, dem::Vec2 c1, dem::Vec2 c2, double dphi1,
                                    double dphi2, double r1, double r2) {
  const dem::Vec2 d_old = c2o - c1o, d_new = c2 - c1;
  const dem::Vec2 nrm = d_new * (1.0 / dem::norm(d_new)), t = dem::perp(nrm);
  const dem::Vec2 rel = (c1 - c1o) - (c2 - c2o);
  dem::FaceKinematics k;
  k.du_projected = dem::dot(rel, nrm);
  k.dv_translation = dem::dot(rel, t);
  k.du_exact = dem::norm(d_old) - dem::norm(d_new);
  k.dbeta = std::atan2(dem::cross(d_old, d_new), dem::dot(d_old, d_new));
  k.dphi1 = dphi1;
  k.dphi2 = dphi2;
  k.r1 = r1;
  k.r2 = r2;
  return k;
}

}  // namespace

TEST_CASE("face: a rigid rotation of a bonded pair by 90 deg leaves the exact law's forces unchanged",
          "[face][objectivity]") {
  // Pair turned about its midpoint in m equal steps Δ = (π/2)/m, both elements turning with it.
  const double preload = GENERATE(0.0, 1e-5);  // initial overlap δ [m]
  const int m = GENERATE(90, 900);
  const int n = 3;
  CAPTURE(preload, m);
  const double r1 = 0.012, r2 = a, dist = r1 + r2 - preload;
  auto law = face_law(n);
  law.normal = dem::NormalIncrement::exact;
  law.tangential = dem::TangentialIncrement::exact;
  const auto c = constants(n);
  dem::FaceHistory h;
  dem::start_face(law, c, preload, true, /*geometric=*/false, h);
  const double step = 0.5 * std::numbers::pi / m;
  auto centre = [&](double beta, double s) { return dem::Vec2{s * std::cos(beta), s * std::sin(beta)} * (0.5 * dist); };
  dem::FaceForce f;
  for (int k = 0; k < m; ++k) {
    const double bo = k * step, bn = (k + 1) * step;
    const auto kin = pair_kinematics(centre(bo, -1), centre(bo, 1), centre(bn, -1), centre(bn, 1), step, step, r1, r2);
    f = dem::face_contact_force(law, c, kin, inv_dt, h);
    REQUIRE_THAT(f.p, WithinAbs(n * kn * preload, 1e-12 * kn * a));
    REQUIRE_THAT(f.q, WithinAbs(0.0, 1e-12 * ks * a));
    REQUIRE_THAT(f.p_moment, WithinAbs(0.0, 1e-12 * kn * a * a));
  }
  CHECK_THAT(h.theta1, WithinAbs(0.0, 1e-12));
  CHECK_THAT(h.theta2, WithinAbs(0.0, 1e-12));
}

TEST_CASE("face: under the same rigid rotation the linearised law errs by second order per step",
          "[face][objectivity]") {
  // Per step, Δx1 − Δx2 = −D(n_new − n_old): Δū = −D(1 − cos Δ), Δv̄ = −D sin Δ, and (M15.2) adds
  // (r1 + r2)Δ: Δv = (r1 + r2 − D)Δ + D(Δ − sin Δ) = δΔ + D(Δ − sin Δ), with δ the overlap.
  // After m steps: P_e = K_n(δ − m D(1 − cos Δ)) and Q_e = K_s m(δΔ + D(Δ − sin Δ)) per segment.
  // Without preload both vanish like Δ as Δ → 0 for a fixed total angle (mDΔ²/2, mDΔ³/6);
  // a preloaded contact keeps a shear K_s δ Θ that does not vanish — K5's lever r_i, not r_i − δ/2.
  const double preload = GENERATE(0.0, 1e-5);
  const int m = GENERATE(90, 900);
  const int n = 2;
  CAPTURE(preload, m);
  const double r1 = 0.012, r2 = a, dist = r1 + r2 - preload;
  auto law = face_law(n);
  const auto c = constants(n);
  dem::FaceHistory h;
  dem::start_face(law, c, preload, true, /*geometric=*/false, h);
  const double step = 0.5 * std::numbers::pi / m;
  auto centre = [&](double beta, double s) { return dem::Vec2{s * std::cos(beta), s * std::sin(beta)} * (0.5 * dist); };
  for (int k = 0; k < m; ++k) {
    const double bo = k * step, bn = (k + 1) * step;
    dem::face_contact_force(
        law, c, pair_kinematics(centre(bo, -1), centre(bo, 1), centre(bn, -1), centre(bn, 1), step, step, r1, r2),
        inv_dt, h);
  }
  const double pe = kn * (preload - m * dist * (1 - std::cos(step)));
  const double qe = ks * m * (preload * step + dist * (step - std::sin(step)));
  CHECK_THAT(h.seg[0].pe, WithinRel(pe, 1e-6));
  CHECK_THAT(h.seg[1].pe, WithinRel(pe, 1e-6));
  CHECK_THAT(h.seg[0].qe, WithinRel(qe, 1e-6));
  if (preload == 0.0) {
    // second order per step: the whole 90° turn leaves an approach error of about D Θ Δ/2
    const double theta = 0.5 * std::numbers::pi;
    CHECK_THAT(h.seg[0].pe / kn, WithinRel(-dist * theta * step / 2, 1e-3));
  }
}

namespace {
bool same_bits(double x, double y) { return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y); }

// The face law's segment loop for N = 3, 4, 5 runs segments 0 … min(N, 4) − 1 in vector lanes when all of them
// are on the usual path (face_detail::segment_block); the generic loop (segments<0>) is the scalar law.
template <int N>
void check_lanes_against_scalar(const dem::face_detail::SegmentInputs& in, const dem::FaceHistory& h0, int& vector_path) {
  using namespace dem::face_detail;
  dem::FaceHistory hv = h0, hs = h0, hb = h0;
  SegmentSums rv, rs;
  segments<N>(in, N, hv, rv);
  segments<0>(in, N, hs, rs);
  V4d sums{0.0, 0.0, 0.0, 0.0};
  if (segment_block<N < 4 ? N : 4>(in, hb, sums)) ++vector_path;
  CHECK(same_bits(rv.p, rs.p));
  CHECK(same_bits(rv.q, rs.q));
  CHECK(same_bits(rv.moment, rs.moment));
  CHECK(rv.links == rs.links);
  CHECK((rv.any_intact != 0) == (rs.any_intact != 0));
  for (int i = 0; i < dem::kMaxSegments; ++i) {
    const auto& v = hv.seg[static_cast<std::size_t>(i)];
    const auto& s = hs.seg[static_cast<std::size_t>(i)];
    CAPTURE(i);
    CHECK(same_bits(v.u, s.u));
    CHECK(same_bits(v.pe, s.pe));
    CHECK(same_bits(v.qe, s.qe));
    CHECK(v.linked == s.linked);
    CHECK(v.intact == s.intact);
  }
}

template <int N>
int lanes_against_scalar_trials() {
  std::mt19937_64 rng(20261123 + N);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> pos(0.0, 1.0);
  int vector_path = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    dem::face_detail::SegmentInputs in{};
    in.xis = dem::kSegmentXi.xi[0][N];
    in.a = a;
    in.du0 = 1e-6 * unit(rng), in.du_xi = 1e-6 * unit(rng), in.dv0 = 1e-6 * unit(rng), in.dv_xi = 1e-6 * unit(rng);
    in.kn = kn, in.ks = ks, in.eta_n = 100.0 * pos(rng), in.eta_s = 50.0 * pos(rng), in.inv_dt = inv_dt;
    // every other trial strong (the usual path), the others near the strengths (breaks, sliding, τ_y < 0)
    const double strength = trial % 2 == 0 ? 1e6 : 3.0 * pos(rng);
    in.tension_intact = -strength, in.tension_broken = -0.0;
    in.cohesion_intact = trial % 2 == 0 ? 1e6 : 2.0 * pos(rng), in.cohesion_broken = 0.0;
    in.tan_phi = pos(rng);
    in.healing = trial % 3 == 0;
    dem::FaceHistory h;
    for (auto& s : h.seg) {
      s.u = 1e-6 * unit(rng);
      s.pe = 3.0 * unit(rng);
      s.qe = 3.0 * unit(rng);
      s.linked = (trial % 2 == 0 || pos(rng) < 0.9) ? 1 : 0;
      s.intact = (trial % 2 == 0 || pos(rng) < 0.8) ? 1 : 0;
      if (!s.linked) s.pe = s.qe = 0.0;
    }
    if (trial % 4 == 3) {  // weak, but segments 0..3 well inside their limits: the lanes go, segment 4 decides
      in.tan_phi = 0.5 + 0.5 * pos(rng);
      for (std::size_t i = 0; i < 4; ++i) {
        auto& s = h.seg[i];
        s.linked = s.intact = 1, s.pe = 3.0 + pos(rng), s.qe = 0.1 * unit(rng);
      }
    }
    // beyond the face (i ≥ N): a state off the usual path, which the lanes must neither test nor change
    for (std::size_t i = N; i < h.seg.size(); ++i) h.seg[i].linked = 0, h.seg[i].intact = 7, h.seg[i].pe = -1e300;
    if (trial == 1) {  // signed zeros: P = −0.0 on the segments with ξ < 0, Σ starts from +0.0
      in.du0 = -0.0, in.du_xi = 0.0, in.dv0 = -0.0, in.dv_xi = 0.0, in.eta_n = in.eta_s = 1.0;
      in.tension_intact = -1e6, in.cohesion_intact = 1e6;
      for (auto& s : h.seg) s.u = 0.0, s.pe = s.qe = -0.0, s.linked = s.intact = 1;
    }
    CAPTURE(trial);
    check_lanes_against_scalar<N>(in, h, vector_path);
  }
  return vector_path;
}
}  // namespace

TEST_CASE("face: segments in vector lanes give the scalar law's states and sums bit for bit, N = 3 4 5", "[face]") {
  // Both ways must be exercised: the strong trials (half) and most of every fourth take the lanes.
  for (const int taken : {lanes_against_scalar_trials<3>(), lanes_against_scalar_trials<4>(), lanes_against_scalar_trials<5>()}) {
    CAPTURE(taken);
    CHECK(taken > 2500);
    CHECK(taken < 3500);
  }
}

TEST_CASE("face: face_contact_force (segments in lanes) gives face_contact_force_scalar's bits, every N and reading",
          "[face]") {
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int steps = 0;
  for (int n = 1; n <= dem::kMaxSegments; ++n)
    for (const auto normal : {dem::NormalIncrement::exact, dem::NormalIncrement::linearised})
      for (const auto tangential : {dem::TangentialIncrement::exact, dem::TangentialIncrement::literal,
                                    dem::TangentialIncrement::linearised, dem::TangentialIncrement::hisatake}) {
        dem::FaceLaw law;
        law.segments = n;
        law.positions = n == 2 && tangential == dem::TangentialIncrement::literal ? dem::SegmentPositions::ends
                                                                                 : dem::SegmentPositions::centres;
        law.normal = normal, law.tangential = tangential;
        law.tensile_strength = 2e6, law.cohesion = 1e6, law.tan_phi = 0.6, law.healing = n % 2 == 0;
        dem::FaceConstants c;
        c.kn = kn, c.ks = ks, c.eta_n = 40.0, c.eta_s = 20.0, c.half_length = a, c.segment_area = 1e-6 / n;
        dem::FaceHistory fast, readable;
        dem::start_face(law, c, 1e-7, true, n % 3 == 0, fast);
        readable = fast;
        for (int k = 0; k < 300; ++k) {
          dem::FaceKinematics m;
          const double scale = k % 50 < 40 ? 1e-8 : 1e-6;  // mostly small (linked, sticking), now and then large
          m.du_projected = scale * unit(rng), m.du_exact = m.du_projected * (1.0 + 1e-3 * unit(rng));
          m.dv_translation = scale * unit(rng), m.dv_frame = 0.0;
          m.dphi1 = scale / a * unit(rng), m.dphi2 = scale / a * unit(rng);
          m.dbeta = 1e-4 * unit(rng), m.r1 = 0.01, m.r2 = 0.012;
          const dem::FaceForce f = dem::face_contact_force(law, c, m, inv_dt, fast);
          const dem::FaceForce g = dem::face_contact_force_scalar(law, c, m, inv_dt, readable);
          CAPTURE(n, static_cast<int>(normal), static_cast<int>(tangential), k);
          REQUIRE(same_bits(f.p, g.p));
          REQUIRE(same_bits(f.q, g.q));
          REQUIRE(same_bits(f.p_moment, g.p_moment));
          REQUIRE(f.links == g.links);
          REQUIRE(f.any_tensile == g.any_tensile);
          REQUIRE(same_bits(fast.theta1, readable.theta1));
          REQUIRE(same_bits(fast.theta2, readable.theta2));
          REQUIRE(fast.geometric_start == readable.geometric_start);
          for (std::size_t i = 0; i < fast.seg.size(); ++i) {
            const dem::SegmentState &u = fast.seg[i], &v = readable.seg[i];
            REQUIRE((same_bits(u.u, v.u) && same_bits(u.pe, v.pe) && same_bits(u.qe, v.qe)));
            REQUIRE((u.linked == v.linked && u.intact == v.intact));
          }
          ++steps;
        }
      }
  CHECK(steps == 8 * 2 * 4 * 300);
}

TEST_CASE("face: the rotated-corner lever puts each segment force at the element's rotated body point (M19.r)", "[face]") {
  // A wall contact (r2 = 0) of N segments turned by θ in one step with a shear and normal load: the moment
  // on element 1 must be Σ_i x_i × F_i with x_i = R(θ)(r1 n + aξ_i t) and F_i = −P_i n − Q_i t, formed here
  // with explicit vectors (n = (0, −1): the wall below; t = n turned by +90° = (1, 0)); the wall-frame lever
  // (M19) puts F_i at r1 n + aξ_i t instead. Dashpots off, so P_i, Q_i are the segment states after the step.
  const int n = GENERATE(1, 2, 3, 5);
  const double theta = GENERATE(0.0, 0.3, -0.7, 1.2);
  CAPTURE(n, theta);
  const dem::Vec2 nn{0.0, -1.0}, tt{1.0, 0.0};
  for (const auto lever : {dem::FaceLever::wall_frame, dem::FaceLever::rotated_corner}) {
    auto law = face_law(n, n == 2 ? dem::SegmentPositions::ends : dem::SegmentPositions::centres);
    law.normal = dem::NormalIncrement::exact;
    law.tangential = dem::TangentialIncrement::exact;
    law.lever = lever;
    const auto c = constants(n);
    dem::FaceHistory h;
    dem::start_face(law, c, 2e-5, true, false, h);
    dem::FaceKinematics k = normal_step(1e-6, a, 0.0);
    k.dv_translation = k.dv_frame = 3e-6;
    k.dphi1 = theta;
    dem::FaceHistory h_fast = h;
    const dem::FaceForce f = dem::face_contact_force_scalar(law, c, k, inv_dt, h);
    const dem::FaceForce fast = dem::face_contact_force(law, c, k, inv_dt, h_fast);
    CHECK(std::bit_cast<std::uint64_t>(fast.p_moment) == std::bit_cast<std::uint64_t>(f.p_moment));  // the same path
    CHECK(std::bit_cast<std::uint64_t>(fast.q) == std::bit_cast<std::uint64_t>(f.q));
    const double ct = std::cos(theta), st = std::sin(theta);
    double expected = 0.0, scale = 0.0;
    for (int i = 0; i < n; ++i) {
      const auto& s = h.seg[static_cast<std::size_t>(i)];
      REQUIRE(s.linked == 1);
      const double xi = law.positions == dem::SegmentPositions::ends ? (i == 0 ? -1.0 : 1.0) : (2.0 * i + 1.0 - n) / n;
      const dem::Vec2 body = nn * a + tt * (a * xi);  // r1 = a
      const dem::Vec2 at = lever == dem::FaceLever::rotated_corner ? dem::Vec2{ct * body.x - st * body.y, st * body.x + ct * body.y} : body;
      const dem::Vec2 force = nn * (-s.pe) - tt * s.qe;
      expected += at.x * force.y - at.y * force.x;
      scale += a * (std::abs(s.pe) + std::abs(s.qe));
    }
    CAPTURE(static_cast<int>(lever));
    CHECK_THAT(-a * f.q + f.p_moment, WithinAbs(expected, 1e-14 * scale));  // M1 = −r1 Q + p_moment
  }
}

TEST_CASE("face: the two levers differ once the element has turned and agree before (M19, M19.r)", "[face]") {
  auto law = face_law(2, dem::SegmentPositions::ends);
  const auto c = constants(2);
  dem::FaceHistory h0;
  dem::start_face(law, c, 2e-5, true, false, h0);
  for (const double theta : {0.0, 0.2}) {
    dem::FaceKinematics k = normal_step(1e-6, a, 0.0);
    k.dv_translation = k.dv_frame = 3e-6;
    k.dphi1 = theta;
    dem::FaceHistory hw = h0, hr = h0;
    law.lever = dem::FaceLever::wall_frame;
    const dem::FaceForce w = dem::face_contact_force(law, c, k, inv_dt, hw);
    law.lever = dem::FaceLever::rotated_corner;
    const dem::FaceForce r = dem::face_contact_force(law, c, k, inv_dt, hr);
    CHECK(r.p == w.p);
    CHECK(r.q == w.q);
    if (theta == 0.0) CHECK_THAT(r.p_moment, WithinAbs(w.p_moment, 1e-15 * std::abs(a * w.q)));
    else CHECK(std::abs(r.p_moment - w.p_moment) > 0.05 * std::abs(a * w.p));
  }
}
