// The quantile functions x = F⁻¹(u) of a sensitivity parameter's distribution (sensitivity_sampling.hpp):
//   normal(mean m, sd σ):               x = m + σ Φ⁻¹(u)
//   truncated normal on [a, b]:         x = m + σ Φ⁻¹(Φ(α) + u (Φ(β) − Φ(α))), α = (a − m)/σ, β = (b − m)/σ
//   triangular(a, c, b):                x = a + √(u (b − a)(c − a))        for u < (c − a)/(b − a),
//                                       x = b − √((1 − u)(b − a)(b − c))   otherwise
//   log-normal(median e^m, σ of ln x):  x = exp(m + σ Φ⁻¹(u))
//   levels x_1 … x_k:                   x = x_{min(⌊u k⌋, k − 1) + 1}, each with probability 1/k
// Φ⁻¹ = normal_quantile (sensitivity_estimators.hpp). Normal and log-normal: u clamped to [0.001, 0.999].
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/sensitivity_estimators.hpp"
#include "engine/sensitivity_sampling.hpp"

namespace ver::sens {

namespace {

constexpr double kTail = 0.001;  // normal, log-normal: the quantiles at u = 0 and u = 1

double phi(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }  // the standard normal CDF

}  // namespace

double quantile_of(const Parameter& p, double u) {
  u = std::clamp(u, 0.0, 1.0);
  switch (p.distribution) {
    case Distribution::normal:
      return p.mean + p.sd * normal_quantile(std::clamp(u, kTail, 1.0 - kTail));
    case Distribution::log_normal:
      return std::exp(p.mean + p.sd * normal_quantile(std::clamp(u, kTail, 1.0 - kTail)));
    case Distribution::truncated_normal: {
      const double fa = phi((p.low - p.mean) / p.sd), fb = phi((p.high - p.mean) / p.sd);
      const double q = fa + u * (fb - fa);
      if (q <= 0.0) return p.low;
      if (q >= 1.0) return p.high;
      return std::clamp(p.mean + p.sd * normal_quantile(q), p.low, p.high);
    }
    case Distribution::triangular: {
      const double a = p.low, b = p.high, c = p.mode;
      return u < (c - a) / (b - a) ? a + std::sqrt(u * (b - a) * (c - a)) : b - std::sqrt((1.0 - u) * (b - a) * (b - c));
    }
    case Distribution::levels: {
      const auto k = p.levels.size();
      return p.levels.at(std::min(static_cast<std::size_t>(std::floor(u * static_cast<double>(k))), k - 1));
    }
    case Distribution::uniform:
    case Distribution::log_uniform:
      break;
  }
  throw std::logic_error("quantile_of: uniform and log-uniform are value_at's own");
}

std::string distribution_name(Distribution d) {
  switch (d) {
    case Distribution::uniform: return "uniform";
    case Distribution::log_uniform: return "log-uniform";
    case Distribution::normal: return "normal";
    case Distribution::truncated_normal: return "truncated-normal";
    case Distribution::triangular: return "triangular";
    case Distribution::log_normal: return "log-normal";
    case Distribution::levels: return "levels";
  }
  return "uniform";
}

}  // namespace ver::sens
