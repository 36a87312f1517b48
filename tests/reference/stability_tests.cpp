// Unit tests of ref/stability.hpp: the tables of refs §1.5 and §1.7, closed forms against spectral
// bisection, the matrices against the cycle of refs §1.4, long runs of that cycle, and the
// modified-equation damping.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "ref/stability.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using ref::Scheme;

namespace {

// The cycle of refs §1.4 for one contact (m = 1, omega0 = 1, dt = W, F_ext = 0, e_k = K x_k),
// written directly from K6-K19 rather than from the matrices.
struct Cycle {
  double x;   // x_k
  double dx;  // dx_k
  double v;   // v_{k-1}
};

Cycle step(Scheme scheme, Cycle c, double W, double zeta) {
  const double k = 1.0;
  const double m = 1.0;
  const double eta = 2.0 * zeta;  // 2 zeta sqrt(m K)
  const double dt = W;
  const double e = k * c.x;          // (K6.a, K7.a)
  const double d = eta * c.dx / dt;  // (K6.b, K7.b)
  const double f = -(e + d);
  const double v = c.v + dt * f / m;                                              // (K17)
  const double dx_next = scheme == Scheme::K18 ? v * dt : 0.5 * (c.dx + v * dt);  // (K18) / (K19)
  return {c.x + dx_next, dx_next, v};
}

// Largest |x| over the last 10 % of n steps of the cycle started from x = 1 at rest.
double late_amplitude(Scheme scheme, double W, double zeta, long n) {
  Cycle c{1.0, 0.0, 0.0};
  double amplitude = 0.0;
  for (long i = 0; i < n; ++i) {
    c = step(scheme, c, W, zeta);
    if (!std::isfinite(c.x)) return HUGE_VAL;
    if (i >= n - n / 10) amplitude = std::max(amplitude, std::abs(c.x));
  }
  return amplitude;
}

}  // namespace

TEST_CASE("stability: closed-form limits reproduce refs §1.5", "[stability]") {
  const double s2 = std::numbers::sqrt2;
  const std::vector<std::pair<double, double>> k18{
      {0.0, 2.0},           {0.1, 1.809975}, {0.3, 1.488061}, {0.5, 1.236068},
      {1.0 / s2, 1.035276}, {1.0, 0.828427}, {s2, 0.635674},  {2.0, 0.472136}};
  for (const auto& [zeta, limit] : k18) {
    CAPTURE(zeta);
    CHECK_THAT(ref::stability_limit(Scheme::K18, zeta), WithinAbs(limit, 1e-6));
  }
  const std::vector<std::pair<double, double>> k19{{0.0, 0.0},     {0.1, 0.2},     {0.3, 0.6},
                                                   {0.5, 1.0},     {0.7, 1.4},     {1.0, 2.0},
                                                   {s2, 1.643709}, {2.0, 1.291503}};
  for (const auto& [zeta, limit] : k19) {
    CAPTURE(zeta);
    CHECK_THAT(ref::stability_limit(Scheme::K19, zeta), WithinAbs(limit, 1e-6));
  }
  // K21 corrected: undamped K18 limit dt = 2 sqrt(m/K).
  CHECK(ref::stability_limit(Scheme::K18, 0.0) == 2.0);
  // At zeta = 1, K19 allows a 2.4x larger step than K18.
  CHECK_THAT(ref::stability_limit(Scheme::K19, 1.0) / ref::stability_limit(Scheme::K18, 1.0),
             WithinAbs(2.414, 1e-3));
}

TEST_CASE("stability: closed forms equal the spectral-radius bisection to 1e-6", "[stability]") {
  for (double zeta = 0.0; zeta <= 4.0; zeta += 0.05) {
    CAPTURE(zeta);
    CHECK_THAT(ref::stability_limit_spectral(Scheme::K18, zeta),
               WithinAbs(ref::stability_limit(Scheme::K18, zeta), 1e-6));
    if (zeta > 0.0) {
      CHECK_THAT(ref::stability_limit_spectral(Scheme::K19, zeta),
                 WithinAbs(ref::stability_limit(Scheme::K19, zeta), 1e-6));
    }
  }
  for (double zeta : {1.0 / std::numbers::sqrt2, 1.0, std::numbers::sqrt2}) {
    CHECK_THAT(ref::stability_limit_spectral(Scheme::K18, zeta),
               WithinAbs(ref::stability_limit(Scheme::K18, zeta), 1e-6));
    CHECK_THAT(ref::stability_limit_spectral(Scheme::K19, zeta),
               WithinAbs(ref::stability_limit(Scheme::K19, zeta), 1e-6));
  }
  // Undamped K19 is unstable for every step: the limit is 0 (resolved to the near-defective pair).
  CHECK(ref::stability_limit_spectral(Scheme::K19, 0.0) < 1e-5);
  for (double W : {1e-3, 0.01, 0.1, 1.0, 3.0})
    CHECK(ref::spectral_radius(ref::amplification_matrix_K19(W, 0.0)) > 1.0);
}

TEST_CASE("stability: the stable set is the interval below the limit", "[stability]") {
  for (double zeta : {0.05, 0.3, 1.0, 2.5}) {
    for (const auto scheme : {Scheme::K18, Scheme::K19}) {
      const double limit = ref::stability_limit(scheme, zeta);
      for (double fraction = 0.02; fraction < 2.0; fraction += 0.02) {
        const double W = fraction * limit;
        if (W >= 4.0 || std::abs(fraction - 1.0) < 1e-9) continue;
        CAPTURE(zeta, scheme == Scheme::K18 ? "K18" : "K19", fraction);
        const double radius = ref::spectral_radius(ref::amplification_matrix(scheme, W, zeta));
        if (fraction < 1.0)
          CHECK(radius < 1.0);
        else
          CHECK(radius > 1.0);
      }
    }
  }
}

TEST_CASE("stability: the matrices of refs §1.5 are one step of the cycle of refs §1.4",
          "[stability]") {
  const double W = 0.37;
  const double zeta = 0.6;
  const Cycle c{0.8, -0.3, 0.45};
  {
    // K18: state (x_k, p_{k-1}) with p = v dt; the cycle needs dx_k = p_{k-1}.
    const Cycle k18{c.x, c.v * W, c.v};
    const Cycle next = step(Scheme::K18, k18, W, zeta);
    const Eigen::Vector2d y =
        ref::amplification_matrix_K18(W, zeta) * Eigen::Vector2d(k18.x, k18.v * W);
    CHECK_THAT(y(0), WithinAbs(next.x, 1e-15));
    CHECK_THAT(y(1), WithinAbs(next.v * W, 1e-15));
  }
  {
    const Cycle next = step(Scheme::K19, c, W, zeta);
    const Eigen::Vector3d y =
        ref::amplification_matrix_K19(W, zeta) * Eigen::Vector3d(c.x, c.v * W, c.dx);
    CHECK_THAT(y(0), WithinAbs(next.x, 1e-15));
    CHECK_THAT(y(1), WithinAbs(next.v * W, 1e-15));
    CHECK_THAT(y(2), WithinAbs(next.dx, 1e-15));
  }
}

TEST_CASE("stability: characteristic polynomials of refs §1.5", "[stability]") {
  for (double W : {0.1, 0.9, 1.7}) {
    for (double zeta : {0.0, 0.4, 1.3}) {
      const Eigen::Matrix2d a = ref::amplification_matrix_K18(W, zeta);
      CHECK_THAT(a.trace(), WithinAbs(2.0 - W * W - 2.0 * zeta * W, 1e-14));
      CHECK_THAT(a.determinant(), WithinAbs(1.0 - 2.0 * zeta * W, 1e-14));
      const Eigen::Matrix3d b = ref::amplification_matrix_K19(W, zeta);
      const double minors = b(0, 0) * b(1, 1) - b(0, 1) * b(1, 0) + b(0, 0) * b(2, 2) -
                            b(0, 2) * b(2, 0) + b(1, 1) * b(2, 2) - b(1, 2) * b(2, 1);
      CHECK_THAT(b.trace(), WithinAbs(2.5 - W * W / 2.0 - zeta * W, 1e-14));
      CHECK_THAT(minors, WithinAbs(2.0 - zeta * W, 1e-14));
      CHECK_THAT(b.determinant(), WithinAbs(0.5, 1e-14));
    }
  }
}

TEST_CASE("stability: 1000 periods of the cycle stay bounded below the limit and blow up above it",
          "[stability]") {
  for (double zeta : {0.1, 0.5, 1.0, 2.0}) {
    for (const auto scheme : {Scheme::K18, Scheme::K19}) {
      const double limit = ref::stability_limit(scheme, zeta);
      CAPTURE(zeta, scheme == Scheme::K18 ? "K18" : "K19");
      const auto steps = [](double W) {
        return static_cast<long>(1000.0 * 2.0 * std::numbers::pi / W);
      };
      CHECK(late_amplitude(scheme, 0.97 * limit, zeta, steps(0.97 * limit)) < 1.0);
      CHECK(late_amplitude(scheme, 1.03 * limit, zeta, steps(1.03 * limit)) > 1e6);
    }
  }
  // Undamped: K18 neither grows nor decays below W = 2; K19 grows at any step.
  CHECK(late_amplitude(Scheme::K18, 1.9, 0.0, 3307) < 20.0);
  CHECK(late_amplitude(Scheme::K18, 1.9, 0.0, 3307) > 0.5);
  CHECK(late_amplitude(Scheme::K19, 0.1, 0.0, 62832) > 1e6);
}

TEST_CASE("stability: limits in seconds (refs §1.7)", "[stability]") {
  {  // Kiyama Table 2, disk-disk contact: m/2 on K_n with eta_n/sqrt 2
    const double rho_g = 2650.0 * 9.80665;
    const double m = 2650.0 * std::numbers::pi * 1e-4;
    const ref::Oscillator contact(m / 2.0, 364.0 * rho_g, 0.153 * rho_g);
    CHECK_THAT(ref::stability_limit_time_step(Scheme::K18, contact), WithinRel(1.736e-4, 1e-3));
    CHECK_THAT(ref::stability_limit_time_step(Scheme::K19, contact), WithinRel(4.19e-4, 1e-3));
  }
  {  // Kiyama Table 1, first column: single mass on K_n, critical eta: 2/omega0 = eta/K = 5.933e-4
     // s
    const double rho_g = 2650.0 * 9.80665;
    const double m = 2650.0 * std::numbers::pi * 1e-4;
    const double k = 364.0 * rho_g;
    const ref::Oscillator contact(m, k, ref::critical_damping(m, k));
    CHECK_THAT(ref::stability_limit_time_step(Scheme::K19, contact), WithinRel(5.933e-4, 2e-4));
    CHECK_THAT(ref::kiyama_time_step_limit(k, ref::critical_damping(m, k)),
               WithinRel(5.933e-4, 2e-4));
  }
  {  // Matsui M-A: N K_n = 2 x 12 kN/mm, m = 67.1 g, h_n = 1
    const double k = 2.0 * 12e6;
    const double m = 0.0671;
    CHECK_THAT(std::sqrt(m / k), WithinRel(5.29e-5, 1e-3));
    const ref::Oscillator case1(m, k, ref::critical_damping(m, k));
    const ref::Oscillator case4(m, 100.0 * k, ref::critical_damping(m, 100.0 * k));
    CHECK_THAT(ref::stability_limit_time_step(Scheme::K18, case1), WithinRel(4.38e-5, 1e-3));
    CHECK_THAT(ref::stability_limit_time_step(Scheme::K18, case4), WithinRel(4.38e-6, 1e-3));
  }
  // For zeta <= 1 the K19 limit is Kiyama's dt < eta/K (K26).
  for (double zeta : {0.1, 0.5, 1.0}) {
    const ref::Oscillator o(3.0, 5.0, 2.0 * zeta * std::sqrt(15.0));
    CHECK_THAT(ref::stability_limit_time_step(Scheme::K19, o),
               WithinRel(ref::kiyama_time_step_limit(5.0, o.damping()), 1e-14));
  }
}

TEST_CASE("stability: modified-equation damping is the first-order decay of the spectral radius",
          "[stability]") {
  for (const auto scheme : {Scheme::K18, Scheme::K19}) {
    for (double zeta : {0.0, 0.1, 0.4, 0.8}) {
      if (scheme == Scheme::K18 && zeta == 0.0) continue;  // |lambda| = 1 exactly: nothing to fit
      CAPTURE(scheme == Scheme::K18 ? "K18" : "K19", zeta);
      const auto remainder = [&](double W) {
        const double decay =
            -std::log(ref::spectral_radius(ref::amplification_matrix(scheme, W, zeta))) / W;
        return decay - ref::numerical_damping_ratio(scheme, zeta, W);
      };
      // The remainder is O(W^2) (O(W^3) for K19 at zeta = 0): halving W divides it by >= 4.
      const double r1 = remainder(4e-3);
      const double r2 = remainder(2e-3);
      CHECK(std::abs(r1) < 10.0 * 4e-3 * 4e-3);
      CHECK(r1 / r2 > 3.9);
    }
  }
  // K19 undamped bounce: e = exp(pi W/2) = 1.003089 at W = pi/1600 (refs §1.5).
  const double W = std::numbers::pi / 1600.0;
  CHECK_THAT(std::exp(-std::numbers::pi * ref::numerical_damping_ratio(Scheme::K19, 0.0, W)),
             WithinAbs(1.003089, 1e-6));
}

TEST_CASE("stability: bad input is rejected", "[stability]") {
  CHECK_THROWS_AS(ref::stability_limit(Scheme::K18, -0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::stability_limit(Scheme::K19, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(ref::amplification_matrix_K18(-1.0, 0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::amplification_matrix_K19(0.1, -0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::stability_limit_spectral(Scheme::K18, 0.1, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::kiyama_time_step_limit(0.0, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::spectral_radius(Eigen::MatrixXd(2, 3)), std::invalid_argument);
}
