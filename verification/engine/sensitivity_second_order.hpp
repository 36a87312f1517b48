#pragma once
// Second-order Sobol' indices from Saltelli's extended design (Saltelli 2002, Comput. Phys. Commun.
// 145, 280–297, Theorem 1; the form SALib uses): besides A, B and AB_i (A with column i from B) the
// matrices BA_i (B with column i from A). f(BA_j) and f(AB_k) share x_j and x_k and nothing else, so
//   V^c_jk = mean_r [f(BA_j)_r f(AB_k)_r − f(A)_r f(B)_r]          (the closed variance of (x_j, x_k))
//   S_jk   = V^c_jk / V − S_j − S_k,   S_j = mean_r f(B)_r (f(AB_j)_r − f(A)_r) / V  (Saltelli 2010)
// V = the variance of f over A ∪ B. N (2d + 2) runs in all. Bootstrap percentile intervals as for the
// first and total indices (sensitivity_estimators.hpp): rows drawn with replacement, same seed rule.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/sensitivity_estimators.hpp"

namespace ver::sens {

struct SecondOrderIndex {
  std::size_t i = 0, j = 0;  // i < j, 0-based parameter numbers
  Interval s2;
};

/// Every pair i < j; rows where any of f(A), f(B), f(AB_k), f(BA_k) is missing (NaN) are dropped.
std::vector<SecondOrderIndex> sobol_second_order(const std::vector<double>& fa, const std::vector<double>& fb,
                                                 const std::vector<std::vector<double>>& fab,
                                                 const std::vector<std::vector<double>>& fba, std::size_t resamples = 1000,
                                                 double confidence = 0.95, std::uint64_t seed = 12345);

}  // namespace ver::sens
