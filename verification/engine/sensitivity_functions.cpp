#include "engine/sensitivity_functions.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ver::sens {

std::size_t dimension(const TestFunction& f) {
  if (f.name == "ishigami") return 3;
  if (f.name == "g" || f.name == "linear") return f.coefficients.size();
  throw std::invalid_argument("unknown test function \"" + f.name + "\" (ishigami, g, linear)");
}

double evaluate(const TestFunction& f, const std::vector<double>& x) {
  if (x.size() != dimension(f)) throw std::invalid_argument("test function " + f.name + ": wrong number of inputs");
  if (f.name == "ishigami") {
    const double a = f.coefficients.at(0), b = f.coefficients.at(1);
    const double s2 = std::sin(x[1]);
    return std::sin(x[0]) + a * s2 * s2 + b * std::pow(x[2], 4) * std::sin(x[0]);
  }
  double y = f.name == "g" ? 1.0 : 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double c = f.coefficients[i];
    if (f.name == "g") y *= (std::abs(4.0 * x[i] - 2.0) + c) / (1.0 + c);
    else y += c * x[i];
  }
  return y;
}

ExactIndices exact_indices(const TestFunction& f, const std::vector<double>& low, const std::vector<double>& high,
                           const std::vector<double>& variances, const std::vector<bool>& linear_inputs) {
  ExactIndices e;
  const std::size_t d = dimension(f);
  if (f.name == "ishigami") {
    const double a = f.coefficients.at(0), b = f.coefficients.at(1), pi = std::numbers::pi;
    const double pi4 = std::pow(pi, 4), pi8 = pi4 * pi4;
    const double v1 = 0.5 * (1.0 + b * pi4 / 5.0) * (1.0 + b * pi4 / 5.0);
    const double v2 = a * a / 8.0;
    const double v13 = 8.0 * b * b * pi8 / 225.0;
    const double var = v1 + v2 + v13;
    e.variance = var;
    e.first = {v1 / var, v2 / var, 0.0};
    e.total = {(v1 + v13) / var, v2 / var, v13 / var};
    e.second.assign(3, std::vector<double>(3, 0.0));
    e.second[0][2] = v13 / var;  // the only interaction: b x3⁴ sin x1
  } else if (f.name == "g") {
    std::vector<double> v(d);
    double prod = 1.0;
    for (std::size_t i = 0; i < d; ++i) {
      v[i] = 1.0 / (3.0 * (1.0 + f.coefficients[i]) * (1.0 + f.coefficients[i]));
      prod *= 1.0 + v[i];
    }
    const double var = prod - 1.0;
    e.variance = var;
    for (std::size_t i = 0; i < d; ++i) {
      e.first.push_back(v[i] / var);
      e.total.push_back(v[i] * prod / (1.0 + v[i]) / var);
    }
    e.second.assign(d, std::vector<double>(d, 0.0));  // the ANOVA term of a product: V_ij = V_i V_j
    for (std::size_t i = 0; i < d; ++i)
      for (std::size_t j = i + 1; j < d; ++j) e.second[i][j] = v[i] * v[j] / var;
  } else {  // linear, uniform ranges: additive, S_i = S_Ti = c_i² w_i² / Σ
    double var = 0.0;
    std::vector<double> vi(d);
    for (std::size_t i = 0; i < d; ++i) {
      const double w = high.at(i) - low.at(i);
      vi[i] = f.coefficients[i] * f.coefficients[i] * (variances.empty() ? w * w / 12.0 : variances.at(i));
      var += vi[i];
      const bool exact = linear_inputs.empty() || linear_inputs.at(i) || f.coefficients[i] == 0.0;
      e.morris_mu_star.push_back(exact ? std::abs(f.coefficients[i]) * w : std::nan(""));
      e.morris_sigma.push_back(exact ? 0.0 : std::nan(""));
    }
    e.variance = var;
    for (std::size_t i = 0; i < d; ++i) {
      e.first.push_back(vi[i] / var);
      e.total.push_back(vi[i] / var);
    }
    e.second.assign(d, std::vector<double>(d, 0.0));  // additive: no interactions
  }
  return e;
}

ExactIndices exact_indices_of_log(const TestFunction& f) {
  ExactIndices e;
  if (f.name != "g") return e;
  for (double a : f.coefficients)
    if (!(a > 0.0)) return e;
  auto f1 = [](double t) { return t * std::log(t) - t; };
  auto f2 = [](double t) { return t * std::log(t) * std::log(t) - 2.0 * t * std::log(t) + 2.0 * t; };
  std::vector<double> v;
  double var = 0.0;
  for (double a : f.coefficients) {
    const double m1 = 0.5 * (f1(a + 2.0) - f1(a)), m2 = 0.5 * (f2(a + 2.0) - f2(a));
    v.push_back(m2 - m1 * m1);
    var += v.back();
  }
  for (double vi : v) {
    e.first.push_back(vi / var);
    e.total.push_back(vi / var);
  }
  return e;
}

}  // namespace ver::sens
