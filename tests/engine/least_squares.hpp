#pragma once
// Least-squares slope of y against x, for the tests' fitted convergence orders.
#include <cstddef>
#include <vector>

namespace test {

inline double least_squares_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    mx += x[k] / x.size();
    my += y[k] / y.size();
  }
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxy += (x[k] - mx) * (y[k] - my);
    sxx += (x[k] - mx) * (x[k] - mx);
  }
  return sxy / sxx;
}

}  // namespace test
