// A bonded face turned rigidly (ref/face_rotation.hpp) against hand values and its small-angle limit,
// and through the registry.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "ref/face_rotation.hpp"
#include "ref/registry.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("face rotation: a quarter turn stretches the face-end springs as drawn by hand", "[face_rotation]") {
  // r = 1, θ = 90°: the material point at (−1, −1) from the centre goes to (1, −1), the one at (1, −1)
  // to (1, 1). Stretches (2, 0) and (0, 2): F_x = 2 K_s, F_y = 2 K_n.
  const auto f = ref::face_rotation_wall_force(3.0, 5.0, 1.0, 2, true, std::numbers::pi / 2);
  CHECK_THAT(f.fx, WithinRel(10.0, 1e-15));
  CHECK_THAT(f.fy, WithinRel(6.0, 1e-15));
  // on the element: −(10, 0) at (−1, −1) and −(0, 6) at (1, −1) from the centre: M = −10 − 6 = −16
  CHECK_THAT(f.moment, WithinRel(-16.0, 1e-15));
  // clockwise: the point at (1, −1) goes to (−1, −1), the one at (−1, −1) to (−1, 1): F_x = −2 K_s
  const auto g = ref::face_rotation_wall_force(3.0, 5.0, 1.0, 2, true, -std::numbers::pi / 2);
  CHECK_THAT(g.fx, WithinRel(-10.0, 1e-15));
  CHECK_THAT(g.fy, WithinRel(6.0, 1e-15));
}

TEST_CASE("face rotation: the sums are N K_s r sin θ and N K_n r (1 - cos θ) and tend to the linearised face", "[face_rotation]") {
  const double kn = 1.2e7, ks = 4.8e6, r = 0.02;
  for (int n : {1, 3, 5, 8})
    for (double theta : {-0.9, -0.2, 0.35, 1.2}) {
      const auto f = ref::face_rotation_wall_force(kn, ks, r, n, false, theta);
      CHECK_THAT(f.fx, WithinRel(n * ks * r * std::sin(theta), 1e-13));
      CHECK_THAT(f.fy, WithinRel(n * kn * r * (1.0 - std::cos(theta)), 1e-12));
      double sum_s2 = 0.0;  // Σ s_i² at the segment centres
      for (int i = 1; i <= n; ++i) sum_s2 += std::pow(r * (2 * i - 1 - n) / n, 2);
      CHECK_THAT(f.moment, WithinRel(-(kn * sum_s2 + n * ks * r * r) * std::sin(theta), 1e-12));
    }
  // small angles: F_x → N K_s r θ (M14.2), F_y → 0 at second order (M14.1 has no lift)
  const double theta = 1e-4;
  const auto f = ref::face_rotation_wall_force(kn, ks, r, 5, false, theta);
  CHECK_THAT(f.fx, WithinRel(5 * ks * r * theta, 2e-9));
  CHECK_THAT(f.fy, WithinAbs(0.0, 5 * kn * r * theta * theta));
}

TEST_CASE("face rotation: registry arguments and refusals", "[face_rotation]") {
  const std::map<std::string, double> args{{"Kn", 1.2e7}, {"Ks", 1.2e7}, {"r", 0.0125}, {"N", 2}, {"ends", 1}, {"theta", 0.5}};
  CHECK_THAT(ref::evaluate("face.rotation_wall_fx", args), WithinRel(2 * 1.2e7 * 0.0125 * std::sin(0.5), 1e-13));
  CHECK_THAT(ref::evaluate("face.rotation_wall_fy", args), WithinRel(2 * 1.2e7 * 0.0125 * (1 - std::cos(0.5)), 1e-12));
  auto bad = args;
  bad["ends"] = 0.5;
  CHECK_THROWS_AS(ref::evaluate("face.rotation_wall_fx", bad), std::invalid_argument);
  bad = args;
  bad["N"] = 3;  // face ends need N = 2
  CHECK_THROWS_AS(ref::evaluate("face.rotation_wall_fx", bad), std::invalid_argument);
  CHECK_THROWS_AS(ref::face_rotation_wall_force(-1.0, 1.0, 1.0, 2, false, 0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::face_rotation_wall_force(1.0, 1.0, 1.0, 2, false, std::nan("")), std::invalid_argument);
}
