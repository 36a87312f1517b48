// Unit tests of ref/disk_on_slope.hpp: the rigid-body limits of the sticking and sliding disk, the slip
// onset where the spring force reaches μN, continuity there, and the argument checks.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ref/disk_on_slope.hpp"
#include "ref/pre_time_step.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
const double deg = std::numbers::pi / 180.0;
ref::DiskOnSlope kiyama_disk(double alpha_deg, double phi_deg) {
  return {.m = 0.8325220532012952, .kn = 1.89e7, .s = 0.25, .zeta = 0.2, .alpha = alpha_deg * deg, .phi = phi_deg * deg, .g = 9.80665};
}
}  // namespace

TEST_CASE("disk on slope: a sticking contact rolls on at (2/3) g sin alpha once the slip oscillator has decayed") {
  const auto d = kiyama_disk(40.0, 30.0);
  const double t = 0.1, a = (2.0 / 3.0) * d.g * std::sin(d.alpha);
  const auto motion = ref::disk_on_slope(d, t);
  CHECK_FALSE(motion.sliding);
  CHECK_THAT(motion.v, WithinRel(a * t, 1e-12));
  CHECK_THAT(motion.spin_speed, WithinRel(a * t, 1e-12));
  // x = a t²/2 + s_eq/3 with the spring at rest at s_eq = m g sin α/(3 K_s)
  CHECK_THAT(motion.x, WithinRel(0.5 * a * t * t + d.m * d.g * std::sin(d.alpha) / (9.0 * d.s * d.kn), 1e-12));
}

TEST_CASE("disk on slope: a sliding disk accelerates at g (sin alpha - tan phi cos alpha) and spins up at 2 tan phi g cos alpha") {
  const auto d = kiyama_disk(40.0, 10.0);
  const double mu = std::tan(d.phi), h = 1e-4;
  const auto a = ref::disk_on_slope(d, 0.05), b = ref::disk_on_slope(d, 0.05 + h);
  CHECK(a.sliding);
  CHECK_THAT((b.v - a.v) / h, WithinRel(d.g * (std::sin(d.alpha) - mu * std::cos(d.alpha)), 1e-9));
  CHECK_THAT((b.spin_speed - a.spin_speed) / h, WithinRel(2.0 * mu * d.g * std::cos(d.alpha), 1e-9));
  // the elastic stick phase leads the rigid Coulomb slide, by less than μ g cos α / ω_s in velocity
  const double omega_s = std::sqrt(3.0 * d.s * d.kn / d.m), rigid = d.g * (std::sin(d.alpha) - mu * std::cos(d.alpha)) * 0.05;
  CHECK(a.v > rigid);
  CHECK(a.v - rigid < mu * d.g * std::cos(d.alpha) / omega_s);
}

TEST_CASE("disk on slope: the motion is continuous at the slip onset") {
  const auto d = kiyama_disk(30.0, 5.0);
  double lo = 0.0, hi = 2e-3;  // the onset lies in (0, 2 ms): find it from the sliding flag
  for (int k = 0; k < 80; ++k) {
    const double c = 0.5 * (lo + hi);
    (ref::disk_on_slope(d, c).sliding ? hi : lo) = c;
  }
  const auto before = ref::disk_on_slope(d, lo), after = ref::disk_on_slope(d, hi);
  CHECK_THAT(after.v, WithinAbs(before.v, 1e-12));
  CHECK_THAT(after.x, WithinAbs(before.x, 1e-15));
  CHECK_THAT(after.spin_speed, WithinAbs(before.spin_speed, 1e-12));
}

TEST_CASE("disk on slope: bad arguments are refused") {
  auto d = kiyama_disk(40.0, 10.0);
  CHECK_THROWS_AS(ref::disk_on_slope(d, -1.0), std::invalid_argument);
  d.alpha = 0.0;
  CHECK_THROWS_AS(ref::disk_on_slope(d, 0.1), std::invalid_argument);
  d = kiyama_disk(40.0, 90.0);
  CHECK_THROWS_AS(ref::disk_on_slope(d, 0.1), std::invalid_argument);
  d = kiyama_disk(40.0, 10.0);
  d.kn = 0.0;
  CHECK_THROWS_AS(ref::disk_on_slope(d, 0.1), std::invalid_argument);
}

TEST_CASE("matsui time step: h_n sqrt(m/k) - the K18 limit lies below it at h_n = 1") {
  CHECK_THAT(ref::matsui_time_step(1.0, 1.0, 1e6), WithinRel(1e-3, 1e-15));
  CHECK_THAT(ref::matsui_time_step(0.3, 4.0, 1e6), WithinRel(6e-4, 1e-15));
  CHECK(2.0 * (std::sqrt(2.0) - 1.0) < 1.0);  // K18's ω₀Δt limit at ζ = 1 against M26's h_n = 1
  CHECK_THROWS_AS(ref::matsui_time_step(1.0, 0.0, 1e6), std::invalid_argument);
}
