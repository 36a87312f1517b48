#include "ref/ishigami_delta.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace ref {

namespace {

constexpr double pi = std::numbers::pi;

double cdf_sin(double t) { return t <= -1.0 ? 0.0 : t >= 1.0 ? 1.0 : 0.5 + std::asin(t) / pi; }          // P(sin x1 ≤ t)
double cdf_sin2(double w, double a) { return w <= 0.0 ? 0.0 : w >= a ? 1.0 : 2.0 / pi * std::asin(std::sqrt(w / a)); }  // P(a sin² x2 ≤ w)

std::vector<double> midpoints(double lo, double hi, int n) {
  std::vector<double> x(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) x[static_cast<std::size_t>(k)] = lo + (hi - lo) * (k + 0.5) / n;
  return x;
}

/// ½ E_c Σ_k |ΔF_k − ΔG_c,k| with cond[c][k] = G_c(y_k) and F = the mean of the G_c (the node average).
double half_mean_variation(const std::vector<std::vector<double>>& cond) {
  const std::size_t nk = cond.front().size();
  std::vector<double> f(nk, 0.0);
  for (const auto& g : cond)
    for (std::size_t k = 0; k < nk; ++k) f[k] += g[k] / static_cast<double>(cond.size());
  double sum = 0.0;
  for (const auto& g : cond)
    for (std::size_t k = 1; k < nk; ++k) sum += std::abs((f[k] - f[k - 1]) - (g[k] - g[k - 1]));
  return 0.5 * sum / static_cast<double>(cond.size());
}

}  // namespace

std::array<double, 3> ishigami_delta(double a, double b, int nodes, int grid) {
  if (!(a > 0.0) || !(b >= 0.0) || nodes < 2 || grid < 2) throw std::invalid_argument("ishigami_delta: need a > 0, b >= 0, nodes, grid >= 2");
  const double c_max = 1.0 + b * std::pow(pi, 4);
  const double y_lo = -c_max, y_hi = a + c_max;  // f's range (sin x1 (1 + b x3⁴) and a sin² x2 independent)
  std::vector<double> y(static_cast<std::size_t>(grid + 1));
  for (int k = 0; k <= grid; ++k) y[static_cast<std::size_t>(k)] = y_lo + (y_hi - y_lo) * k / grid;
  std::vector<double> s1, s2, c3;  // sin x1, a sin² x2, 1 + b x3⁴ at the midpoint nodes
  for (double x : midpoints(-pi / 2, pi / 2, nodes)) s1.push_back(std::sin(x));
  for (double x : midpoints(0.0, pi / 2, nodes)) s2.push_back(a * std::sin(x) * std::sin(x));
  for (double x : midpoints(0.0, pi, nodes)) c3.push_back(1.0 + b * std::pow(x, 4));
  const std::size_t n = s1.size();
  std::vector<std::vector<double>> g(n, std::vector<double>(y.size(), 0.0));
  std::array<double, 3> delta{};
  for (std::size_t c = 0; c < n; ++c)  // x1 given: E_{x3} P(a sin² x2 ≤ y − sin x1 c3)
    for (std::size_t k = 0; k < y.size(); ++k) {
      double sum = 0.0;
      for (double c3j : c3) sum += cdf_sin2(y[k] - s1[c] * c3j, a);
      g[c][k] = sum / static_cast<double>(n);
    }
  delta[0] = half_mean_variation(g);
  for (std::size_t c = 0; c < n; ++c)  // x2 given: E_{x3} P(sin x1 ≤ (y − a sin² x2)/c3)
    for (std::size_t k = 0; k < y.size(); ++k) {
      double sum = 0.0;
      for (double c3j : c3) sum += cdf_sin((y[k] - s2[c]) / c3j);
      g[c][k] = sum / static_cast<double>(n);
    }
  delta[1] = half_mean_variation(g);
  for (std::size_t c = 0; c < n; ++c)  // x3 given: E_{x2} P(sin x1 ≤ (y − a sin² x2)/c3)
    for (std::size_t k = 0; k < y.size(); ++k) {
      double sum = 0.0;
      for (double s2j : s2) sum += cdf_sin((y[k] - s2j) / c3[c]);
      g[c][k] = sum / static_cast<double>(n);
    }
  delta[2] = half_mean_variation(g);
  return delta;
}

}  // namespace ref
