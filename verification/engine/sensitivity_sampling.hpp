#pragma once
// Samplers of the sensitivity studies (sensitivity.hpp), all in the unit cube [0,1)^d; a parameter's
// range maps a unit coordinate to its value (uniform or log-uniform).
//   - Sobol' quasi-random points (GSL gsl_qrng_sobol, Joe–Kuo direction numbers as GSL ships them),
//     with the origin put back as point 0 so that the first 2^m points form a (t,m,s)-net;
//   - Saltelli's matrices A, B and AB_i (A with column i from B), from one 2d-dimensional Sobol'
//     sequence (Saltelli et al. 2010, Comput. Phys. Commun. 181, 259–270, §3);
//   - Morris trajectories on a p-level grid (Morris 1991; step Δ = p / (2 (p − 1)));
//   - one-at-a-time grids.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ver::sens {

/// An uncertain parameter: any `--set` path of the case, a range in the case's units (SI unless the
/// value carries a unit) and a distribution.
struct Parameter {
  std::string path;          // e.g. contact.0.kn
  std::string label;         // e.g. K_n
  double low = 0.0, high = 1.0;
  bool log_uniform = false;  // uniform in ln x
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

/// The value of a parameter at unit coordinate u ∈ [0, 1] (integer: low + min(⌊u (high − low + 1)⌋, high − low)).
double value_at(const Parameter& p, double u);

using Matrix = std::vector<std::vector<double>>;  // rows = points, columns = parameters

/// The first n points of the d-dimensional Sobol' sequence (1 <= d <= 40), point 0 the origin.
Matrix sobol_points(std::size_t n, std::size_t d);

/// Saltelli's design: A, B (n × d) and AB[i] (A with column i from B), from the first n points of
/// the 2d-dimensional Sobol' sequence (A = its first d columns, B the last d).
struct SaltelliDesign {
  Matrix a, b;
  std::vector<Matrix> ab;
};
SaltelliDesign saltelli_design(std::size_t n, std::size_t d);

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
