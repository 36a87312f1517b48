// Morris statistics where σ is not zero, by hand (verification/engine/sensitivity_estimators.hpp): the
// bilinear model f = x₁x₂ in unit coordinates has the elementary effects EE₁ = x₂ (at the point where x₁
// moves) and EE₂ = x₁. Three trajectories move x₁ from 0 to 2/3 at x₂ = 0, 1/3, 1, then x₂ at x₁ = 2/3:
// EE₁ = {0, 1/3, 1}: μ = μ* = 4/9, σ = √(7/27) (sample sd, r − 1); EE₂ = 2/3 three times: σ = 0.
// The bootstrap of three effects has a discrete distribution (27 equally likely draws): the mean is 0
// with probability 1/27, 1/9 with 3/27, ..., 7/9 with 3/27, 1 with 1/27, so its percentile interval
// is exact: [0, 1] at 95 % (1/27 = 3.7 % > 2.5 % at each end) and [1/9, 7/9] at 90 %; σ of a draw is 0
// when all three are equal (3/27), so σ's 95 % interval starts at 0. Planted bugs that turned this red:
// σ with 1/n instead of 1/(n − 1); the interval's ends taken at q and 1 − q swapped (lo = 0.5(1 + c)).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "engine/sensitivity_estimators.hpp"
#include "engine/sensitivity_sampling.hpp"

using namespace ver::sens;
using Catch::Matchers::WithinAbs;

namespace {

std::vector<MorrisTrajectory> bilinear_trajectories() {
  std::vector<MorrisTrajectory> tr;
  for (const double x2 : {0.0, 1.0 / 3.0, 1.0}) {
    const double x2_next = x2 < 0.5 ? x2 + 2.0 / 3.0 : x2 - 2.0 / 3.0;
    tr.push_back({{{0.0, x2}, {2.0 / 3.0, x2}, {2.0 / 3.0, x2_next}}, {0, 1}});
  }
  return tr;
}

}  // namespace

TEST_CASE("Morris sigma of f = x1 x2 and its exact bootstrap quantiles", "[sensitivity][morris]") {
  const std::vector<MorrisTrajectory> tr = bilinear_trajectories();
  std::vector<std::vector<double>> f;
  for (const auto& t : tr) {
    f.emplace_back();
    for (const auto& p : t.points) f.back().push_back(p[0] * p[1]);
  }
  constexpr double tol = 1e-14;
  for (const double confidence : {0.95, 0.9}) {
    CAPTURE(confidence);
    const MorrisEffects m = morris_effects(tr, f, 2, 20000, confidence);
    CHECK(m.effects[0] == 3);
    CHECK_THAT(m.mu[0], WithinAbs(4.0 / 9.0, tol));
    CHECK_THAT(m.mu_star[0], WithinAbs(4.0 / 9.0, tol));
    CHECK_THAT(m.sigma[0], WithinAbs(std::sqrt(7.0 / 27.0), tol));
    CHECK_THAT(m.mu[1], WithinAbs(2.0 / 3.0, tol));
    CHECK_THAT(m.sigma[1], WithinAbs(0.0, tol));
    // the percentile interval of μ (and μ*: the effects are ≥ 0) at the exact quantiles of the bootstrap
    const double low = confidence == 0.95 ? 0.0 : 1.0 / 9.0, high = confidence == 0.95 ? 1.0 : 7.0 / 9.0;
    for (const Interval& iv : {m.mu_ci[0], m.mu_star_ci[0]}) {
      CHECK_THAT(iv.low, WithinAbs(low, tol));
      CHECK_THAT(iv.high, WithinAbs(high, tol));
    }
    CHECK_THAT(m.sigma_ci[0].low, WithinAbs(0.0, tol));
    // σ of a draw is largest for {0, 1, 1} or {0, 0, 1}: 1/√3 (probability 6/27 > 2.5 %)
    CHECK_THAT(m.sigma_ci[0].high, WithinAbs(1.0 / std::sqrt(3.0), tol));
    CHECK_THAT(m.mu_ci[1].low, WithinAbs(2.0 / 3.0, tol));  // identical effects: a point interval
    CHECK_THAT(m.mu_ci[1].high, WithinAbs(2.0 / 3.0, tol));
  }
}
