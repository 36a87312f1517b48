// The rolling-disk reference (reference/ref/rolling_disk.hpp): the continuous model tends to the rigid limit's
// closed forms as its springs stiffen (rolling to rest, rolling down a slope, held on one), keeps its moment at
// μ_r r N while rolling, and refuses bad arguments.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "ref/rolling_disk.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// A 1 cm disk of 0.8 kg (per unit thickness), g = 9.81, stick friction μ = 0.6; the springs `stiffness` times
// K_s = 1e6 N/m and k_r = 10 N·m/rad; the slip oscillator (m/3, K_s) damped at 0.3 of critical (undamped, it
// would ring at ±5e-4 m/s on the velocity when the rolling moment sets in), the rolling spring undamped.
ref::RollingDisk disk(double stiffness, double alpha, double v0) {
  const double ks = 1e6 * stiffness;
  return {.m = 0.8, .r = 0.01, .g = 9.81, .alpha = alpha, .ks = ks, .eta_s = 0.6 * std::sqrt(0.8 / 3.0 * ks), .mu = 0.6,
          .kr = 10.0 * stiffness, .cr = 0.0, .mu_r = 0.1, .v0 = v0};
}

}  // namespace

TEST_CASE("rolling_disk: rolling to rest on a flat wall tends to 3 v0²/(4 μ_r g)", "[reference][rolling]") {
  const double want = ref::rolling_stop_distance(0.1, 0.1, 9.81);
  CHECK_THAT(want, WithinRel(3.0 * 0.01 / (4.0 * 0.981), 1e-15));
  CHECK_THAT(ref::rolling_stop_time(0.1, 0.1, 9.81), WithinRel(0.3 / (2.0 * 0.981), 1e-15));
  // the elastic rotation θ_L = μ_r r N/k_r: 7.85e-4 rad at k_r = 10, 7.85e-6 at 1000; the distance follows r θ_L
  const double soft = ref::rolling_disk(disk(1.0, 0.0, 0.1), 0.3).x;
  const double stiff = ref::rolling_disk(disk(100.0, 0.0, 0.1), 0.3).x;
  CHECK(std::abs(soft - want) < 2.0 * 0.01 * 7.85e-4);
  CHECK(std::abs(stiff - want) < 2.0 * 0.01 * 7.85e-6);
  CHECK(std::abs(stiff - want) < std::abs(soft - want));
  // while it rolls the moment is the limit μ_r r N
  CHECK_THAT(ref::rolling_disk(disk(1.0, 0.0, 0.1), 0.05).moment, WithinRel(0.1 * 0.01 * 0.8 * 9.81, 1e-9));
  // the spring reaches the limit after τ = θ_L/ω0 = 7.85e-5 s: the velocity leads by at most (2/3) μ_r g τ = 5.1e-5
  CHECK_THAT(ref::rolling_disk(disk(1.0, 0.0, 0.1), 0.05).v, WithinAbs(0.1 - (2.0 / 3.0) * 0.1 * 9.81 * 0.05, 5.2e-5));
}

TEST_CASE("rolling_disk: on a slope it rolls at (2/3) g (sin α − μ_r cos α) above tan α = μ_r, else stays",
          "[reference][rolling]") {
  const double rolls = 10.0 * std::numbers::pi / 180.0, held = 5.0 * std::numbers::pi / 180.0;  // tan: 0.176, 0.087
  const double a = ref::rolling_slope_acceleration(rolls, 0.1, 9.81);
  CHECK_THAT(a, WithinRel((2.0 / 3.0) * 9.81 * (std::sin(rolls) - 0.1 * std::cos(rolls)), 1e-15));
  CHECK(ref::rolling_slope_acceleration(held, 0.1, 9.81) == 0.0);
  // from rest the spring loads over τ_L = √(2 r θ_L/a_0) = 0.4 ms at k_r = 1000: ≤ (2/3) μ_r g cos α τ_L = 2.6e-4
  CHECK_THAT(ref::rolling_disk(disk(100.0, rolls, 0.0), 0.2).v, WithinAbs(a * 0.2, 2.6e-4));
  CHECK(std::abs(ref::rolling_disk(disk(100.0, held, 0.0), 0.2).x) < 1e-6);
  CHECK(ref::rolling_rigid_velocity(0.1, 0.0, 0.1, 9.81, 1.0) == 0.0);  // stopped and stays
}

namespace {

// The rigid disk's initial motion found another way: each of the four hypotheses (stays; slides without
// turning; rolls without slip; rolls and slides) solved for its forces and accelerations and kept only if it
// is consistent (m = r = g = 1, I = 1/2, N = cos α). Returns the consistent ones.
std::vector<int> consistent_modes(double alpha, double mu, double mu_r) {
  const double n = std::cos(alpha), s = std::sin(alpha), i = 0.5;
  std::vector<int> modes;
  if (s <= mu * n && s <= mu_r * n) modes.push_back(0);                // F = s, M = F r = s
  if (s - mu * n > 0.0 && mu * n <= mu_r * n) modes.push_back(1);      // F = μN, no turn: M = F r within its cap
  const double a = (s - mu_r * n) / (1.0 + i);                         // a = r ω̇, M = μ_r N, F = s − a
  if (a > 0.0 && s - a <= mu * n) modes.push_back(2);
  const double a3 = s - mu * n, spin = (mu * n - mu_r * n) / i;        // F = μN, M = μ_r N
  if (spin > 0.0 && a3 - spin > 0.0) modes.push_back(3);
  return modes;
}

}  // namespace

TEST_CASE("rolling_disk: the initial motion on a slope is the one consistent hypothesis (refs 7.4)", "[reference][rolling]") {
  const double deg = std::numbers::pi / 180.0;
  int checked = 0;
  for (double mu_r : {0.25, 1.0 / 3.0, 0.5, 0.75, 1.0, 2.0})
    for (double phi = 10.0; phi <= 60.0; phi += 2.5)
      for (double alpha = 1.0; alpha <= 88.0; alpha += 1.5) {
        const double mu = std::tan(phi * deg);
        const std::vector<int> modes = consistent_modes(alpha * deg, mu, mu_r);
        CAPTURE(mu_r, phi, alpha);
        // On a boundary (α = φ on the grid, two hypotheses at equality, or one lost to round-off): no test of
        // the inequalities.
        const double t = std::tan(alpha * deg);
        const bool on_boundary = std::abs(t - mu) < 1e-9 || std::abs(t - mu_r) < 1e-9 || std::abs(t - (3.0 * mu - 2.0 * mu_r)) < 1e-9;
        if (modes.size() != 1 || on_boundary) continue;
        CHECK(ref::rolling_disk_mode(alpha * deg, mu, mu_r) == modes.front());
        ++checked;
      }
  CHECK(checked > 3000);
  // the four regions all occur: μ_r = 1/2, φ = 38°: stays at 20°, rolls at 40°, rolls and slides at 60°; μ_r = 2: slides at 60°
  const double mu38 = std::tan(38.0 * deg);
  CHECK(ref::rolling_disk_mode(20.0 * deg, mu38, 0.5) == 0);
  CHECK(ref::rolling_disk_mode(40.0 * deg, mu38, 0.5) == 2);
  CHECK(ref::rolling_disk_mode(60.0 * deg, mu38, 0.5) == 3);
  CHECK(ref::rolling_disk_mode(60.0 * deg, mu38, 2.0) == 1);
  CHECK_THROWS_AS(ref::rolling_disk_mode(-0.1, 0.5, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(ref::rolling_disk_mode(0.5, -0.5, 0.5), std::invalid_argument);
}

TEST_CASE("rolling_disk refuses bad arguments", "[reference][rolling]") {
  CHECK_THROWS_AS(ref::rolling_disk(disk(1.0, -0.1, 0.0), 0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::rolling_disk(disk(1.0, 0.0, 0.0), -1.0), std::invalid_argument);
  ref::RollingDisk d = disk(1.0, 0.0, 0.0);
  d.kr = 0.0;
  CHECK_THROWS_AS(ref::rolling_disk(d, 0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::rolling_stop_distance(0.1, 0.0, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(ref::rolling_rigid_velocity(-0.1, 0.0, 0.1, 9.81, 1.0), std::invalid_argument);
}
