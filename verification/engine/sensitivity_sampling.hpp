#pragma once
// Samplers of the sensitivity studies (sensitivity.hpp), all in the unit cube [0,1)^d; a parameter's
// range maps a unit coordinate to its value (uniform or log-uniform).
//   - Sobol' quasi-random points (GSL gsl_qrng_sobol, Joe–Kuo direction numbers as GSL ships them),
//     with the origin put back as point 0 so that the first 2^m points form a (t,m,s)-net, then
//     Owen-scrambled (nested uniform scrambling, Owen 1995; seeded, sensitivity_scramble.hpp): the
//     net property stays, every point is uniform on the cube, and no point sits at the origin. The
//     raw sequence's origin is one row where A, B and every AB_i agree; an output far out there (the
//     corner of the cube) makes f(A) and f(B) look correlated and Janon's S_i of an input without any
//     effect read 0.93 (issue 36, block on a slope) while its S_Ti is 1e-6;
//   - Saltelli's matrices A, B and AB_i (A with column i from B), from one 2d-dimensional Sobol'
//     sequence (Saltelli et al. 2010, Comput. Phys. Commun. 181, 259–270, §3), and for second-order
//     indices BA_i (B with column i from A; Saltelli 2002, Comput. Phys. Commun. 145, 280–297);
//   - Morris trajectories on a p-level grid (Morris 1991; step Δ = p / (2 (p − 1)));
//   - one-at-a-time grids.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ver::sens {

/// How a parameter's value x follows from its unit coordinate u (the quantile function x = F⁻¹(u);
/// sensitivity_distribution.cpp). Unbounded ones (normal, log-normal) are cut at their 0.1 % and
/// 99.9 % quantiles (u clamped to [0.001, 0.999], ±3.09 σ) so that the ends of a Morris or
/// one-at-a-time grid (u = 0, 1) are finite values; 0.2 % of the probability moves to the two ends.
enum class Distribution { uniform, log_uniform, normal, truncated_normal, triangular, log_normal, levels };

/// An uncertain parameter: any `--set` path of the case, a range in the case's units (SI unless the
/// value carries a unit) and a distribution.
struct Parameter {
  std::string path;          // e.g. contact.0.kn
  std::string label;         // e.g. K_n
  std::string name;          // ASCII, for CSV headers (sensitivity_names.hpp): [[parameter]] name, or from the label
  std::string unit = "1";    // the SI unit of its values, ASCII ("m", "kg/s^2", "rad"; "1": a plain number)
  double low = 0.0, high = 1.0;  // the support (normal, log-normal, levels: the values at u = 0 and 1)
  bool log_uniform = false;  // uniform in ln x
  Distribution distribution = Distribution::uniform;  // log_uniform above mirrors Distribution::log_uniform
  double mean = 0.0, sd = 1.0;  // normal, truncated normal: of x; log-normal: of ln x (mean = ln median)
  double mode = 0.0;            // triangular
  std::vector<double> levels;   // discrete levels, each with probability 1 / levels.size()
  bool angle = false;        // given in an angle unit: the value (SI, rad) is passed to --set as "x rad"
  bool integer = false;      // the integers low … high, each with probability 1/(high − low + 1)
  /// Further `--set` paths that follow the parameter's value x: path = scale × x^exponent (the same
  /// stiffness on two laws: scale 1, exponent 1; a probe time at a fixed plate travel: travel / v).
  struct Follower {
    std::string path;
    double scale = 1.0, exponent = 1.0;
  };
  std::vector<Follower> also;
};

/// The value of a parameter at unit coordinate u ∈ [0, 1] (integer: low + min(⌊u (high − low + 1)⌋, high − low);
/// other distributions: their quantile function, sensitivity_distribution.cpp).
double value_at(const Parameter& p, double u);

/// The quantile function of the distributions other than uniform and log-uniform (sensitivity_distribution.cpp).
double quantile_of(const Parameter& p, double u);

/// The name of a distribution as the sensitivity file writes it ("log-uniform", "truncated-normal", …).
std::string distribution_name(Distribution d);

using Matrix = std::vector<std::vector<double>>;  // rows = points, columns = parameters

/// `scramble` = 0: the raw sequence (point 0 the origin, every coordinate k / 2^30); any other value
/// seeds an Owen scrambling (coordinates (k + 1/2) / 2^32, never 0 or 1).
constexpr std::uint64_t kUnscrambled = 0;

/// The first n points of the d-dimensional Sobol' sequence (1 <= d <= 40), Owen-scrambled with seed
/// `scramble` (kUnscrambled: the raw sequence, point 0 the origin).
Matrix sobol_points(std::size_t n, std::size_t d, std::uint64_t scramble = 1);

/// Saltelli's design: A, B (n × d) and AB[i] (A with column i from B), from the first n points of
/// the 2d-dimensional Sobol' sequence (A = its first d columns, B the last d); with second_order also
/// BA[i] (B with column i from A).
struct SaltelliDesign {
  Matrix a, b;
  std::vector<Matrix> ab, ba;
};
SaltelliDesign saltelli_design(std::size_t n, std::size_t d, std::uint64_t scramble = 1, bool second_order = false);

/// r Morris trajectories of d + 1 points each on the p-level grid {0, 1/(p−1), …, 1}: a random base
/// point, then each factor (in a random order) moved once by ±Δ, Δ = p / (2 (p − 1)), staying in
/// [0, 1]. Deterministic for a seed (std::mt19937_64, own integer draws: the same on every platform).
struct MorrisTrajectory {
  Matrix points;                    // d + 1 points
  std::vector<std::size_t> order;   // order[k]: the factor changed from point k to k + 1
};
std::vector<MorrisTrajectory> morris_trajectories(std::size_t r, std::size_t d, int levels, std::uint64_t seed);
double morris_delta(int levels);

/// n points evenly spaced in u over [0, 1] (n >= 2).
std::vector<double> oat_grid(std::size_t n);

}  // namespace ver::sens
