// The rolling-disk reference (reference/ref/rolling_disk.hpp): the continuous model tends to the rigid limit's
// closed forms as its springs stiffen (rolling to rest, rolling down a slope, held on one), keeps its moment at
// μ_r r N while rolling, and refuses bad arguments.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

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

TEST_CASE("rolling_disk refuses bad arguments", "[reference][rolling]") {
  CHECK_THROWS_AS(ref::rolling_disk(disk(1.0, -0.1, 0.0), 0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::rolling_disk(disk(1.0, 0.0, 0.0), -1.0), std::invalid_argument);
  ref::RollingDisk d = disk(1.0, 0.0, 0.0);
  d.kr = 0.0;
  CHECK_THROWS_AS(ref::rolling_disk(d, 0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::rolling_stop_distance(0.1, 0.0, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(ref::rolling_rigid_velocity(-0.1, 0.0, 0.1, 9.81, 1.0), std::invalid_argument);
}
