#pragma once
// Estimators of the sensitivity studies (sensitivity.hpp), on model outputs at the samplers' points
// (sensitivity_sampling.hpp). Outputs that are missing (a failed run) are passed as NaN: the Sobol'
// estimators drop every row j where f(A_j), f(B_j) or f(AB_i,j) is missing, Morris drops the
// elementary effects that touch a missing point; the counts are reported.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/sensitivity_sampling.hpp"

namespace ver::sens {

struct Interval {
  double estimate = 0.0, low = 0.0, high = 0.0;  // the estimate and its bootstrap percentile interval
};

struct SobolIndices {
  std::vector<Interval> first, total;  // per parameter
  std::vector<Interval> first_janon;   // per parameter: the first order by Janon et al. (below)
  double variance = 0.0;               // Var Y over A ∪ B
  std::size_t rows_used = 0;           // rows with every output available
};

/// First-order index (Saltelli et al. 2010, Table 2 (b)):  S_i  = mean_j f(B)_j (f(AB_i)_j − f(A)_j) / V
/// Total index (Jansen 1999; Saltelli et al. 2010, Table 2 (f)): S_Ti = mean_j (f(A)_j − f(AB_i)_j)² / (2 V)
/// V = the variance of f over A and B together.
/// First order also by Janon, Klein, Lagnoux, Nodet & Prieur 2014 (ESAIM: P&S 18, 342–364),
/// with Y = f(B), Y^i = f(AB_i) (they share only x_i), m = mean_j (Y + Y^i)/2:
///   S_i = (mean_j Y Y^i − m²) / (mean_j (Y² + Y^i²)/2 − m²)
/// centred on the pair's own mean and normalised by the pair's own variance: asymptotically efficient
/// among such estimators, no uncentred f factor (Saltelli's first order for f = x: σ_∞² = 7.4, this: 0).
/// The bootstrap draws the same rows for all three estimators (the Saltelli/Jansen results do not change). Bootstrap: `resamples` draws of the rows with
/// replacement (std::mt19937_64, seed), percentile interval at `confidence` (e.g. 0.95).
/// Outputs that are means of R replicates with run-to-run noise: the variance of each row's mean that
/// the noise leaves (its replicates' unbiased variance / R) for A, B and each AB_i. Given, the
/// estimators are those of E[Y | x] (the effect without the noise): the noise is taken out of V
/// (mean of (σ²_A + σ²_B)/2), of Jansen's numerator (σ²_A + σ²_ABi per row) and of Janon's
/// denominator ((σ²_B + σ²_ABi)/2 per row); Saltelli's numerator is unbiased as it is.
struct MeanNoise {
  std::vector<double> a, b;
  std::vector<std::vector<double>> ab;
};

SobolIndices sobol_indices(const std::vector<double>& fa, const std::vector<double>& fb,
                           const std::vector<std::vector<double>>& fab, std::size_t resamples = 1000,
                           double confidence = 0.95, std::uint64_t seed = 12345, const MeanNoise* noise = nullptr);

/// The asymptotic standard deviations σ_∞ of √N (Ŝ_i − S_i) and √N (Ŝ_Ti − S_Ti) for N i.i.d. rows
/// (central limit theorem with the delta method for the ratio Ŝ = mean Z / V̂):
///   σ_∞² = Var_j[(Z_j − S W_j)] / V²,  W_j = ((f(A)_j − μ)² + (f(B)_j − μ)²) / 2,
///   Z_j = f(B)_j (f(AB_i)_j − f(A)_j) (first order), Z_j = (f(A)_j − f(AB_i)_j)² / 2 (Jansen total),
/// with S, μ, V estimated from the given rows (a large design gives the population values). The
/// percentile bootstrap over N rows estimates the same spread, so its interval is about
/// 2 z_{(1+c)/2} σ_∞ / √N wide (z = 1.96 at c = 0.95).
/// Janon's first order: σ_∞² = Var[(Y − m)(Y^i − m) − S ((Y − m)² + (Y^i − m)²)/2] / V_i² (their asymptotic normality result).
struct SobolAsymptoticSd {
  std::vector<double> first, total;  // σ_∞ per parameter
  std::vector<double> first_janon;   // σ_∞ of Janon's first order per parameter
};
SobolAsymptoticSd sobol_asymptotic_sd(const std::vector<double>& fa, const std::vector<double>& fb,
                                      const std::vector<std::vector<double>>& fab);

/// The standard normal quantile z with Φ(z) = p (0 < p < 1): Acklam's approximation and one Halley step (round-off).
double normal_quantile(double p);

/// The q-quantile of v (0 ≤ q ≤ 1) between its order statistics: position q (n − 1) of the sorted values,
/// linear between the two around it (Hyndman & Fan's type 7). The bootstrap percentile intervals use it.
double percentile(std::vector<double> v, double q);

struct MorrisEffects {
  std::vector<double> mu, mu_star, sigma;  // per parameter: mean, mean |EE|, standard deviation (r − 1)
  std::vector<std::size_t> effects;        // elementary effects used per parameter
  /// Bootstrap of each parameter's elementary effects (drawn with replacement, `resamples` times):
  /// percentile intervals of μ*, μ and σ (estimate = the value above), and SALib's μ*_conf, the
  /// half-width z_{(1+c)/2} × the bootstrap standard deviation of μ* (SALib morris.analyze).
  std::vector<Interval> mu_star_ci, mu_ci, sigma_ci;
  std::vector<double> mu_star_conf;
};

/// Elementary effects EE_i = (f(x + Δ e_i) − f(x)) / (±Δ) in unit coordinates (Morris 1991), μ*
/// (Campolongo et al. 2007), σ; f[t][k] is the output at point k of trajectory t. Bootstrap as above
/// (std::mt19937_64, seed; resamples = 0: intervals of zero width).
MorrisEffects morris_effects(const std::vector<MorrisTrajectory>& tr, const std::vector<std::vector<double>>& f,
                             std::size_t d, std::size_t resamples = 1000, double confidence = 0.95, std::uint64_t seed = 12345);

}  // namespace ver::sens
