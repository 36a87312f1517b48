// Convergence analysis of a refinement sequence (h_k, Q_k), k = 0 (coarse) ... n-1 (fine).
//
// h is any step-size-like parameter (dt, 1/N, element size) that goes to zero under refinement; the
// ratios r_k = h_{k-1}/h_k need not be constant. With an exact reference Q* the errors are |Q_k -
// Q*|; without one they are taken against the Richardson extrapolation of the finest three levels.
//
// References:
//   [R]  P.J. Roache, "Perspective: a method for uniform reporting of grid refinement studies",
//        J. Fluids Eng. 116 (1994) 405-413 (GCI, safety factors 1.25 / 3.0, asymptotic check).
//   [C]  I.B. Celik et al., "Procedure for estimation and reporting of uncertainty due to
//        discretization in CFD applications", J. Fluids Eng. 130 (2008) 078001 (three-level order
//        for non-constant r, eqs. (3)-(5); extrapolation (6); GCI (8)).
// Missing values are std::optional; to_json writes them as null (never NaN).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace ver {

// How the analysis is done. Every member has a sensible default.
struct ConvergenceOptions {
  std::optional<double> reference;  // exact value Q*; absent: errors against Richardson
  std::optional<double>
      expected_order;  // theoretical order (reported, used by check_order and plots)
  std::optional<double> assumed_order;  // order for Richardson/GCI instead of the observed one
  std::vector<std::size_t> fit_levels;  // level indices used by the least-squares fit; empty = all
  double asymptotic_tolerance = 0.1;    // asymptotic iff |GCI ratio - 1| <= this
};

// Where the order used for Richardson extrapolation and the GCI came from.
enum class OrderSource { none, assumed, three_level, two_level_reference };

// Result of the analysis; the members named as in RESULT_FORMAT.md are written by to_json.
struct Series {
  std::string name;           // quantity, e.g. "e, zeta=0.3 (K18)"
  std::string parameter;      // refined parameter with unit, e.g. "dt [s]"
  std::vector<double> h;      // coarse -> fine, strictly decreasing
  std::vector<double> value;  // Q_k

  std::optional<double> reference;         // exact Q* if given
  bool errors_against_richardson = false;  // true when no reference was given

  std::vector<std::optional<double>> error;           // |Q_k - Q*| (or - Richardson)
  std::vector<std::optional<double>> relative_error;  // error / |Q*| (null if Q* == 0 or unknown)
  // From level k-1 to k; entry 0 is null. With a reference: two-level order from the errors;
  // without: three-level order of levels k-2, k-1, k [C] (entries 0 and 1 null).
  std::vector<std::optional<double>> observed_order;

  std::optional<double> fitted_order;          // least-squares slope of log e vs log h
  std::vector<std::size_t> fit_levels;         // levels actually used by the fit (e > 0)
  std::vector<std::size_t> zero_error_levels;  // levels skipped by the fit because e == 0

  std::optional<double> expected_order;
  std::optional<double> three_level_order;  // [C] from the finest three levels (independent of Q*)
  std::optional<double> extrapolation_order;  // order used for Richardson and GCI
  OrderSource extrapolation_order_source = OrderSource::none;

  std::optional<double> richardson;        // from the two finest levels
  std::optional<double> gci_fine;          // relative, finest pair [R]
  std::optional<double> gci_coarse;        // relative, next pair (three or more levels)
  std::optional<double> asymptotic_ratio;  // gci_coarse / (r^p gci_fine), r = finest ratio
  std::optional<bool> asymptotic;          // |ratio - 1| <= tolerance
  double safety_factor = 0.0;              // Fs: 1.25 with >= 3 levels, 3.0 with 2

  std::vector<std::string> notes;  // degenerate cases met, in words
};

// --- Building blocks (usable on their own) ------------------------------------------------------

// Two-level observed order p = ln(e_coarse/e_fine)/ln r; null if an error is zero or r <= 1.
std::optional<double> observed_order(double error_coarse, double error_fine, double ratio);

// Three-level observed order [C] (eqs. 3-5) from coarse, medium, fine levels (h3 > h2 > h1).
// Fixed-point iteration as in [C]; falls back to bisection if it does not converge. Null if
// the two differences vanish or the equation has no positive root.
std::optional<double> three_level_order(double h_coarse, double h_medium, double h_fine,
                                        double q_coarse, double q_medium, double q_fine);

// Least-squares slope of log(error) vs log(h) over the levels with error > 0 (null if < 2).
std::optional<double> fitted_order(const std::vector<double>& h, const std::vector<double>& error);

// Richardson extrapolation Q_fine + (Q_fine - Q_coarse)/(r^p - 1) [C eq. 6].
double richardson_extrapolation(double q_coarse, double q_fine, double ratio, double order);

// Roache's GCI of the finer level of a pair: Fs |(Q_coarse - Q_fine)/Q_fine| / (r^p - 1) [R];
// null if Q_fine == 0 or r^p <= 1.
std::optional<double> grid_convergence_index(double q_coarse, double q_fine, double ratio,
                                             double order, double safety_factor);

// --- The whole analysis
// ---------------------------------------------------------------------------

// Throws std::invalid_argument for fewer than 2 levels, size mismatch, non-finite numbers, h <= 0,
// h not strictly decreasing, or fit_levels out of range.
Series analyse_convergence(std::vector<double> h, std::vector<double> value,
                           const ConvergenceOptions& options = {}, std::string name = {},
                           std::string parameter = {});

// Order check: passes iff the least-squares order fitted over the series' fit levels is within
// band of the expected order.
struct OrderCheck {
  std::optional<double> observed;  // fitted order (null: not enough nonzero errors -> fails)
  double expected = 0.0;
  double band = 0.0;
  bool passed = false;
  std::string estimate;  // which estimate was used, e.g. "least-squares fit over levels 0-3"
};
OrderCheck check_order(const Series& series, double expected_order, double band);

// The "series" entry of result.json (RESULT_FORMAT.md) plus a few extra keys:
// relative_error, errors_against, three_level_order, extrapolation_order(_source), gci_coarse,
// safety_factor, fit_levels, notes.
nlohmann::json to_json(const Series& series);

const char* to_string(OrderSource source);

}  // namespace ver
