#pragma once
// Borgonovo's moment-independent index δ_i = ½ E_{x_i} ∫ |f_Y(y) − f_{Y|x_i}(y)| dy (Borgonovo 2007),
// estimated from a given sample (x, y) as Plischke, Borgonovo & Smith 2013 do (and SALib's `delta`):
// the points are split into M classes of equal size by the rank of x_i, M = min(⌈N^(2/(7 + tanh((1500 − N)/500)))⌉, 48);
// f_Y and each class's f_{Y|class} are Gaussian kernel density estimates (Silverman's bandwidth,
// σ̂ (3n/4)^(−1/5)) on 100 points spanning [min y, max y]; δ̂_i = Σ_classes (n_c / 2N) ∫ |f_Y − f_c| dy
// (trapezoid rule). Bias reduction (their eq. 30): the estimate is the mean of 2 δ̂ − δ̂_b over
// `resamples` bootstrap draws of the points, its interval the percentiles of those values.
// Any output, smooth or not (a discharge with arches): δ depends on the whole distribution, not on
// the variance alone. The kernel smoothing biases δ̂ low where the densities have sharp features
// (Ishigami: docs/findings.md).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/sensitivity_estimators.hpp"

namespace ver::sens {

/// δ_i with its interval for each input; x[i][j]: input i at point j (any monotone scale: ranks only),
/// y[j]: the output (points with a non-finite y are dropped).
/// The same δ_i by histograms instead of kernels (this project's, findings F15): the same M classes by
/// rank; f_Y and each class's distribution as frequencies in K = 2⌈√(N/M)⌉ equal cells of [min y, max y];
/// δ̂_i = Σ_classes (n_c / 2N) Σ_cells |p_c − p|, the total variation of the two CDFs on the cells (no
/// smoothing of sharp features; the frequencies' noise biases it up, the cells down); bias reduction and
/// interval as above. Ishigami: within 0.03 of the quadrature δ at 8192 points.
std::vector<Interval> histogram_delta(const std::vector<std::vector<double>>& x, const std::vector<double>& y, std::size_t resamples = 100,
                                      double confidence = 0.95, std::uint64_t seed = 12345);

std::vector<Interval> borgonovo_delta(const std::vector<std::vector<double>>& x, const std::vector<double>& y, std::size_t resamples = 100,
                                      double confidence = 0.95, std::uint64_t seed = 12345);

}  // namespace ver::sens
