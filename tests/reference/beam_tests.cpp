// Elastic beam theory and the square PRE lattice's beam (refs §4.1–§4.4).
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "ref/beam.hpp"
#include "ref/registry.hpp"

using Catch::Matchers::WithinRel;
using ref::SegmentPositions;

namespace {
// The M-D prism: 40 × 40 mm section, span 100 mm (refs §4.1).
const ref::BeamSection prism{0.040, 0.040, 0.100};
constexpr double E = 4000e6, nu = 1.0 / 6.0;  // Pa
constexpr double mm = 1e-3;
}  // namespace

TEST_CASE("Beam: section and peak load of the mortar prism (refs 4.1)", "[beam]") {
  CHECK_THAT(ref::second_moment(prism), WithinRel(213333.3333e-12, 1e-9));
  CHECK_THAT(ref::flexural_peak_load(prism, 5.6e6), WithinRel(2389.3333, 1e-7));
}

TEST_CASE("Beam: Euler-Bernoulli and Timoshenko stiffness of the prism (refs 4.1)", "[beam]") {
  const double G = E / (2.0 * (1.0 + nu));
  CHECK_THAT(G, WithinRel(1714.286e6, 1e-6));
  CHECK_THAT(ref::euler_bernoulli_stiffness(prism, E) * mm, WithinRel(40960.0, 1e-9));
  // δ(P_max) = 0.058333 mm (EB) and 0.084467 mm (Timoshenko, κ = 5/6).
  const double P = ref::flexural_peak_load(prism, 5.6e6);
  CHECK_THAT(P / ref::euler_bernoulli_stiffness(prism, E) / mm, WithinRel(0.058333, 1e-5));
  const double kT = ref::timoshenko_stiffness(prism, E, G, ref::shear_coefficient_parabolic());
  CHECK_THAT(kT * mm, WithinRel(28287.0, 2e-5));
  CHECK_THAT(P / kT / mm, WithinRel(0.084467, 1e-5));
  CHECK_THAT(ref::shear_coefficient_cowper(nu), WithinRel(0.843373, 1e-6));
  CHECK_THAT(ref::timoshenko_stiffness(prism, E, G, ref::shear_coefficient_cowper(nu)) * mm,
             WithinRel(28392.0, 3e-5));
}

TEST_CASE("Beam: the square lattice is orthotropic with E = kn, G = ks/2, nu = 0 (refs 4.3)", "[beam]") {
  const auto m = ref::square_lattice_moduli(4300e6, 1720e6);
  CHECK(m.young == 4300e6);
  CHECK(m.shear_modulus == 860e6);
  CHECK(m.poisson == 0.0);
  // Beam stiffness of the lattice: EB 44 032 N/mm; Timoshenko 22 465 N/mm (paper constants) and
  // 22 391 N/mm (M25.l's exact constants 4285.7, 1714.3 → G_eff = 857.1).
  CHECK_THAT(ref::euler_bernoulli_stiffness(prism, m.young) * mm, WithinRel(44032.0, 1e-5));
  CHECK_THAT(ref::timoshenko_stiffness(prism, m.young, m.shear_modulus, 5.0 / 6.0) * mm, WithinRel(22465.0, 3e-5));
  const auto exact = ref::square_lattice_moduli(E * 15.0 / 14.0, 0.4 * E * 15.0 / 14.0);
  CHECK_THAT(ref::timoshenko_stiffness(prism, exact.young, exact.shear_modulus, 5.0 / 6.0) * mm,
             WithinRel(22391.0, 3e-5));
  // The continuum target is ~21 % stiffer (28 287 N/mm), almost all from G_eff = G/2.
  const double G = E / (2.0 * (1.0 + nu));
  const double ratio = ref::timoshenko_stiffness(prism, m.young, m.shear_modulus, 5.0 / 6.0) /
                       ref::timoshenko_stiffness(prism, E, G, 5.0 / 6.0);
  CHECK_THAT(ratio, WithinRel(0.794, 2e-3));
}

TEST_CASE("Beam: discrete faces change the bending moment of inertia (refs 4.3)", "[beam]") {
  CHECK(ref::lattice_bending_factor(1, 1, SegmentPositions::centres) == 0.0);  // N = 1, one row: no face moment
  CHECK_THAT(ref::lattice_bending_factor(6, 5, SegmentPositions::centres), WithinRel(1.0 - 1.0 / 900.0, 1e-14));
  CHECK_THAT(ref::lattice_bending_factor(4, 2, SegmentPositions::face_ends), WithinRel(1.125, 1e-14));
  // A finer lattice approaches the continuum from below (centres) and from above (ends).
  CHECK(ref::lattice_bending_factor(10, 1, SegmentPositions::centres) > ref::lattice_bending_factor(6, 1, SegmentPositions::centres));
  CHECK(ref::lattice_bending_factor(10, 2, SegmentPositions::face_ends) < ref::lattice_bending_factor(6, 2, SegmentPositions::face_ends));
}

TEST_CASE("Beam: first-crack ratio table of refs 4.4", "[beam]") {
  struct Row { int rows; double by_n[5]; double ends; };
  const Row table[] = {{2, {1.5000, 1.2500, 1.1667, 1.1250, 1.1000}, 1.5000},
                       {3, {1.3333, 1.1667, 1.1111, 1.0833, 1.0667}, 1.2222},
                       {4, {1.2500, 1.1250, 1.0833, 1.0625, 1.0500}, 1.1250},
                       {6, {1.1667, 1.0833, 1.0556, 1.0417, 1.0333}, 1.0556},
                       {10, {1.1000, 1.0500, 1.0333, 1.0250, 1.0200}, 1.0200}};
  for (const auto& row : table) {
    CAPTURE(row.rows);
    for (int N = 1; N <= 5; ++N) {
      CAPTURE(N);
      CHECK_THAT(ref::lattice_first_crack_ratio(row.rows, N, SegmentPositions::centres), WithinRel(row.by_n[N - 1], 5e-5));
    }
    CHECK_THAT(ref::lattice_first_crack_ratio(row.rows, 2, SegmentPositions::face_ends), WithinRel(row.ends, 5e-5));
  }
}

TEST_CASE("Beam: invalid inputs are refused", "[beam]") {
  CHECK_THROWS_AS(ref::second_moment({0.0, 0.04, 0.1}), std::invalid_argument);
  CHECK_THROWS_AS(ref::euler_bernoulli_stiffness(prism, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::lattice_first_crack_ratio(0, 1, SegmentPositions::centres), std::invalid_argument);
  CHECK_THROWS_AS(ref::lattice_bending_factor(4, 3, SegmentPositions::face_ends), std::invalid_argument);
  CHECK_THROWS_AS(ref::shear_coefficient_cowper(0.5), std::invalid_argument);
}

TEST_CASE("Beam: support springs in series and the lattice beam through the registry (refs 4.3)", "[beam]") {
  // Two support contacts of 172 kN/mm each carry P/2: δ = P/k + P/(2 k_c).
  CHECK_THAT(ref::stiffness_on_support_springs(22465e3, 172e6) * mm,
             WithinRel(1.0 / (1.0 / 22465.0 + 0.5 / 172000.0), 3e-5));
  CHECK_THAT(ref::stiffness_on_support_springs(1e3, 1e300), WithinRel(1e3, 1e-12));
  // 2 × 8 lattice, N = 5 at the centres: I_eff = I(1 − 1/100), paper constants.
  const double k = ref::lattice_beam_stiffness(prism, 4300e6, 1720e6, 2, 5, SegmentPositions::centres);
  const double by_hand = 1.0 / (0.1 * 0.1 * 0.1 / (48.0 * 4300e6 * 213333.333e-12 * 0.99) +
                                0.1 / (4.0 * (5.0 / 6.0) * 860e6 * 0.0016));
  CHECK_THAT(k, WithinRel(by_hand, 1e-8));
  const std::map<std::string, double> a{{"b", 0.04}, {"h", 0.04}, {"L", 0.1}, {"kn", 4300e6}, {"ks", 1720e6},
                                        {"n_h", 2},   {"N", 5},     {"ends", 0},  {"k_c", 172e6}};
  CHECK_THAT(ref::evaluate("beam.lattice_stiffness", a), WithinRel(ref::stiffness_on_support_springs(k, 172e6), 1e-14));
  auto ends = a;
  ends["N"] = 2;
  ends["ends"] = 1;
  CHECK(ref::evaluate("beam.lattice_stiffness", ends) > ref::evaluate("beam.lattice_stiffness", a));  // I(1 + 2/n_h²)
  // The continuum beam on the same supports, and its -21 % gap to the lattice without them.
  const double kc = ref::evaluate("beam.continuum_stiffness",
                                  {{"b", 0.04}, {"h", 0.04}, {"L", 0.1}, {"E", 4000e6}, {"nu", 1.0 / 6.0}, {"k_c", 1e300}});
  CHECK_THAT(kc * mm, WithinRel(28287.0, 2e-5));
  CHECK_THAT(ref::evaluate("beam.peak_load", {{"b", 0.04}, {"h", 0.04}, {"L", 0.1}, {"sigma_t", 5.6e6}}),
             WithinRel(2389.3333, 1e-7));
  CHECK_THAT(ref::evaluate("beam.first_crack_ratio", {{"n_h", 6}, {"N", 3}, {"ends", 0}}), WithinRel(1.0 + 1.0 / 18.0, 1e-14));
  CHECK_THROWS_AS(ref::evaluate("beam.first_crack_ratio", {{"n_h", 6}, {"N", 3}, {"ends", 1}}), std::invalid_argument);
  CHECK_THROWS_AS(ref::stiffness_on_support_springs(1e3, 0.0), std::invalid_argument);
}

TEST_CASE("Beam: the load disk wedged in the top groove raises the first-crack load", "[beam]") {
  const double P = ref::flexural_peak_load(prism, 5.6e6);
  // By hand for 2 × 8 (r = 10 mm, R = 5 mm): sin θ = 2/3, t = tan θ/2 = 0.447214, contact height
  // y_p = 30 + 10 cos θ = 37.4536 mm, e = 17.4536 mm. Without the lattice factors (a huge n_h·N would
  // be needed), the wedge factor is 150/(150 − 6 t e + t h) = 1.2391.
  const double t = 0.5 * (2.0 / 3.0) / std::sqrt(1.0 - 4.0 / 9.0), e = 30.0 + 10.0 * std::sqrt(5.0 / 9.0) - 20.0;
  const double wedge = 150.0 / (150.0 - 6.0 * t * e + t * 40.0);
  CHECK_THAT(wedge, WithinRel(1.23910, 1e-5));
  const double p1 = ref::groove_first_crack_load(prism, 5.6e6, 2, 5, SegmentPositions::centres, 5e-3);
  // With the lattice: M y_max/I_eff = (L/4 − t e) P (h/2)(1 − 1/10)/(I · 0.99), plus t P/A.
  const double I = 213333.3333e-12, by_hand =
      5.6e6 / ((0.025 - t * e * mm) * 0.02 * 0.9 / (I * 0.99) + t / 0.0016);
  CHECK_THAT(p1, WithinRel(by_hand, 1e-8));
  // Over P_max: the bending part is divided by the first-crack ratio 1.1, the tension part is not.
  CHECK_THAT(p1 / P, WithinRel(1.0 / ((1.0 - t * e / 25.0) / 1.1 + t * 40.0 / 150.0), 1e-9));
  // A vanishing load disk radius... is refused; a huge one approaches the plain estimate (θ → 0).
  CHECK_THROWS_AS(ref::groove_first_crack_load(prism, 5.6e6, 2, 5, SegmentPositions::centres, 0.0), std::invalid_argument);
  CHECK_THAT(ref::groove_first_crack_load(prism, 5.6e6, 2, 5, SegmentPositions::centres, 1e6) / P,
             WithinRel(ref::lattice_first_crack_ratio(2, 5, SegmentPositions::centres), 1e-6));
  // The wedge matters less on finer lattices (smaller cores under the same disk).
  const double f6 = ref::groove_first_crack_load(prism, 5.6e6, 6, 5, SegmentPositions::centres, 5e-3) /
                    (P * ref::lattice_first_crack_ratio(6, 5, SegmentPositions::centres));
  const double f10 = ref::groove_first_crack_load(prism, 5.6e6, 10, 5, SegmentPositions::centres, 5e-3) /
                     (P * ref::lattice_first_crack_ratio(10, 5, SegmentPositions::centres));
  CHECK(f10 < f6);
  CHECK(f6 < wedge);
  CHECK(f10 > 1.0);
}
