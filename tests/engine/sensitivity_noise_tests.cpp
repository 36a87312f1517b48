// The noise split of replicated samples and the noise-corrected Sobol' estimators
// (verification/engine/sensitivity_noise.hpp, sensitivity_estimators.hpp), and Borgonovo's δ estimator
// (sensitivity_delta.hpp) on cases with known answers.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "engine/sensitivity_delta.hpp"
#include "engine/sensitivity_noise.hpp"

using namespace ver::sens;

TEST_CASE("noise_split recovers a known noise fraction from replicated samples", "[sensitivity][noise]") {
  // y = effect + noise: effect ~ N(0, 4), noise ~ N(0, 1), R = 3 → φ = 1/(4 + 1) = 0.2.
  const std::size_t n = 20000, r = 3;
  std::vector<double> means(n), within(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double effect = 2.0 * standard_normal_draw(11, k);
    double m = 0.0, m2 = 0.0;
    for (std::size_t j = 0; j < r; ++j) {
      const double y = effect + standard_normal_draw(12, k * r + j);
      m += y;
      m2 += y * y;
    }
    means[k] = m / r;
    within[k] = (m2 - m * m / r) / (r - 1.0);
  }
  const NoiseSplit s = noise_split(means, within, r, 200);
  CHECK(std::abs(s.fraction.estimate - 0.2) < 0.01);
  CHECK(s.fraction.low <= 0.2);
  CHECK(s.fraction.high >= 0.2);
  CHECK(std::abs(s.effect_var - 4.0) < 0.15);
  CHECK(std::abs(s.noise_var - 1.0) < 0.03);
}

TEST_CASE("borgonovo_delta of an inert input is near 0 and of the only input large", "[sensitivity][delta]") {
  // y = x1 (x2 inert), x ~ U(0, 1) from the generator: δ_1 = ½ E ∫ |f_Y − δ(y − x1)| = 1 in theory; the
  // kernel estimate of a class of width 1/M gives much less but far above the inert input's.
  const std::size_t n = 4000;
  std::vector<std::vector<double>> x(2, std::vector<double>(n));
  std::vector<double> y(n);
  for (std::size_t j = 0; j < n; ++j) {
    x[0][j] = 0.5 + 0.1 * standard_normal_draw(21, j);
    x[1][j] = standard_normal_draw(22, j);
    y[j] = x[0][j];
  }
  const auto d = borgonovo_delta(x, y, 20);
  CHECK(d[0].estimate > 0.6);
  CHECK(std::abs(d[1].estimate) < 0.05);
}
