// Exact values of two sensitivity helpers, by hand on tiny inputs (engine/sensitivity_estimators.hpp,
// sensitivity_functions.hpp). Planted bugs that turn these red: Janon's σ_∞ summed over one row past the
// end, and the linear function's second-order indices left unset (every second-order check of a linear
// study then reads an empty table).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "engine/sensitivity_estimators.hpp"
#include "engine/sensitivity_functions.hpp"

using namespace ver::sens;

TEST_CASE("Janon's asymptotic sd equals its formula on four rows", "[sensitivity]") {
  const std::vector<double> fa{1.0, 2.0, 4.0, 3.0}, fb{2.0, 5.0, 1.0, 3.0};
  const std::vector<std::vector<double>> fab{{3.0, 4.0, 1.5, 2.0}};
  const SobolAsymptoticSd sd = sobol_asymptotic_sd(fa, fb, fab);
  REQUIRE(sd.first_janon.size() == 1);
  // σ_∞ = sd(ψ) / V_i with Y = f(B), Y^i = f(AB_i), m their pooled mean, V_i their pooled variance,
  // S = Cov / V_i and ψ = (Y − m)(Y^i − m) − S ((Y − m)² + (Y^i − m)²)/2 (population moments, two passes)
  const std::vector<double>& y = fb;
  const std::vector<double>& yi = fab[0];
  double m = 0.0;
  for (int j = 0; j < 4; ++j) m += (y[j] + yi[j]) / 8.0;
  double cov = 0.0, v = 0.0;
  for (int j = 0; j < 4; ++j) cov += (y[j] - m) * (yi[j] - m) / 4.0, v += ((y[j] - m) * (y[j] - m) + (yi[j] - m) * (yi[j] - m)) / 8.0;
  const double s = cov / v;
  std::vector<double> psi;
  double mean = 0.0;
  for (int j = 0; j < 4; ++j) {
    psi.push_back((y[j] - m) * (yi[j] - m) - s * 0.5 * ((y[j] - m) * (y[j] - m) + (yi[j] - m) * (yi[j] - m)));
    mean += psi.back() / 4.0;
  }
  double var = 0.0;
  for (double p : psi) var += (p - mean) * (p - mean) / 4.0;
  CHECK(sd.first_janon[0] == Approx(std::sqrt(var) / v).epsilon(1e-12));
}

TEST_CASE("the linear function has no interactions: every second-order index is zero", "[sensitivity]") {
  const ExactIndices e = exact_indices({"linear", {1.0, 2.0, 3.0}}, {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  REQUIRE(e.second.size() == 3);
  for (const auto& row : e.second) {
    REQUIRE(row.size() == 3);
    for (double x : row) CHECK(x == 0.0);
  }
  CHECK(e.first[2] == Approx(9.0 / 14.0).epsilon(1e-15));  // c_i² / Σ c² with equal ranges
}
