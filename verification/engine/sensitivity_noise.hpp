#pragma once
// Run-to-run noise against parameter effect (issue 36). With R replicates per sample (each sample run
// R times, its outputs the mean), an output's variance splits into
//   σ²_noise = mean_k s²_k                         (s²_k: the unbiased variance of sample k's replicates)
//   V_effect = Var_k ȳ_k − σ²_noise / R            (the variance of the means less the noise left in them)
// and the noise fraction of a single run, φ = σ²_noise / (V_effect + σ²_noise): 0 for a deterministic
// model, 1 when the parameters do nothing. Each is unbiased for independent samples from the inputs'
// distribution (Sobol': the rows of A and B) whatever the noise's distribution; the interval is a
// percentile bootstrap over the samples.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/sensitivity_estimators.hpp"

namespace ver::sens {

struct NoiseSplit {
  double noise_var = 0.0, effect_var = 0.0;  // σ²_noise, V_effect (per single run)
  Interval fraction;                          // φ with its bootstrap interval
  Interval noise_sd;                          // σ_noise with its bootstrap interval
  std::size_t samples = 0, replicates = 0;
};

/// The split over the samples whose mean and within-sample variance are both finite.
NoiseSplit noise_split(const std::vector<double>& means, const std::vector<double>& within_var, std::size_t replicates,
                       std::size_t resamples = 1000, double confidence = 0.95, std::uint64_t seed = 12345);

/// A standard normal draw that depends only on (seed, k): SplitMix64 of both, Box–Muller (the test
/// functions' noise; the same numbers on every platform, unlike std::normal_distribution).
double standard_normal_draw(std::uint64_t seed, std::uint64_t k);

}  // namespace ver::sens
