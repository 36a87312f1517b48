// Unit tests of ref/base_friction_onset.hpp: the friction the pivot of a toppling block needs (refs §3.6,
// §3.8) and the rotation and plate travel at which it reaches tan phi_w; and of the corner-following
// lever of ref/base_friction_pre_face.hpp (WallLever::rotated_corner).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ref/base_friction_m21.hpp"
#include "ref/base_friction_onset.hpp"
#include "ref/base_friction_travel.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double degree = std::numbers::pi / 180.0;
constexpr double seed_w = 0.025;  // Matsui's M-C block (docs/model.md §3)
constexpr double seed_h = 0.075;
constexpr double phi_w = 38 * degree;

// An independent evaluation of the rigid block's pivot demand: the block in its own coordinates (w along
// the base from the pivot corner, h up), rotated by θ about the corner, turning at the M21 rate of
// ref/base_friction_m21.hpp; the M21 forces summed and resolved along and normal to the slope.
double rigid_demand_by_rotation(double theta, double alpha, int n_w, int n_h) {
  const double s = seed_w / n_w, r = 0.5 * s;
  const double omega = ref::m21_rate(alpha + theta, seed_w, seed_h, n_w, n_h);  // per unit plate travel
  const double gx = -std::sin(alpha), gy = -std::cos(alpha);                     // plate velocity / v_B
  double fx = 0.0, fy = 0.0;
  for (int j = 0; j < n_h; ++j)
    for (int i = 0; i < n_w; ++i) {
      const double w = (i + 0.5) * s, h = (j + 0.5) * s;
      const double x = w * std::cos(theta) - h * std::sin(theta), y = w * std::sin(theta) + h * std::cos(theta);
      const double vx = -omega * y - gx, vy = omega * x - gy;  // centre velocity relative to the plate
      const double speed = std::hypot(std::hypot(vx, vy), omega * r);
      fx -= vx / speed;  // the M21 force on the element, per μ_B m g
      fy -= vy / speed;
    }
  return -fx / -fy;  // the reaction is -Σ F: R_x / R_y
}

}  // namespace

TEST_CASE("Onset: the corner-following lever with the exact law is the rigid block's M21 rate",
          "[base_friction][onset]") {
  for (double theta_deg : {0.0, 5.0, 20.0, 40.0, 60.0})
    for (int n : {1, 2, 5}) {
      const double theta = theta_deg * degree, alpha = 60 * degree;
      CHECK_THAT(ref::pre_face_rate(theta, alpha, seed_w, seed_h, n, 3 * n, ref::WallTangentialLaw::exact,
                                    ref::WallLever::rotated_corner),
                 WithinRel(ref::m21_rate(alpha + theta, seed_w, seed_h, n, 3 * n), 1e-10));
    }
}

TEST_CASE("Onset: the rigid pivot's friction demand against an independent sum", "[base_friction][onset]") {
  for (double alpha_deg : {50.0, 60.0, 75.0})
    for (double theta_deg : {0.0, 10.0, 30.0})
      for (int n : {1, 3}) {
        const double alpha = alpha_deg * degree, theta = theta_deg * degree;
        CHECK_THAT(ref::pivot_friction_demand(theta, alpha, seed_w, seed_h, n, 3 * n, ref::rigid_m21_pivot),
                   WithinAbs(rigid_demand_by_rotation(theta, alpha, n, 3 * n), 1e-9));
      }
}

TEST_CASE("Onset: the demand reaches tan phi_w first at the onset rotation", "[base_friction][onset]") {
  for (double alpha_deg : {60.0, 75.0})
    for (ref::PivotModel model : {ref::rigid_m21_pivot, ref::pre_face_pivot}) {
      const double alpha = alpha_deg * degree;
      const double onset = ref::onset_rotation(alpha, phi_w, seed_w, seed_h, 1, 3, model);
      REQUIRE(onset > 0.0);
      REQUIRE(onset < std::numbers::pi / 2.0);
      CHECK_THAT(ref::pivot_friction_demand(onset, alpha, seed_w, seed_h, 1, 3, model),
                 WithinAbs(std::tan(phi_w), 1e-8));
      for (double f : {0.0, 0.25, 0.5, 0.9, 0.99})
        CHECK(ref::pivot_friction_demand(f * onset, alpha, seed_w, seed_h, 1, 3, model) < std::tan(phi_w));
    }
  // α = 50°: the pivot holds beyond θ = 47.4°, where base_friction_onset's control run ends (60 mm);
  // measured 52.7°.
  CHECK(ref::onset_rotation(50 * degree, phi_w, seed_w, seed_h, 1, 3, ref::rigid_m21_pivot) > 50 * degree);
}

TEST_CASE("Onset: the travel inverts the rotation and the PRE model converges to the rigid block",
          "[base_friction][onset]") {
  const double alpha = 60 * degree;
  const double theta = ref::onset_rotation(alpha, phi_w, seed_w, seed_h, 1, 3, ref::rigid_m21_pivot);
  const double travel = ref::onset_travel(alpha, phi_w, seed_w, seed_h, 1, 3, ref::rigid_m21_pivot);
  CHECK_THAT(ref::theta_at_travel_m21(travel, alpha, seed_w, seed_h, 1, 3), WithinAbs(theta, 1e-8));
  // the PRE model's block reaches the limit earlier, by less as the elements shrink (O(r))
  double previous = 1.0;
  for (int n : {1, 2, 3, 5}) {
    const double rigid = ref::onset_rotation(alpha, phi_w, seed_w, seed_h, n, 3 * n, ref::rigid_m21_pivot);
    const double pre = ref::onset_rotation(alpha, phi_w, seed_w, seed_h, n, 3 * n, ref::pre_face_pivot);
    CHECK(pre < rigid);
    CHECK(rigid - pre < previous);
    previous = rigid - pre;
  }
}

TEST_CASE("Onset: bad input is rejected", "[base_friction][onset]") {
  CHECK_THROWS_AS(ref::onset_rotation(1.0, 0.0, seed_w, seed_h, 1, 3, ref::rigid_m21_pivot), std::invalid_argument);
  CHECK_THROWS_AS(ref::onset_rotation(1.0, 1.6, seed_w, seed_h, 1, 3, ref::rigid_m21_pivot), std::invalid_argument);
  CHECK_THROWS_AS(ref::pivot_friction_demand(0.1, 0.2, seed_w, seed_h, 1, 3, ref::rigid_m21_pivot),
                  std::invalid_argument);  // α = 11.5°: the block does not topple
  CHECK_THROWS_AS(ref::onset_travel(1.0, 0.6, seed_w, seed_h, 1, 2, ref::rigid_m21_pivot), std::invalid_argument);
}
