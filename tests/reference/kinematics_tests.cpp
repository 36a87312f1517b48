// Unit tests of ref/free_fall.hpp and ref/resting_overlap.hpp (refs §1.6, §1.7).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ref/free_fall.hpp"
#include "ref/resting_overlap.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("free fall: position and velocity", "[free_fall]") {
  const double g = -9.80665;
  CHECK_THAT(ref::free_fall_position(1.0, 2.0, g, 0.5),
             WithinRel(1.0 + 1.0 - 9.80665 / 8.0, 1e-15));
  CHECK_THAT(ref::free_fall_velocity(2.0, g, 0.5), WithinRel(2.0 - 9.80665 / 2.0, 1e-15));
  CHECK(ref::free_fall_position(0.25, -3.0, g, 0.0) == 0.25);
  // Drop from rest: falls g t^2/2, and v^2 = 2 g h.
  const double t = 0.3;
  const double drop = ref::free_fall_position(0.0, 0.0, g, t);
  CHECK_THAT(drop, WithinRel(-0.5 * 9.80665 * 0.09, 1e-15));
  CHECK_THAT(std::pow(ref::free_fall_velocity(0.0, g, t), 2), WithinRel(2.0 * g * drop, 1e-14));
  CHECK_THROWS_AS(ref::free_fall_position(0.0, 0.0, std::nan(""), 1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::free_fall_velocity(HUGE_VAL, -9.8, 1.0), std::invalid_argument);
}

TEST_CASE("rest: equilibrium overlap m g / K (refs §1.7)", "[rest]") {
  // One Kiyama disk (r = 1 cm, rho = 2.65 g/cm^3) on the bottom wall, K_w = 2 K_n,
  // K_n = 3.64e4 cm * rho g: x = pi r^2 /(2 * 3.64e4 cm) = 4.315e-5 cm; on a disk 8.631e-5 cm.
  const double g = 9.80665;
  const double rho = 2650.0;
  const double r = 0.01;
  const double m = rho * std::numbers::pi * r * r;
  const double k_n = 364.0 * rho * g;
  CHECK_THAT(ref::resting_overlap(m, g, 2.0 * k_n), WithinRel(4.315e-7, 2e-4));
  CHECK_THAT(ref::resting_overlap(m, g, k_n), WithinRel(8.631e-7, 2e-4));
  CHECK(ref::resting_overlap(m, 0.0, k_n) == 0.0);
  CHECK_THROWS_AS(ref::resting_overlap(-m, g, k_n), std::invalid_argument);
  CHECK_THROWS_AS(ref::resting_overlap(m, g, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::resting_overlap(m, -g, k_n), std::invalid_argument);
}
