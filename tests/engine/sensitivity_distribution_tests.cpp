// Quantile functions of the sensitivity parameters' distributions (verification/engine/
// sensitivity_distribution.cpp) against closed forms, and their moments over a scrambled Sobol' sample.
#include <catch2/catch.hpp>

#include <cmath>

#include "engine/sensitivity_estimators.hpp"
#include "engine/sensitivity_sampling.hpp"

using namespace ver::sens;

namespace {

Parameter with(Distribution d) {
  Parameter p;
  p.distribution = d;
  return p;
}

double cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

/// Mean and variance of the parameter's values over 2^14 Owen-scrambled Sobol' points.
std::pair<double, double> moments(const Parameter& p) {
  const Matrix u = sobol_points(std::size_t{1} << 14, 1, 3);
  double m = 0.0, m2 = 0.0;
  for (const auto& row : u) {
    const double x = value_at(p, row[0]);
    m += x;
    m2 += x * x;
  }
  m /= static_cast<double>(u.size());
  return {m, m2 / static_cast<double>(u.size()) - m * m};
}

}  // namespace

TEST_CASE("normal_quantile inverts the normal CDF to round-off over its range", "[sensitivity]") {
  for (double p : {1e-12, 1e-6, 0.001, 0.02, 0.02425, 0.1, 0.3, 0.5, 0.7, 0.975, 0.999, 1 - 1e-9}) {
    const double z = normal_quantile(p);
    CHECK(cdf(z) == Approx(p).epsilon(1e-12));
  }
  CHECK(normal_quantile(0.975) == Approx(1.959963984540054).epsilon(1e-14));
}

TEST_CASE("normal and log-normal: quantiles, clamped at 0.1 % and 99.9 %", "[sensitivity]") {
  Parameter n = with(Distribution::normal);
  n.mean = 2.0;
  n.sd = 0.5;
  CHECK(value_at(n, 0.5) == Approx(2.0).margin(1e-14));
  CHECK(value_at(n, 0.975) == Approx(2.0 + 0.5 * 1.959963984540054).epsilon(1e-13));
  CHECK(value_at(n, 0.0) == Approx(2.0 - 0.5 * 3.090232306167813).epsilon(1e-12));  // the 0.1 % quantile
  CHECK(value_at(n, 1.0) == Approx(2.0 + 0.5 * 3.090232306167813).epsilon(1e-12));
  const auto [m, v] = moments(n);
  CHECK(m == Approx(2.0).margin(1e-3));
  CHECK(std::sqrt(v) == Approx(0.5).epsilon(0.01));  // the clamp takes 0.1 % of the sd
  Parameter ln = with(Distribution::log_normal);
  ln.mean = std::log(2.0);  // median 2
  ln.sd = 0.4;
  CHECK(value_at(ln, 0.5) == Approx(2.0).epsilon(1e-14));
  CHECK(value_at(ln, cdf(1.0)) == Approx(2.0 * std::exp(0.4)).epsilon(1e-12));
  const auto [lm, lv] = moments(ln);
  CHECK(lm == Approx(2.0 * std::exp(0.08)).epsilon(2e-3));  // E x = median e^{σ²/2}
}

TEST_CASE("truncated normal: the quantile of the normal restricted to [low, high]", "[sensitivity]") {
  Parameter t = with(Distribution::truncated_normal);
  t.mean = 0.0;
  t.sd = 1.0;
  t.low = 0.0;
  t.high = 2.0;
  CHECK(value_at(t, 0.0) == Approx(0.0).margin(1e-12));
  CHECK(value_at(t, 1.0) == Approx(2.0).epsilon(1e-12));
  for (double u : {0.1, 0.5, 0.9}) {  // F(x) = (Φ(x) − Φ(0)) / (Φ(2) − Φ(0))
    const double x = value_at(t, u);
    CHECK((cdf(x) - 0.5) / (cdf(2.0) - 0.5) == Approx(u).epsilon(1e-12));
  }
  // Half-normal on [0, 2]: mean = (φ(0) − φ(2)) / (Φ(2) − Φ(0)) = 0.7449 (closed form).
  const double phi0 = 1.0 / std::sqrt(2.0 * 3.141592653589793), phi2 = phi0 * std::exp(-2.0);
  CHECK(moments(t).first == Approx((phi0 - phi2) / (cdf(2.0) - 0.5)).epsilon(1e-4));
}

TEST_CASE("triangular and discrete levels: quantiles and moments", "[sensitivity]") {
  Parameter tr = with(Distribution::triangular);
  tr.low = 0.0;
  tr.mode = 1.0;
  tr.high = 4.0;
  CHECK(value_at(tr, 0.25) == Approx(1.0));  // F(mode) = (c − a)/(b − a)
  CHECK(value_at(tr, 0.1) == Approx(std::sqrt(0.4)));
  CHECK(value_at(tr, 0.9) == Approx(4.0 - std::sqrt(1.2)));
  const auto [m, v] = moments(tr);
  CHECK(m == Approx(5.0 / 3.0).epsilon(1e-4));                   // (a + b + c)/3
  CHECK(v == Approx((0.0 + 16.0 + 1.0 - 0.0 - 0.0 - 4.0) / 18.0).epsilon(1e-3));  // (a²+b²+c²−ab−ac−bc)/18
  Parameter lv = with(Distribution::levels);
  lv.levels = {1.0, 2.0, 5.0};
  CHECK(value_at(lv, 0.0) == 1.0);
  CHECK(value_at(lv, 0.34) == 2.0);
  CHECK(value_at(lv, 0.67) == 5.0);
  CHECK(value_at(lv, 1.0) == 5.0);
  CHECK(moments(lv).first == Approx(8.0 / 3.0).epsilon(1e-3));
}
