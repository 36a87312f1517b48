// Borgonovo's δ of the Ishigami function by quadrature of CDFs (reference/ref/ishigami_delta.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "ref/ishigami_delta.hpp"

TEST_CASE("ishigami_delta converges as the nodes and the y grid double", "[reference][sensitivity]") {
  // Measured: (100, 1000) 0.26345 0.42598 0.21273; (200, 2000) 0.26330 0.42541 0.21142;
  // (400, 4000) 0.26323 0.42512 0.21073. A Monte Carlo histogram (1e8 points, 100 classes × 200 bins)
  // gave 0.2577 0.4236 0.2072 (binning biases it low).
  const auto coarse = ref::ishigami_delta(7.0, 0.1, 100, 1000);
  const auto fine = ref::ishigami_delta(7.0, 0.1, 200, 2000);
  for (int i = 0; i < 3; ++i) CHECK(std::abs(coarse[i] - fine[i]) < 2e-3);
  CHECK(std::abs(fine[0] - 0.2633) < 1e-3);
  CHECK(std::abs(fine[1] - 0.4254) < 1e-3);
  CHECK(std::abs(fine[2] - 0.2114) < 1e-3);
}

TEST_CASE("ishigami_delta of x3 vanishes when b = 0 and of x1 with it", "[reference][sensitivity]") {
  // b = 0: f = sin x1 + a sin² x2 does not depend on x3 (δ_3 = 0 exactly: every conditional CDF is F_Y).
  const auto d = ref::ishigami_delta(7.0, 0.0, 100, 1000);
  CHECK(std::abs(d[2]) < 1e-12);
  CHECK(d[0] > 0.05);
  CHECK(d[1] > 0.2);
}

TEST_CASE("ishigami_delta refuses bad coefficients", "[reference][sensitivity]") {
  CHECK_THROWS_AS(ref::ishigami_delta(0.0, 0.1), std::invalid_argument);
  CHECK_THROWS_AS(ref::ishigami_delta(7.0, -0.1), std::invalid_argument);
}
