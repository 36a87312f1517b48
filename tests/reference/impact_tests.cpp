// Unit tests of ref/impact.hpp: the table of refs §1.2, the branch formulas of refs §1.2, Odeint event
// detection, consistency with the oscillator closed form, and input validation.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "ref/impact.hpp"
#include "ref/oscillator.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using ref::ContactEnd;

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

struct TableRow {
  double zeta;
  double e_a;
  double tc_a;  // omega0 t_c
  double e_b;
  double tc_b;
};

// refs §1.2, "Reference values" (10 decimals).
const TableRow table[] = {
    {0.0, 1.0, std::numbers::pi, 1.0, std::numbers::pi},
    {0.1, 0.7292476143, 3.1574194170, 0.7440793977, 2.9560753247},
    {0.3, 0.3723261049, 3.2932839419, 0.4509754529, 2.6544745638},
    {0.5, 0.1630335348, 3.6275987285, 0.2984360592, 2.4183991523},
    {0.7, 0.0459879103, 4.3991096250, 0.2102845644, 2.2275622815},
    {1.0 / std::numbers::sqrt2, 0.0432139183, 4.4428829382, 0.2078795764, 2.2214414691},
    {1.0, 0.0, infinity, 0.1353352832, 2.0},
    {std::numbers::sqrt2, 0.0, infinity, 0.0826697966, 1.7627471740},
    {2.0, 0.0, infinity, 0.0477687325, 1.5206919926},
};

// Convention B duration, written as the branches printed in refs §1.2 (independent of the
// single acos/acosh expression used by the library).
double spec_branch_duration_b(double zeta) {
  const double pi = std::numbers::pi;
  if (zeta < 1.0 / std::numbers::sqrt2) {
    const double w = std::sqrt(1.0 - zeta * zeta);
    return (pi - std::atan(2.0 * zeta * w / (1.0 - 2.0 * zeta * zeta))) / w;
  }
  if (zeta == 1.0 / std::numbers::sqrt2) return pi / std::numbers::sqrt2;
  if (zeta < 1.0) {
    const double w = std::sqrt(1.0 - zeta * zeta);
    return std::atan(2.0 * zeta * w / (2.0 * zeta * zeta - 1.0)) / w;
  }
  if (zeta == 1.0) return 2.0;
  const double big_omega = std::sqrt(zeta * zeta - 1.0);
  return std::log((zeta + big_omega) / (zeta - big_omega)) / big_omega;
}

ref::Oscillator make(double w0, double zeta) {
  const double m = 0.25;
  const double k = m * w0 * w0;
  return ref::Oscillator(m, k, 2.0 * zeta * std::sqrt(m * k));
}

}  // namespace

TEST_CASE("impact: restitution and duration reproduce the table of refs §1.2", "[impact]") {
  for (const auto& row : table) {
    CAPTURE(row.zeta);
    CHECK_THAT(ref::restitution(ContactEnd::elastic_force_zero, row.zeta),
               WithinAbs(row.e_a, 1e-10));
    CHECK_THAT(ref::restitution(ContactEnd::total_force_zero, row.zeta), WithinAbs(row.e_b, 1e-10));
    CHECK_THAT(ref::scaled_contact_duration(ContactEnd::total_force_zero, row.zeta),
               WithinAbs(row.tc_b, 1e-10));
    if (std::isinf(row.tc_a)) {
      CHECK(std::isinf(ref::scaled_contact_duration(ContactEnd::elastic_force_zero, row.zeta)));
      CHECK(ref::restitution(ContactEnd::elastic_force_zero, row.zeta) == 0.0);
    } else {
      CHECK_THAT(ref::scaled_contact_duration(ContactEnd::elastic_force_zero, row.zeta),
                 WithinAbs(row.tc_a, 1e-10));
    }
  }
  // Named exact values of the table.
  CHECK_THAT(ref::restitution(ContactEnd::elastic_force_zero, 1.0 / std::numbers::sqrt2),
             WithinRel(std::exp(-std::numbers::pi), 1e-14));
  CHECK_THAT(ref::restitution(ContactEnd::total_force_zero, 1.0 / std::numbers::sqrt2),
             WithinRel(std::exp(-std::numbers::pi / 2.0), 1e-14));
  CHECK_THAT(ref::restitution(ContactEnd::total_force_zero, 1.0), WithinRel(std::exp(-2.0), 1e-15));
}

TEST_CASE("impact: convention B equals the branch formulas of refs §1.2", "[impact]") {
  for (double zeta : {0.0, 0.05, 0.3, 0.6, 0.7, 1.0 / std::numbers::sqrt2, 0.71, 0.9, 0.999, 1.0,
                      1.001, 1.3, 4.0, 50.0}) {
    CAPTURE(zeta);
    const double tc = spec_branch_duration_b(zeta);
    CHECK_THAT(ref::scaled_contact_duration(ContactEnd::total_force_zero, zeta),
               WithinRel(tc, 1e-12));
    CHECK_THAT(ref::restitution(ContactEnd::total_force_zero, zeta),
               WithinRel(std::exp(-zeta * tc), 1e-12));
    CHECK(ref::restitution(ContactEnd::total_force_zero, zeta) > 0.0);  // e_B > 0 for every zeta
    CHECK(ref::restitution(ContactEnd::total_force_zero, zeta) >=
          ref::restitution(ContactEnd::elastic_force_zero, zeta));
  }
}

TEST_CASE("impact: closed forms against Odeint event detection to 1e-10", "[impact][odeint]") {
  const double w0 = 40.0;
  const double v0 = 0.7;
  const auto zeta = GENERATE(0.0, 0.05, 0.1, 0.3, 0.5, 0.7, 1.0 / std::numbers::sqrt2, 0.9, 0.99,
                             1.0, 1.2, std::numbers::sqrt2, 2.0, 5.0);
  const auto o = make(w0, zeta);
  for (const auto end : {ContactEnd::elastic_force_zero, ContactEnd::total_force_zero}) {
    CAPTURE(zeta, end == ContactEnd::elastic_force_zero ? "A" : "B");
    const auto numeric = ref::impact_odeint(end, o, v0);
    const double tc = ref::contact_duration(end, o);
    const double e = ref::restitution(end, zeta);
    if (std::isinf(tc)) {
      CHECK(std::isinf(numeric.duration));
      CHECK(numeric.restitution == 0.0);
    } else {
      CHECK_THAT(numeric.duration, WithinRel(tc, 1e-10));
      CHECK_THAT(numeric.restitution, WithinAbs(e, 1e-10 * std::max(e, 1e-3)));
    }
    const auto maximum = ref::maximum_overlap(o, v0);
    CHECK_THAT(numeric.maximum_overlap, WithinRel(maximum.overlap, 1e-10));
    CHECK_THAT(numeric.time_of_maximum_overlap, WithinRel(maximum.time, 1e-10));
  }
}

TEST_CASE("impact: the end conditions hold on the oscillator closed form", "[impact]") {
  const double w0 = 3.0;
  const double v0 = 2.0;
  for (double zeta : {0.0, 0.2, 0.6, 0.95}) {
    CAPTURE(zeta);
    const auto o = make(w0, zeta);
    {  // A: x(t_c) = 0 and x'(t_c) = -e_A v0
      const auto s = ref::oscillator_state(
          o, {0.0, v0}, ref::contact_duration(ContactEnd::elastic_force_zero, o));
      CHECK_THAT(s.position, WithinAbs(0.0, 1e-14));
      CHECK_THAT(s.velocity,
                 WithinAbs(-v0 * ref::restitution(ContactEnd::elastic_force_zero, zeta), 1e-14));
    }
  }
  for (double zeta : {0.0, 0.2, 0.6, 0.95, 1.0, 1.7, 3.0}) {
    CAPTURE(zeta);
    const auto o = make(w0, zeta);
    // B: K x + eta x' = 0 at t_c and x'(t_c) = -e_B v0; the overlap is still positive for zeta > 0.
    const auto s =
        ref::oscillator_state(o, {0.0, v0}, ref::contact_duration(ContactEnd::total_force_zero, o));
    CHECK_THAT(o.stiffness() * s.position + o.damping() * s.velocity,
               WithinAbs(0.0, 1e-13 * o.stiffness() * v0 / w0));
    CHECK_THAT(s.velocity,
               WithinAbs(-v0 * ref::restitution(ContactEnd::total_force_zero, zeta), 1e-14));
    if (zeta > 0.0) CHECK(s.position > 0.0);
  }
}

TEST_CASE("impact: maximum overlap", "[impact]") {
  const double w0 = 5.0;
  const double v0 = 1.5;
  CHECK_THAT(ref::maximum_overlap(make(w0, 0.0), v0).overlap, WithinRel(v0 / w0, 1e-15));
  CHECK_THAT(ref::maximum_overlap(make(w0, 0.0), v0).time,
             WithinRel(std::numbers::pi / (2.0 * w0), 1e-15));
  CHECK_THAT(ref::maximum_overlap(make(w0, 1.0), v0).overlap,
             WithinRel(v0 / (w0 * std::exp(1.0)), 1e-15));
  CHECK_THAT(ref::maximum_overlap(make(w0, 1.0), v0).time, WithinRel(1.0 / w0, 1e-15));
  for (double zeta : {0.1, 0.5, 1.0 - 1e-12, 1.0 + 1e-12, 2.0}) {
    CAPTURE(zeta);
    const auto o = make(w0, zeta);
    const auto m = ref::maximum_overlap(o, v0);
    // x' = 0 at t_m, x(t_m) = x_max, and x_max = (v0/omega0) sqrt(e_B).
    const auto s = ref::oscillator_state(o, {0.0, v0}, m.time);
    CHECK_THAT(s.velocity, WithinAbs(0.0, 1e-14));
    CHECK_THAT(s.position, WithinRel(m.overlap, 1e-14));
    CHECK_THAT(m.overlap,
               WithinRel(v0 / w0 * std::sqrt(ref::restitution(ContactEnd::total_force_zero, zeta)),
                         1e-14));
  }
}

TEST_CASE("impact: Kiyama's Table 2 contacts are critically damped (refs §1.3, §1.7)", "[impact]") {
  const double rho_g = 2650.0 * 9.80665;                     // N/m^3
  const double m = 2650.0 * std::numbers::pi * 0.01 * 0.01;  // disk, kg per m of thickness
  const double k = 364.0 * rho_g;                            // K_n/rho g = 3.64e4 cm
  const double eta = 0.153 * rho_g;  // eta_n/rho g = 15.3 cm s (after 1/sqrt 2)
  const ref::Oscillator disk_disk(m / 2.0, k, eta);
  const ref::Oscillator disk_wall(m, 2.0 * k, 2.0 * eta);
  CHECK_THAT(m, WithinRel(0.832522, 1e-6));
  CHECK_THAT(k, WithinRel(9.4595e6, 1e-4));
  CHECK_THAT(disk_disk.natural_frequency(), WithinRel(4767.0, 1e-4));
  CHECK_THAT(disk_wall.natural_frequency(), WithinRel(4767.0, 1e-4));
  CHECK_THAT(disk_disk.damping_ratio(), WithinAbs(1.0019, 1e-4));
  CHECK_THAT(disk_wall.damping_ratio(), WithinAbs(1.0019, 1e-4));
  CHECK(ref::restitution(ContactEnd::elastic_force_zero, disk_disk.damping_ratio()) == 0.0);
  CHECK_THAT(ref::restitution(ContactEnd::total_force_zero, 1.0), WithinAbs(0.135, 5e-4));
}

TEST_CASE("impact: bad input is rejected", "[impact]") {
  const auto o = make(1.0, 0.3);
  CHECK_THROWS_AS(ref::restitution(ContactEnd::elastic_force_zero, -0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::restitution(ContactEnd::total_force_zero, std::nan("")),
                  std::invalid_argument);
  CHECK_THROWS_AS(ref::scaled_contact_duration(ContactEnd::total_force_zero, -1.0),
                  std::invalid_argument);
  CHECK_THROWS_AS(ref::maximum_overlap(o, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::maximum_overlap(o, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::impact_odeint(ContactEnd::elastic_force_zero, o, -1.0),
                  std::invalid_argument);
  CHECK_THROWS_AS(ref::impact_odeint(ContactEnd::elastic_force_zero, o, 1.0, 0.0),
                  std::invalid_argument);
}
