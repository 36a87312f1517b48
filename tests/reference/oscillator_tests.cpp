// Unit tests of ref/oscillator.hpp: closed form against independent expressions of refs §1.1 and
// against Boost.Odeint, the restitution inverse, and input validation.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ref/impact.hpp"
#include "ref/oscillator.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// An oscillator with omega0 = w0 and the given damping ratio (m = 2 kg, so not all ones).
ref::Oscillator make(double w0, double zeta) {
  const double m = 2.0;
  const double k = m * w0 * w0;
  return ref::Oscillator(m, k, 2.0 * zeta * std::sqrt(m * k));
}

}  // namespace

TEST_CASE("oscillator: construction validates and derives omega0 and zeta", "[oscillator]") {
  const ref::Oscillator o(0.832522, 9.4595e6, 3976.0);
  CHECK_THAT(o.natural_frequency(), WithinRel(std::sqrt(9.4595e6 / 0.832522), 1e-15));
  CHECK_THAT(o.damping_ratio(), WithinRel(3976.0 / (2.0 * std::sqrt(0.832522 * 9.4595e6)), 1e-15));

  CHECK_THROWS_AS(ref::Oscillator(-1.0, 1.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::Oscillator(0.0, 1.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::Oscillator(1.0, 0.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::Oscillator(1.0, 1.0, -1e-3), std::invalid_argument);
  CHECK_THROWS_AS(ref::Oscillator(std::nan(""), 1.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::Oscillator(1.0, HUGE_VAL, 0.0), std::invalid_argument);
  CHECK_THROWS_WITH(ref::Oscillator(-1.0, 1.0, 0.0), Catch::Contains("mass"));
}

TEST_CASE("oscillator: closed form equals the regime formulas of refs §1.1", "[oscillator]") {
  const double x0 = 0.3;
  const double v0 = -2.0;
  const double w0 = 3.0;
  for (double t : {0.0, 0.05, 0.7, 2.3, 9.1}) {
    CAPTURE(t);
    {  // undamped
      const auto s = ref::oscillator_state(make(w0, 0.0), {x0, v0}, t);
      CHECK_THAT(s.position, WithinAbs(x0 * std::cos(w0 * t) + v0 / w0 * std::sin(w0 * t), 1e-14));
      CHECK_THAT(s.velocity, WithinAbs(-x0 * w0 * std::sin(w0 * t) + v0 * std::cos(w0 * t), 1e-13));
    }
    {  // under-damped, zeta = 0.3
      const double zeta = 0.3;
      const double beta = zeta * w0;
      const double wd = w0 * std::sqrt(1.0 - zeta * zeta);
      const double x =
          std::exp(-beta * t) * (x0 * std::cos(wd * t) + (v0 + beta * x0) / wd * std::sin(wd * t));
      CHECK_THAT(ref::oscillator_state(make(w0, zeta), {x0, v0}, t).position, WithinAbs(x, 1e-14));
    }
    {  // critically damped
      const double x = (x0 + (v0 + w0 * x0) * t) * std::exp(-w0 * t);
      CHECK_THAT(ref::oscillator_state(make(w0, 1.0), {x0, v0}, t).position, WithinAbs(x, 1e-14));
    }
    {  // over-damped, zeta = 2
      const double zeta = 2.0;
      const double beta = zeta * w0;
      const double big_omega = w0 * std::sqrt(zeta * zeta - 1.0);
      const double s1 = -beta + big_omega;
      const double s2 = -beta - big_omega;
      const double c1 = (v0 - s2 * x0) / (s1 - s2);
      const double c2 = x0 - c1;
      const double x = c1 * std::exp(s1 * t) + c2 * std::exp(s2 * t);
      const double v = c1 * s1 * std::exp(s1 * t) + c2 * s2 * std::exp(s2 * t);
      const auto s = ref::oscillator_state(make(w0, zeta), {x0, v0}, t);
      CHECK_THAT(s.position, WithinAbs(x, 1e-14));
      CHECK_THAT(s.velocity, WithinAbs(v, 1e-13));
    }
  }
}

TEST_CASE("oscillator: closed form against Boost.Odeint to 1e-10, all regimes",
          "[oscillator][odeint]") {
  const double w0 = 7.0;
  const auto zeta = GENERATE(0.0, 0.1, 0.5, 1.0 / std::numbers::sqrt2, 0.999, 1.0 - 1e-9, 1.0,
                             1.0 + 1e-9, 1.001, 1.5, 3.0, 20.0);
  const auto o = make(w0, zeta);
  for (const ref::OscillatorState initial :
       {ref::OscillatorState{1.0, 0.0}, {0.0, 1.0}, {0.3, -2.0}}) {
    const double scale = std::max(std::abs(initial.position), std::abs(initial.velocity) / w0);
    for (double scaled_time : {0.1, 1.0, 5.0, 17.3, 50.0}) {
      const double t = scaled_time / w0;
      CAPTURE(zeta, initial.position, initial.velocity, scaled_time);
      const auto exact = ref::oscillator_state(o, initial, t);
      const auto numeric = ref::oscillator_state_odeint(o, initial, t);
      CHECK_THAT(numeric.position, WithinAbs(exact.position, 1e-10 * scale));
      CHECK_THAT(numeric.velocity, WithinAbs(exact.velocity, 1e-10 * scale * w0));
    }
  }
}

TEST_CASE("oscillator: continuous across zeta = 1 (no 0/0 in the near-critical branch)",
          "[oscillator]") {
  const double w0 = 2.0;
  const ref::OscillatorState initial{0.4, 1.3};
  for (double t : {0.01, 0.5, 1.0, 3.0, 10.0}) {
    const auto critical = ref::oscillator_state(make(w0, 1.0), initial, t);
    for (double offset : {1e-14, 1e-10, 1e-7}) {
      CAPTURE(t, offset);
      for (double zeta : {1.0 - offset, 1.0 + offset}) {
        const auto near = ref::oscillator_state(make(w0, zeta), initial, t);
        REQUIRE(std::isfinite(near.position));
        // d x / d zeta is O(t^2 e^{-w0 t}) times the scale: bounded by 10 here.
        CHECK_THAT(near.position, WithinAbs(critical.position, 10.0 * offset + 1e-15));
        CHECK_THAT(near.velocity, WithinAbs(critical.velocity, 10.0 * offset + 1e-15));
      }
    }
  }
}

TEST_CASE("oscillator: heavy damping and long times stay finite and decay", "[oscillator]") {
  const auto s = ref::oscillator_state(make(1.0, 1e4), {1.0, 0.0}, 1e3);
  CHECK(std::isfinite(s.position));
  // Slow root s1 ~ -1/(2 zeta): x ~ exp(-t/(2 zeta)) = exp(-0.05).
  CHECK_THAT(s.position, WithinRel(std::exp(-1e3 / (1e4 + std::sqrt(1e8 - 1.0))), 1e-6));
  const auto late = ref::oscillator_state(make(1.0, 0.5), {1.0, 1.0}, 1e4);
  CHECK(late.position == 0.0);
}

TEST_CASE("oscillator: zero time and zero state", "[oscillator]") {
  const auto o = make(5.0, 0.2);
  const auto s = ref::oscillator_state(o, {0.1, -0.2}, 0.0);
  CHECK(s.position == 0.1);
  CHECK(s.velocity == -0.2);
  const auto z = ref::oscillator_state_odeint(o, {0.0, 0.0}, 3.0);
  CHECK(z.position == 0.0);
  CHECK(z.velocity == 0.0);
}

TEST_CASE("oscillator: bad time or state is rejected", "[oscillator]") {
  const auto o = make(1.0, 0.1);
  CHECK_THROWS_AS(ref::oscillator_state(o, {0.0, 1.0}, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::oscillator_state(o, {std::nan(""), 1.0}, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::oscillator_state_odeint(o, {0.0, 1.0}, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::oscillator_state_odeint(o, {0.0, HUGE_VAL}, 1.0), std::invalid_argument);
}

TEST_CASE("oscillator: damping coefficient and critical damping", "[oscillator]") {
  CHECK_THAT(ref::damping_coefficient(4.0, 9.0, 0.5), WithinRel(6.0, 1e-15));
  CHECK_THAT(ref::critical_damping(4.0, 9.0), WithinRel(12.0, 1e-15));  // (K20)
  CHECK_THAT(ref::Oscillator(4.0, 9.0, ref::critical_damping(4.0, 9.0)).damping_ratio(),
             WithinRel(1.0, 1e-15));
  CHECK_THROWS_AS(ref::damping_coefficient(4.0, 9.0, -0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::critical_damping(-4.0, 9.0), std::invalid_argument);
}

TEST_CASE("oscillator: damping ratio from restitution, convention A (refs §1.2)", "[oscillator]") {
  // Rows of the refs §1.2 table.
  CHECK_THAT(ref::damping_ratio_for_restitution(0.7292476143), WithinAbs(0.1, 1e-10));
  CHECK_THAT(ref::damping_ratio_for_restitution(0.3723261049), WithinAbs(0.3, 1e-10));
  CHECK_THAT(ref::damping_ratio_for_restitution(0.1630335348), WithinAbs(0.5, 1e-9));
  CHECK_THAT(ref::damping_ratio_for_restitution(std::exp(-std::numbers::pi)),
             WithinAbs(1.0 / std::numbers::sqrt2, 1e-15));
  CHECK(ref::damping_ratio_for_restitution(1.0) == 0.0);
  CHECK(ref::damping_ratio_for_restitution(0.0) == 1.0);
  for (double zeta : {0.01, 0.2, 0.6, 0.9, 0.99}) {
    const double e = ref::restitution(ref::ContactEnd::elastic_force_zero, zeta);
    CHECK_THAT(ref::damping_ratio_for_restitution(e), WithinAbs(zeta, 1e-14));
  }
  CHECK_THROWS_AS(ref::damping_ratio_for_restitution(-0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::damping_ratio_for_restitution(1.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::damping_ratio_for_restitution(std::nan("")), std::invalid_argument);
}
