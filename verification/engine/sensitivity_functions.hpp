#pragma once
// Test functions with known sensitivity indices: the function evaluator of the sensitivity studies
// (`function = "..."` instead of a case), which checks the samplers and estimators without the DEM.
//   ishigami(a, b):  f = sin x1 + a sin² x2 + b x3⁴ sin x1, x_i ~ U[−π, π]
//                    (Ishigami & Homma 1990; indices e.g. Saltelli et al. 2008, Global Sensitivity
//                    Analysis: The Primer, §4.7 / Sobol' & Levitan 1999)
//   g(a_1..a_d):     f = Π (|4 x_i − 2| + a_i) / (1 + a_i), x_i ~ U[0, 1]  (Sobol' 1993 / Saltelli & Sobol' 1995)
//   linear(c_1..c_d): f = Σ c_i x_i on any ranges: Morris effects EE_i = c_i (high_i − low_i) exactly
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace ver::sens {

struct TestFunction {
  std::string name;                // ishigami | g | linear
  std::vector<double> coefficients;  // ishigami: {a, b}; g: a_i; linear: c_i
};

/// f(x) with x the parameter values (physical units).
double evaluate(const TestFunction& f, const std::vector<double>& x);

/// The exact indices, where known (ranges as the definitions above; for linear: uniform ranges).
struct ExactIndices {
  std::vector<double> first, total;
  std::vector<double> morris_mu_star, morris_sigma;  // linear only; NaN for an input without an exact value
  /// second[i][j] (i < j): the closed second-order index S_ij = V_ij / V (Ishigami: only S_13 =
  /// 8 b² π⁸ / 225 / V; g: V_i V_j / V; linear: 0). Empty where unknown (ln f).
  std::vector<std::vector<double>> second;
  double variance = std::nan("");  // Var f over the inputs' distributions (NaN where unknown)
};
/// linear with `variances` (one per input, any distribution): S_i = S_Ti = c_i² Var x_i / Σ. Its Morris
/// values: an input whose value is linear in its unit coordinate (`linear_inputs[i]`: uniform, not integer;
/// empty: all) has every elementary effect c_i (high − low), μ* = |c_i| (high − low), σ = 0; so has one with
/// c_i = 0 (every effect 0); any other input's effects vary: NaN, no exact value.
ExactIndices exact_indices(const TestFunction& f, const std::vector<double>& low, const std::vector<double>& high,
                           const std::vector<double>& variances = {}, const std::vector<bool>& linear_inputs = {});

/// The exact indices of ln f where known: the g-function with every a_i > 0, whose logarithm
/// ln g = Σ ln(|4 x_i − 2| + a_i) − ln(1 + a_i) is additive, so S_i = S_Ti = V_i / Σ V_j with
/// V_i = Var ln(t), t ~ U[a_i, a_i + 2] (closed form: ∫ ln t = t ln t − t, ∫ ln² t = t ln² t − 2 t ln t + 2 t).
/// Empty for the other functions (ln of a function that changes sign is not defined).
ExactIndices exact_indices_of_log(const TestFunction& f);

/// How many inputs the function takes (0: any).
std::size_t dimension(const TestFunction& f);

}  // namespace ver::sens
