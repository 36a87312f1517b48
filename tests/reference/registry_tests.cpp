// Unit tests of ref/registry.hpp: the names and argument lists, agreement with the direct calls,
// and the error messages for unknown names, missing or unknown arguments and rejected values.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "ref/base_friction.hpp"
#include "ref/base_friction_m21.hpp"
#include "ref/base_friction_travel.hpp"
#include "ref/block_on_incline.hpp"
#include "ref/elastic_contact_2d.hpp"
#include "ref/impact.hpp"
#include "ref/oscillator.hpp"
#include "ref/registry.hpp"
#include "ref/stability.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace {

using Args = std::map<std::string, double>;
constexpr double degree = std::numbers::pi / 180.0;

std::vector<std::string> argument_names(const std::string& solver) {
  for (const auto& info : ref::solvers()) {
    if (info.name == solver) {
      std::vector<std::string> names;
      for (const auto& argument : info.arguments) names.push_back(argument.name);
      return names;
    }
  }
  return {"<not registered>"};
}

}  // namespace

TEST_CASE("registry: every solver with its exact argument list", "[registry]") {
  using Names = std::vector<std::string>;
  const std::map<std::string, Names> expected{
      {"impact.restitution_A", {"zeta"}},
      {"impact.restitution_B", {"zeta"}},
      {"impact.duration_A", {"m", "K", "eta"}},
      {"impact.duration_B", {"m", "K", "eta"}},
      {"impact.max_overlap", {"m", "K", "eta", "v0"}},
      {"oscillator.position", {"m", "K", "eta", "x0", "v0", "t"}},
      {"oscillator.velocity", {"m", "K", "eta", "x0", "v0", "t"}},
      {"free_fall.position", {"x0", "v0", "g", "t"}},
      {"free_fall.velocity", {"v0", "g", "t"}},
      {"face.bending_moment", {"k", "a", "theta"}},
      {"face.no_tension_moment", {"k", "a", "N", "delta", "r", "theta"}},
      {"face.rotation_wall_fx", {"Kn", "Ks", "r", "N", "ends", "theta"}},
      {"face.rotation_wall_fy", {"Kn", "Ks", "r", "N", "ends", "theta"}},
      {"face.rotation_moment_wall_frame", {"Kn", "Ks", "r", "N", "ends", "theta"}},
      {"rest.overlap", {"m", "g", "K"}},
      {"stability.K18_limit_W", {"zeta"}},
      {"stability.K19_limit_W", {"zeta"}},
      {"stability.K18_limit_dt", {"m", "K", "eta"}},
      {"stability.K19_limit_dt", {"m", "K", "eta"}},
      {"incline.slide_distance", {"alpha", "phi", "g", "t"}},
      {"incline.mode", {"alpha", "phi", "b", "h"}},
      {"incline.mode_gb", {"alpha", "phi", "b", "h"}},
      {"kiyama.contact_stiffness", {"E", "nu", "r", "q", "c"}},
      {"base_friction.rate", {"psi", "W", "H"}},
      {"base_friction.theta", {"alpha", "delta_B", "W", "H"}},
      {"base_friction.travel", {"alpha", "theta", "W", "H"}},
      {"base_friction.m21_rate", {"psi", "W", "H", "n_w", "n_h"}},
      {"base_friction.theta_m21", {"alpha", "delta_B", "W", "H", "n_w", "n_h"}},
      {"base_friction.slide_ratio", {"alpha", "phi_w"}},
      {"beam.lattice_stiffness", {"b", "h", "L", "kn", "ks", "n_h", "N", "ends", "k_c"}},
      {"beam.continuum_stiffness", {"b", "h", "L", "E", "nu", "k_c"}},
      {"beam.peak_load", {"b", "h", "L", "sigma_t"}},
      {"beam.first_crack_ratio", {"n_h", "N", "ends"}},
      {"beam.groove_first_crack_load", {"b", "h", "L", "sigma_t", "n_h", "N", "ends", "R"}},
      {"silo.janssen_wall_force", {"z1", "z2", "rho_b", "g", "B", "K", "mu_w"}},
      {"silo.k_geom", {"s", "B", "r"}},
      {"silo.beverloo_2d", {"C", "rho_b", "g", "D", "k", "d"}},
      {"silo.fill_height", {"s", "B", "r", "count"}},
      {"silo.area_fraction", {"s", "B", "r"}},
      {"silo.fill_weight", {"s", "B", "r", "count", "rho", "g"}},
      {"silo.janssen_contact_force", {"z", "s", "B", "r", "count", "rho", "g", "mu_w"}},
      {"silo.janssen_wall_contact", {"k", "s", "B", "r", "count", "rho", "g", "mu_w"}},
      {"base_friction.pre_face_rate", {"theta", "alpha", "W", "H", "n_w", "n_h"}},
      {"base_friction.theta_pre_face", {"alpha", "delta_B", "W", "H", "n_w", "n_h"}},
      {"base_friction.theta_pre_face_exact", {"alpha", "delta_B", "W", "H", "n_w", "n_h"}},
      {"base_friction.onset_theta_m21", {"alpha", "phi_w", "W", "H", "n_w", "n_h"}},
      {"base_friction.onset_travel_m21", {"alpha", "phi_w", "W", "H", "n_w", "n_h"}},
      {"base_friction.onset_theta_pre_face", {"alpha", "phi_w", "W", "H", "n_w", "n_h"}},
      {"base_friction.onset_travel_pre_face", {"alpha", "phi_w", "W", "H", "n_w", "n_h"}},
      {"beam.lattice_exact_stiffness",
       {"b", "h", "L", "kn", "ks", "n_h", "n_l", "N", "ends", "k_c", "k_t", "k_pt", "R_s", "R_l"}},
      {"beam.lattice_exact_first_crack_load",
       {"b", "h", "L", "kn", "ks", "n_h", "n_l", "N", "ends", "k_c", "k_t", "k_pt", "R_s", "R_l", "sigma_t"}},
      {"matsui.pair_time_step", {"zeta", "m", "K"}},
      {"disk_slope.position", {"m", "kn", "s", "zeta", "alpha", "phi", "g", "t"}},
      {"disk_slope.velocity", {"m", "kn", "s", "zeta", "alpha", "phi", "g", "t"}},
      {"disk_slope.spin_speed", {"m", "kn", "s", "zeta", "alpha", "phi", "g", "t"}},
      {"kiyama.rest_overlap", {"m", "g", "E", "nu", "r", "q", "c", "factor"}},
      {"rolling.position", {"m", "r", "g", "alpha", "ks", "eta_s", "mu", "kr", "cr", "mu_r", "v0", "t"}},
      {"rolling.velocity", {"m", "r", "g", "alpha", "ks", "eta_s", "mu", "kr", "cr", "mu_r", "v0", "t"}},
      {"rolling.omega", {"m", "r", "g", "alpha", "ks", "eta_s", "mu", "kr", "cr", "mu_r", "v0", "t"}},
      {"rolling.moment", {"m", "r", "g", "alpha", "ks", "eta_s", "mu", "kr", "cr", "mu_r", "v0", "t"}},
      {"rolling.spring_moment", {"kr", "kn", "mu_r", "r", "delta", "theta"}},
      {"rolling.pair_spring_moment", {"kr", "kn", "mu_r", "r_i", "r_j", "delta", "theta"}},
      {"rolling.rigid_stop_distance", {"v0", "mu_r", "g"}},
      {"rolling.rigid_stop_time", {"v0", "mu_r", "g"}},
      {"rolling.rigid_velocity", {"v0", "alpha", "mu_r", "g", "t"}},
      {"rolling.mode", {"alpha", "phi", "mu_r"}},
      {"rolling.rigid_slope_acceleration", {"alpha", "mu_r", "g"}},
      {"oblique.vt_after", {"m", "r", "kn", "eta_n", "ks", "eta_s", "mu", "v", "theta", "omega0"}},
      {"oblique.omega_after", {"m", "r", "kn", "eta_n", "ks", "eta_s", "mu", "v", "theta", "omega0"}},
      {"oblique.vn_after", {"m", "r", "kn", "eta_n", "ks", "eta_s", "mu", "v", "theta", "omega0"}},
      {"gap.pull_force", {"k", "eta", "v", "t", "strength"}},
      {"gap.break_time", {"k", "v", "strength"}},
      {"rocking.impact_time", {"b", "h", "theta0", "g"}},
      {"rocking.impact_speed", {"b", "h", "theta0", "g"}},
      {"rocking.rebound_tilt", {"b", "h", "theta0"}},
      {"rocking.restitution", {"b", "h"}},
  };
  const auto infos = ref::solvers();
  CHECK(infos.size() == expected.size());
  std::set<std::string> seen;
  for (const auto& info : infos) {
    CAPTURE(info.name);
    CHECK(seen.insert(info.name).second);  // unique names
    CHECK_FALSE(info.description.empty());
    CHECK_FALSE(info.result_unit.empty());
    for (const auto& argument : info.arguments) CHECK_FALSE(argument.unit.empty());
  }
  for (const auto& [name, names] : expected) {
    CAPTURE(name);
    CHECK(argument_names(name) == names);
  }
}

TEST_CASE("registry: values equal the direct calls", "[registry]") {
  const double m = 0.3, k = 2.0e4, eta = 40.0;
  const ref::Oscillator o(m, k, eta);
  const Args mke{{"m", m}, {"K", k}, {"eta", eta}};
  using ref::ContactEnd;
  using ref::Scheme;
  CHECK(ref::evaluate("impact.restitution_A", {{"zeta", 0.3}}) ==
        ref::restitution(ContactEnd::elastic_force_zero, 0.3));
  CHECK_THAT(ref::evaluate("impact.restitution_B", {{"zeta", 0.1}}), WithinRel(0.7440793977, 1e-9));
  CHECK(ref::evaluate("impact.duration_A", mke) ==
        ref::contact_duration(ContactEnd::elastic_force_zero, o));
  CHECK(ref::evaluate("impact.duration_B", mke) ==
        ref::contact_duration(ContactEnd::total_force_zero, o));
  CHECK(std::isinf(ref::evaluate("impact.duration_A", {{"m", 1.0}, {"K", 1.0}, {"eta", 2.0}})));
  CHECK(ref::evaluate("impact.max_overlap", {{"m", m}, {"K", k}, {"eta", eta}, {"v0", 0.5}}) ==
        ref::maximum_overlap(o, 0.5).overlap);
  const Args motion{{"m", m}, {"K", k}, {"eta", eta}, {"x0", 1e-3}, {"v0", -0.2}, {"t", 0.01}};
  CHECK(ref::evaluate("oscillator.position", motion) ==
        ref::oscillator_state(o, {1e-3, -0.2}, 0.01).position);
  CHECK(ref::evaluate("oscillator.velocity", motion) ==
        ref::oscillator_state(o, {1e-3, -0.2}, 0.01).velocity);
  CHECK_THAT(
      ref::evaluate("free_fall.position", {{"x0", 1.0}, {"v0", 0.0}, {"g", -10.0}, {"t", 0.2}}),
      WithinRel(0.8, 1e-15));
  CHECK_THAT(ref::evaluate("free_fall.velocity", {{"v0", 1.0}, {"g", -10.0}, {"t", 0.2}}),
             WithinRel(-1.0, 1e-15));
  CHECK_THAT(ref::evaluate("rest.overlap", {{"m", 2.0}, {"g", 9.0}, {"K", 3.0}}),
             WithinRel(6.0, 1e-15));
  CHECK(ref::evaluate("stability.K18_limit_W", {{"zeta", 1.0}}) ==
        ref::stability_limit(Scheme::K18, 1.0));
  CHECK(ref::evaluate("stability.K19_limit_W", {{"zeta", 1.0}}) == 2.0);
  CHECK(ref::evaluate("stability.K18_limit_dt", mke) ==
        ref::stability_limit_time_step(Scheme::K18, o));
  CHECK(ref::evaluate("stability.K19_limit_dt", mke) ==
        ref::stability_limit_time_step(Scheme::K19, o));
  CHECK_THAT(
      ref::evaluate("incline.slide_distance",
                    {{"alpha", 40 * degree}, {"phi", 38 * degree}, {"g", 9.80665}, {"t", 0.5}}),
      WithinRel(54.2897e-3, 2e-6));
  const Args block{{"alpha", 50 * degree}, {"phi", std::atan(0.78129)}, {"b", 0.025}, {"h", 0.075}};
  CHECK(ref::evaluate("incline.mode", block) == 2.0);     // topple
  CHECK(ref::evaluate("incline.mode_gb", block) == 3.0);  // slide + topple
  const double kgf = 9.80665;
  const double kn = ref::evaluate(
      "kiyama.contact_stiffness",
      {{"E", 750.0 * kgf / 1e-4}, {"nu", 0.3}, {"r", 0.01}, {"q", 0.068 * kgf / 1e-2}, {"c", 1.5}});
  CHECK_THAT(kn / (2650.0 * kgf) * 100.0, WithinRel(3.637e4, 2e-4));

  // Base friction (refs §3), seed block W = 25 mm, H = 75 mm.
  const double w = 0.025, h = 0.075;
  CHECK(ref::evaluate("base_friction.rate", {{"psi", 60 * degree}, {"W", w}, {"H", h}}) ==
        ref::base_friction_rate(60 * degree, w, h));
  CHECK_THAT(ref::evaluate("base_friction.rate", {{"psi", 60 * degree}, {"W", w}, {"H", h}}) * h,
             WithinRel(0.95934234, 1e-8));
  CHECK(ref::evaluate("base_friction.theta",
                      {{"alpha", 30 * degree}, {"delta_B", 0.02}, {"W", w}, {"H", h}}) ==
        ref::theta_at_travel(0.02, 30 * degree, w, h));
  CHECK(ref::evaluate("base_friction.travel",
                      {{"alpha", 75 * degree}, {"theta", 10 * degree}, {"W", w}, {"H", h}}) ==
        ref::travel_at_theta(10 * degree, 75 * degree, w, h));
  const Args lattice{{"psi", 40 * degree}, {"W", w}, {"H", h}, {"n_w", 1.0}, {"n_h", 3.0}};
  CHECK(ref::evaluate("base_friction.m21_rate", lattice) == ref::m21_rate(40 * degree, w, h, 1, 3));
  CHECK(ref::evaluate("base_friction.theta_m21", {{"alpha", 60 * degree},
                                                  {"delta_B", 0.01},
                                                  {"W", w},
                                                  {"H", h},
                                                  {"n_w", 5.0},
                                                  {"n_h", 15.0}}) ==
        ref::theta_at_travel_m21(0.01, 60 * degree, w, h, 5, 15));
  CHECK_THAT(
      ref::evaluate("base_friction.slide_ratio", {{"alpha", 60 * degree}, {"phi_w", 38 * degree}}),
      WithinRel(0.475383, 1e-6));
}

TEST_CASE("registry: bad names and arguments throw with a clear message", "[registry]") {
  CHECK_THROWS_AS(ref::evaluate("impact.restitution_C", {{"zeta", 0.1}}), std::invalid_argument);
  CHECK_THROWS_WITH(ref::evaluate("impact.restitution_C", {{"zeta", 0.1}}),
                    Contains("unknown solver 'impact.restitution_C'"));
  CHECK_THROWS_AS(ref::evaluate("", {}), std::invalid_argument);

  CHECK_THROWS_AS(ref::evaluate("impact.duration_A", {{"m", 1.0}, {"K", 1.0}}),
                  std::invalid_argument);
  CHECK_THROWS_WITH(ref::evaluate("impact.duration_A", {{"m", 1.0}, {"K", 1.0}}),
                    Contains("impact.duration_A") && Contains("missing argument 'eta'"));

  CHECK_THROWS_WITH(ref::evaluate("rest.overlap", {{"m", 1.0}, {"g", 9.8}, {"K", 1.0}, {"k", 1.0}}),
                    Contains("rest.overlap") && Contains("unknown argument 'k'"));

  CHECK_THROWS_AS(ref::evaluate("impact.duration_B", {{"m", -1.0}, {"K", 1.0}, {"eta", 0.1}}),
                  std::invalid_argument);
  CHECK_THROWS_WITH(ref::evaluate("impact.duration_B", {{"m", -1.0}, {"K", 1.0}, {"eta", 0.1}}),
                    Contains("impact.duration_B") && Contains("mass"));
  CHECK_THROWS_AS(
      ref::evaluate("incline.mode", {{"alpha", 0.5}, {"phi", 0.5}, {"b", 1.0}, {"h", 0.0}}),
      std::invalid_argument);
  CHECK_THROWS_AS(ref::evaluate("kiyama.contact_stiffness",
                                {{"E", 1e7}, {"nu", 0.6}, {"r", 0.01}, {"q", 10.0}, {"c", 1.5}}),
                  std::invalid_argument);
  CHECK_THROWS_AS(ref::evaluate("stability.K19_limit_W", {{"zeta", std::nan("")}}),
                  std::invalid_argument);
  CHECK_THROWS_WITH(
      ref::evaluate("base_friction.m21_rate",
                    {{"psi", 1.0}, {"W", 0.025}, {"H", 0.075}, {"n_w", 1.5}, {"n_h", 3.0}}),
      Contains("base_friction.m21_rate") && Contains("n_w must be a whole number"));
  CHECK_THROWS_AS(ref::evaluate("base_friction.theta",
                                {{"alpha", 2.0}, {"delta_B", 0.01}, {"W", 0.025}, {"H", 0.075}}),
                  std::invalid_argument);
}
