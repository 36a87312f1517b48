#pragma once
// A declared monotone transform of a sensitivity study's output before the Sobol' estimators
// (`[sobol] transform = "log" | "rank"`): the indices are then those of the TRANSFORMED output, a
// different quantity from the indices of the output itself (Sobol' indices are not invariant under a
// nonlinear transform), and are labelled so. A few far-out runs (heavy tails) set most of the variance
// of the output; ranks (or logarithms of a positive output) share it out among all runs.
//   log:  y → ln y (y <= 0 becomes missing: the row is dropped and counted);
//   rank: y → its rank among all finite outputs of the design (f(A), f(B), every f(AB_i) pooled),
//         1 … n, ties get their mean rank (Iman & Conover 1979; Saltelli & Sobol' 1995).
#include <string>
#include <vector>

namespace ver::sens {

enum class Transform { none, log, rank };

/// "none" | "log" | "rank"; anything else throws std::invalid_argument.
Transform parse_transform(const std::string& name);
std::string transform_name(Transform t);
/// How the transformed output of `output` reads in a title: "x_0.2", "ln(x_0.2)", "rank(x_0.2)".
std::string transformed_label(Transform t, const std::string& output);

/// Transforms f(A), f(B), each f(AB_i) and each f(BA_i) (second order; may be empty) in place,
/// ranks over all of them pooled (NaN stays NaN, see above).
void apply_transform(Transform t, std::vector<double>& fa, std::vector<double>& fb, std::vector<std::vector<double>>& fab,
                     std::vector<std::vector<double>>& fba);
inline void apply_transform(Transform t, std::vector<double>& fa, std::vector<double>& fb, std::vector<std::vector<double>>& fab) {
  std::vector<std::vector<double>> none;
  apply_transform(t, fa, fb, fab, none);
}

}  // namespace ver::sens
