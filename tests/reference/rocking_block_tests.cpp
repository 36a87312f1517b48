// Unit tests of ref/rocking_block.hpp (Housner's rocking block, refs §2.4): the time to the first impact
// against a direct integration of I_o θ̈ = −m g R sin(α − θ) (RK4 written here, independent of GSL's
// QAWS), Housner's linearised time for a slender block, energy for the impact speed, the restitution of a
// square and of a slender block, and the rebound tilt by energy.
#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

#include "ref/rocking_block.hpp"

using Catch::Matchers::WithinRel;

namespace {

/// θ(t) from rest at θ₀ by RK4 with step dt until θ crosses 0; the crossing by linear interpolation.
double impact_time_rk4(double b, double h, double theta0, double g, double dt) {
  const double alpha = std::atan2(b, h), p2 = 3.0 * g / (4.0 * std::hypot(b, h));
  auto acc = [&](double th) { return -p2 * std::sin(alpha - th); };
  double t = 0.0, th = theta0, w = 0.0;
  while (true) {
    const double k1t = w, k1w = acc(th);
    const double k2t = w + 0.5 * dt * k1w, k2w = acc(th + 0.5 * dt * k1t);
    const double k3t = w + 0.5 * dt * k2w, k3w = acc(th + 0.5 * dt * k2t);
    const double k4t = w + dt * k3w, k4w = acc(th + dt * k3t);
    const double th1 = th + dt / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    const double w1 = w + dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
    if (th1 <= 0.0) return t + dt * th / (th - th1);
    t += dt, th = th1, w = w1;
  }
}

}  // namespace

TEST_CASE("rocking block: the time to the first impact against a direct integration", "[rocking]") {
  for (const auto& [b, h, f] : {std::tuple{0.025, 0.1, 0.5}, std::tuple{0.05, 0.15, 0.8}, std::tuple{0.5, 0.5, 0.3},
                                std::tuple{0.01, 1.0, 0.99}}) {
    CAPTURE(b, h, f);
    const double theta0 = f * std::atan2(b, h);
    const double t = ref::rocking_impact_time(b, h, theta0, 9.81);
    // RK4 at two steps: the interpolated crossing is O(dt²); their difference bounds the error
    const double fine = impact_time_rk4(b, h, theta0, 9.81, 1e-6), coarse = impact_time_rk4(b, h, theta0, 9.81, 2e-6);
    CHECK(std::abs(t - fine) < 4.0 * std::abs(fine - coarse) + 1e-12);
    CHECK_THAT(t, WithinRel(fine, 1e-8));
  }
  // the reference case of verification/polygon_rocking: 0.156181 s (and Housner's linearised 0.155906 s)
  CHECK_THAT(ref::rocking_impact_time(0.025, 0.1, 0.12248933156343207, 9.80665), WithinRel(0.15618095681623675, 1e-10));
}

TEST_CASE("rocking block: Housner's linearised time is the slender limit", "[rocking]") {
  const double b = 0.001, h = 1.0, theta0 = 0.5 * std::atan2(b, h);
  CHECK_THAT(ref::rocking_impact_time_linear(b, h, theta0, 9.81), WithinRel(ref::rocking_impact_time(b, h, theta0, 9.81), 1e-6));
  // at α = 14° it is 0.18 % short
  const double t = ref::rocking_impact_time(0.025, 0.1, 0.12248933156343207, 9.80665);
  CHECK(ref::rocking_impact_time_linear(0.025, 0.1, 0.12248933156343207, 9.80665) < t * (1 - 1e-3));
}

TEST_CASE("rocking block: impact speed, restitution and rebound tilt", "[rocking]") {
  const double b = 0.025, h = 0.1, alpha = std::atan2(b, h), theta0 = 0.5 * alpha, g = 9.80665;
  const double R = std::hypot(b, h), p2 = 3 * g / (4 * R);
  // energy about the pivot: ½ I_o ω₁² = m g R (cos(α − θ₀) − cos α)
  CHECK_THAT(ref::rocking_impact_speed(b, h, theta0, g), WithinRel(std::sqrt(2 * p2 * (std::cos(alpha - theta0) - std::cos(alpha))), 1e-12));
  CHECK_THAT(ref::rocking_restitution(1.0, 1.0), WithinRel(0.25, 1e-14));  // a square: 1 − 1.5 · ½
  CHECK_THAT(ref::rocking_restitution(b, h), WithinRel(1.0 - 1.5 / 17.0, 1e-14));  // sin²α = 1/17
  // rising on the other corner with ω₂ = r ω₁ to rest: ½ I_o ω₂² = m g R (cos(α − θ₂) − cos α)
  const double r = ref::rocking_restitution(b, h), w2 = r * ref::rocking_impact_speed(b, h, theta0, g);
  const double theta2 = ref::rocking_rebound_tilt(b, h, theta0);
  CHECK_THAT(w2 * w2, WithinRel(2 * p2 * (std::cos(alpha - theta2) - std::cos(alpha)), 1e-10));
  CHECK(theta2 < theta0);
  CHECK_THROWS_AS(ref::rocking_impact_time(b, h, 1.1 * alpha, g), std::invalid_argument);
  CHECK_THROWS_AS(ref::rocking_rebound_tilt(b, h, 0.0), std::invalid_argument);
}
