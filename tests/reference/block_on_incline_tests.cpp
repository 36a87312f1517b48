// Unit tests of ref/block_on_incline.hpp: the delta(t) table of refs §2.1, the seed cases and the
// full mode map of refs §2.3 (Sagaseta and Goodman & Bray), and the initial-motion consistency.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "ref/block_on_incline.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using ref::Mode;

namespace {

constexpr double degree = std::numbers::pi / 180.0;

std::string mode_row(double beta, double phi_deg, bool goodman_bray) {
  std::string row;
  for (int alpha_deg = 5; alpha_deg <= 85; alpha_deg += 5) {
    const double alpha = alpha_deg * degree;
    const double phi = phi_deg * degree;
    row += ref::mode_code(goodman_bray ? ref::mode_goodman_bray(alpha, phi, beta)
                                       : ref::mode_sagaseta(alpha, phi, beta));
  }
  return row;
}

std::string boundary_text(double beta, double phi_deg) {
  char text[96];
  const auto st = ref::slide_topple_angle(phi_deg * degree, beta);
  char st_text[16] = "none";
  if (st) std::snprintf(st_text, sizeof st_text, "%.2f", *st / degree);
  std::snprintf(text, sizeof text, "slide %.2f, topple %.2f, S+T %s",
                ref::sliding_angle(phi_deg * degree) / degree, ref::toppling_angle(beta) / degree,
                st_text);
  return text;
}

struct MapRow {
  double beta;
  double phi_deg;
  const char* sagaseta;
  const char* boundaries;
  const char* goodman_bray;
};

// refs §2.3 "Mode map for issue B", alpha = 5 ... 85 degrees.
const MapRow mode_map[] = {
    {2.0, 20, "....SSSSSSSSSSSSS", "slide 20.00, topple 63.43, S+T none", "....SSSSSSSSXXXXX"},
    {2.0, 30, "......SSSSSSSSSSS", "slide 30.00, topple 63.43, S+T none", "......SSSSSSXXXXX"},
    {2.0, 38, ".......SSSSSSSSSS", "slide 38.00, topple 63.43, S+T none", ".......SSSSSXXXXX"},
    {2.0, 45, ".........SSSSSSSS", "slide 45.00, topple 63.43, S+T none", ".........SSSXXXXX"},
    {1.0, 20, "....SSSSSSSSSSSSS", "slide 20.00, topple 45.00, S+T none", "....SSSSSXXXXXXXX"},
    {1.0, 30, "......SSSSSSSSSSS", "slide 30.00, topple 45.00, S+T none", "......SSSXXXXXXXX"},
    {1.0, 38, ".......SSSSSSSSSS", "slide 38.00, topple 45.00, S+T none", ".......SSXXXXXXXX"},
    {1.0, 45, ".........SSSSSSSS", "slide 45.00, topple 45.00, S+T none", ".........XXXXXXXX"},
    {0.5, 20, "....SSSSSSSSSSSSS", "slide 20.00, topple 26.57, S+T none", "....SXXXXXXXXXXXX"},
    {0.5, 30, ".....TTTXXXXXXXXX", "slide 30.00, topple 26.57, S+T 40.07", ".....TXXXXXXXXXXX"},
    {0.5, 38, ".....TTTTTTTTXXXX", "slide 38.00, topple 26.57, S+T 65.54", ".....TTXXXXXXXXXX"},
    {0.5, 45, ".....TTTTTTTTTTXX", "slide 45.00, topple 26.57, S+T 79.70", ".....TTTTXXXXXXXX"},
    {1.0 / 3.0, 20, "...TXXXXXXXXXXXXX", "slide 20.00, topple 18.43, S+T 24.67",
     "...TXXXXXXXXXXXXX"},
    {1.0 / 3.0, 30, "...TTTTTTTTXXXXXX", "slide 30.00, topple 18.43, S+T 57.74",
     "...TTTXXXXXXXXXXX"},
    {1.0 / 3.0, 38, "...TTTTTTTTTTTXXX", "slide 38.00, topple 18.43, S+T 73.31",
     "...TTTTXXXXXXXXXX"},
    {1.0 / 3.0, 45, "...TTTTTTTTTTTTTX", "slide 45.00, topple 18.43, S+T 81.87",
     "...TTTTTTXXXXXXXX"},
};

}  // namespace

TEST_CASE("incline: sliding acceleration and the delta(t) table of refs §2.1", "[incline]") {
  const double alpha = 40.0 * degree;
  const double phi = 38.0 * degree;
  CHECK_THAT(ref::sliding_acceleration(alpha, phi, 9.80665), WithinRel(0.434318, 2e-6));
  // M20 as printed (cos alpha (tan alpha - tan phi)) is the same acceleration.
  CHECK_THAT(ref::sliding_acceleration(alpha, phi, 9.80665),
             WithinRel(std::cos(alpha) * (std::tan(alpha) - std::tan(phi)) * 9.80665, 1e-14));
  const double t[] = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5};
  const double delta_g0[] = {0.54290, 2.17159, 8.68636, 19.5443, 34.7454, 54.2897};    // mm
  const double delta_g981[] = {0.54308, 2.17233, 8.68932, 19.5510, 34.7573, 54.3083};  // mm
  for (int i = 0; i < 6; ++i) {
    CAPTURE(t[i]);
    CHECK_THAT(ref::slide_distance(alpha, phi, 9.80665, t[i]) * 1e3, WithinRel(delta_g0[i], 2e-5));
    CHECK_THAT(ref::slide_distance(alpha, phi, 9.81, t[i]) * 1e3, WithinRel(delta_g981[i], 2e-5));
  }
  // Friction holds: no slide.
  CHECK(ref::slide_distance(30.0 * degree, phi, 9.81, 1.0) == 0.0);
  CHECK(ref::sliding_acceleration(30.0 * degree, phi, 9.81) < 0.0);
}

TEST_CASE("incline: seed cases of refs §2.3", "[incline]") {
  // Square block, alpha = 40, phi = 38: slide under both criteria.
  CHECK(ref::mode_sagaseta(40.0 * degree, 38.0 * degree, 1.0) == Mode::slide);
  CHECK(ref::mode_goodman_bray(40.0 * degree, 38.0 * degree, 1.0) == Mode::slide);
  // Aluminium block in gravity, beta = 25/75, tan phi = 0.78129.
  const double beta = 25.0 / 75.0;
  const double phi = std::atan(0.78129);
  CHECK_THAT(ref::toppling_friction_threshold(50.0 * degree, beta), WithinAbs(0.5132, 5e-5));
  CHECK_THAT(ref::toppling_friction_threshold(60.0 * degree, beta), WithinAbs(0.5993, 5e-5));
  CHECK_THAT(ref::toppling_friction_threshold(75.0 * degree, beta), WithinAbs(0.8148, 5e-5));
  CHECK(ref::mode_sagaseta(50.0 * degree, phi, beta) == Mode::topple);
  CHECK(ref::mode_goodman_bray(50.0 * degree, phi, beta) == Mode::slide_topple);
  CHECK(ref::mode_sagaseta(60.0 * degree, phi, beta) == Mode::topple);
  CHECK(ref::mode_sagaseta(75.0 * degree, phi, beta) == Mode::slide_topple);
  const auto alpha_st = ref::slide_topple_angle(phi, beta);
  REQUIRE(alpha_st.has_value());
  CHECK_THAT(*alpha_st / degree, WithinAbs(73.31, 5e-3));
  CHECK_THAT(ref::toppling_friction_threshold(*alpha_st, beta), WithinRel(0.78129, 1e-13));
}

TEST_CASE("incline: the full mode map of refs §2.3, Sagaseta and Goodman & Bray", "[incline]") {
  for (const auto& row : mode_map) {
    CAPTURE(row.beta, row.phi_deg);
    CHECK(mode_row(row.beta, row.phi_deg, false) == row.sagaseta);
    CHECK(mode_row(row.beta, row.phi_deg, true) == row.goodman_bray);
    CHECK(boundary_text(row.beta, row.phi_deg) == row.boundaries);
  }
}

TEST_CASE("incline: mode codes and enum values", "[incline]") {
  CHECK(ref::mode_code(Mode::stable) == '.');
  CHECK(ref::mode_code(Mode::slide) == 'S');
  CHECK(ref::mode_code(Mode::topple) == 'T');
  CHECK(ref::mode_code(Mode::slide_topple) == 'X');
  CHECK(static_cast<int>(Mode::slide_topple) == 3);
}

TEST_CASE("incline: properties of T and of the two classifications", "[incline]") {
  for (double beta : {0.2, 1.0 / 3.0, 0.5, 1.0, 2.0}) {
    double previous = 0.0;
    for (int alpha_deg = 1; alpha_deg <= 89; ++alpha_deg) {
      const double alpha = alpha_deg * degree;
      const double t = ref::toppling_friction_threshold(alpha, beta);
      CAPTURE(beta, alpha_deg);
      CHECK(t > previous);  // T increases with tan alpha
      previous = t;
      if (std::tan(alpha) > beta) {
        CHECK(t > beta);
        CHECK(t < std::tan(alpha));
      }
      for (int phi_deg = 5; phi_deg <= 60; phi_deg += 5) {
        const double phi = phi_deg * degree;
        const Mode gb = ref::mode_goodman_bray(alpha, phi, beta);
        const Mode sagaseta = ref::mode_sagaseta(alpha, phi, beta);
        // Sagaseta refines only G&B's slide + topple region.
        if (gb != Mode::slide_topple) CHECK(sagaseta == gb);
        if (gb == Mode::slide_topple) CHECK(sagaseta != Mode::stable);
      }
    }
  }
  // Either side of alpha_ST: topple below, slide + topple above.
  const double phi = 38.0 * degree;
  const double alpha_st = *ref::slide_topple_angle(phi, 0.5);
  CHECK(ref::mode_sagaseta(alpha_st - 1e-6, phi, 0.5) == Mode::topple);
  CHECK(ref::mode_sagaseta(alpha_st + 1e-6, phi, 0.5) == Mode::slide_topple);
  // No S+T when beta >= tan phi, or when the denominator 4 beta^2 + 1 - 3 beta tan phi <= 0.
  CHECK_FALSE(ref::slide_topple_angle(phi, 1.0).has_value());
  CHECK_FALSE(ref::slide_topple_angle(80.0 * degree, 0.5).has_value());  // 2 - 1.5 tan 80 < 0
  CHECK(ref::mode_sagaseta(85.0 * degree, 80.0 * degree, 0.5) == Mode::topple);
}

TEST_CASE("incline: initial motion is consistent with the mode", "[incline]") {
  const double g = 9.80665;
  const double h = 0.075;
  for (double beta : {0.2, 1.0 / 3.0, 0.5, 1.0, 2.0}) {
    for (int alpha_deg = 2; alpha_deg <= 88; alpha_deg += 2) {
      for (int phi_deg = 5; phi_deg <= 60; phi_deg += 5) {
        const double alpha = alpha_deg * degree;
        const double tan_phi = std::tan(phi_deg * degree);
        const auto motion = ref::initial_motion(alpha, phi_deg * degree, beta * h, h, g);
        CAPTURE(beta, alpha_deg, phi_deg, ref::mode_code(motion.mode));
        CHECK(motion.normal_force_ratio > 0.0);
        switch (motion.mode) {
          case Mode::stable:
            CHECK(std::abs(motion.friction_force_ratio) <=
                  tan_phi * motion.normal_force_ratio + 1e-15);
            break;
          case Mode::slide:
            CHECK(motion.slide_acceleration > 0.0);
            CHECK(motion.angular_acceleration == 0.0);
            break;
          case Mode::topple:  // no slip at the pivot; the block tips down-slope
            CHECK(motion.angular_acceleration > 0.0);
            CHECK(std::abs(motion.friction_force_ratio) <=
                  tan_phi * motion.normal_force_ratio * (1.0 + 1e-12));
            break;
          case Mode::slide_topple:  // pivot slides down-slope while the block tips
            CHECK(motion.angular_acceleration > 0.0);
            CHECK(motion.slide_acceleration > 0.0);
            CHECK_THAT(motion.friction_force_ratio,
                       WithinRel(-tan_phi * motion.normal_force_ratio, 1e-14));
            break;
        }
      }
    }
  }
  // Aluminium block (25 x 75 mm) at 60 degrees: pure toppling, theta'' = (3g/2)(h sin - b cos)/(b^2
  // + h^2).
  const double b = 0.025;
  const auto topple = ref::initial_motion(60.0 * degree, std::atan(0.78129), b, h, g);
  REQUIRE(topple.mode == Mode::topple);
  const double s = std::sin(60.0 * degree);
  const double c = std::cos(60.0 * degree);
  CHECK_THAT(topple.angular_acceleration,
             WithinRel(1.5 * g * (h * s - b * c) / (b * b + h * h), 1e-14));
  // Newton along the slope for the whole block: m a_cm,s = m g sin alpha + F with a_cm,s = theta''
  // h/2.
  CHECK_THAT(topple.angular_acceleration * h / 2.0,
             WithinRel(g * s + g * topple.friction_force_ratio, 1e-12));
  // and normal: m a_cm,n = N - m g cos alpha with a_cm,n = theta'' b/2.
  CHECK_THAT(topple.angular_acceleration * b / 2.0,
             WithinRel(g * topple.normal_force_ratio - g * c, 1e-12));
}

TEST_CASE("incline: bad input is rejected", "[incline]") {
  CHECK_THROWS_AS(ref::mode_sagaseta(90.0 * degree, 0.5, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::mode_sagaseta(-0.1, 0.5, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::mode_goodman_bray(0.5, 0.5, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::toppling_friction_threshold(0.5, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::slide_distance(0.5, 0.3, 9.81, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::sliding_acceleration(0.5, std::nan(""), 9.81), std::invalid_argument);
  CHECK_THROWS_AS(ref::initial_motion(0.5, 0.3, 0.0, 1.0, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(ref::initial_motion(0.5, 0.3, 1.0, 1.0, 0.0), std::invalid_argument);
}
