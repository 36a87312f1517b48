#pragma once
// Borgonovo's moment-independent index δ_i of the Ishigami function f = sin x1 + a sin² x2 + b x3⁴ sin x1,
// x_i ~ U[−π, π] independent (Borgonovo 2007, Reliab. Eng. Syst. Saf. 92, 771–784):
//   δ_i = ½ E_{x_i} ∫ |f_Y(y) − f_{Y|x_i}(y)| dy,
// computed here from cumulative distribution functions only, without densities (which are singular):
// ½ ∫ |f − g| dy is the total variation of F − G, approached from below by Σ_k |ΔF_k − ΔG_k| on a grid
// of y. Every CDF is an expectation of a closed-form CDF over the remaining inputs:
//   P(sin x1 ≤ t) = ½ + asin(t)/π (|t| ≤ 1),   P(a sin² x2 ≤ w) = (2/π) asin √(w/a) (0 ≤ w ≤ a),
//   F_{Y|x1}(y) = E_{x3} P(a sin² x2 ≤ y − sin x1 (1 + b x3⁴)),
//   F_{Y|x2}(y) = E_{x3} P(sin x1 ≤ (y − a sin² x2)/(1 + b x3⁴)),
//   F_{Y|x3}(y) = E_{x2} P(sin x1 ≤ (y − a sin² x2)/(1 + b x3⁴)),
// and F_Y = E_{x_i} F_{Y|x_i}, with the midpoint rule on `nodes` points over each remaining input (using
// sin x1 ~ sin of U[−π/2, π/2], sin² x2 ~ sin² of U[0, π/2], x3⁴ ~ x3⁴ of U[0, π]) and `grid` cells of y
// over [min f, max f]. Accuracy: the change from (nodes, grid) to (2 nodes, 2 grid) is the error
// estimate (tests/reference).
#include <array>

namespace ref {

/// δ_1, δ_2, δ_3 of the Ishigami function with coefficients a > 0, b >= 0.
std::array<double, 3> ishigami_delta(double a, double b, int nodes = 400, int grid = 4000);

}  // namespace ref
