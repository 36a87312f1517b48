// Convergence analysis: observed orders, least-squares order, Richardson extrapolation, GCI.
// See convergence.hpp for the definitions and references [R] (Roache 1994), [C] (Celik et al.
// 2008).
#include "engine/convergence.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <stdexcept>

namespace ver {

namespace {

constexpr double safety_factor_three_levels = 1.25;  // [R], [C] eq. (8)
constexpr double safety_factor_two_levels = 3.0;     // [R]
constexpr int fixed_point_max_iterations = 200;
constexpr double fixed_point_tolerance = 1e-13;  // relative change of p
constexpr double bisection_order_min = 1e-6;     // search interval for p when fixed point fails
constexpr double bisection_order_max = 30.0;
constexpr int bisection_scan_steps = 600;

bool is_positive(const std::optional<double>& x) { return x && *x > 0.0; }

// "0-3" for contiguous level lists, "0, 2, 3" otherwise.
std::string describe_levels(const std::vector<std::size_t>& levels) {
  if (levels.empty()) return "none";
  bool contiguous = true;
  for (std::size_t i = 1; i < levels.size(); ++i) contiguous &= levels[i] == levels[i - 1] + 1;
  if (contiguous && levels.size() > 1) return fmt::format("{}-{}", levels.front(), levels.back());
  return fmt::format("{}", fmt::join(levels, ", "));
}

void validate(const std::vector<double>& h, const std::vector<double>& value,
              const ConvergenceOptions& options) {
  if (h.size() != value.size())
    throw std::invalid_argument(
        fmt::format("convergence: {} step sizes but {} values", h.size(), value.size()));
  if (h.size() < 2)
    throw std::invalid_argument(
        fmt::format("convergence: need at least 2 levels, got {}", h.size()));
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (!std::isfinite(h[k]) || !std::isfinite(value[k]))
      throw std::invalid_argument(fmt::format("convergence: level {} is not finite", k));
    if (h[k] <= 0.0)
      throw std::invalid_argument(fmt::format("convergence: h[{}] = {} is not positive", k, h[k]));
    if (k > 0 && !(h[k] < h[k - 1]))
      throw std::invalid_argument(fmt::format(
          "convergence: h must decrease strictly from coarse to fine (h[{}] = {}, h[{}] = {})",
          k - 1, h[k - 1], k, h[k]));
  }
  if (options.reference && !std::isfinite(*options.reference))
    throw std::invalid_argument("convergence: reference value is not finite");
  for (std::size_t level : options.fit_levels)
    if (level >= h.size())
      throw std::invalid_argument(
          fmt::format("convergence: fit level {} out of range (n = {})", level, h.size()));
}

}  // namespace

std::optional<double> observed_order(double error_coarse, double error_fine, double ratio) {
  if (!(error_coarse > 0.0) || !(error_fine > 0.0) || !(ratio > 1.0)) return std::nullopt;
  return std::log(error_coarse / error_fine) / std::log(ratio);
}

std::optional<double> three_level_order(double h_coarse, double h_medium, double h_fine,
                                        double q_coarse, double q_medium, double q_fine) {
  const double r21 = h_medium / h_fine;  // [C] notation: 1 = fine, 2 = medium, 3 = coarse
  const double r32 = h_coarse / h_medium;
  const double eps32 = q_coarse - q_medium;
  const double eps21 = q_medium - q_fine;
  if (!(r21 > 1.0) || !(r32 > 1.0) || eps21 == 0.0 || eps32 == 0.0) return std::nullopt;

  const double s = eps32 / eps21 > 0.0 ? 1.0 : -1.0;  // [C] eq. (5)
  const double log_ratio = std::log(std::abs(eps32 / eps21));
  // p = |ln|eps32/eps21| + q(p)| / ln r21, q(p) = ln((r21^p - s)/(r32^p - s))   [C] eqs. (3)-(4)
  auto iterate = [&](double p) {
    const double q = std::log((std::pow(r21, p) - s) / (std::pow(r32, p) - s));
    return std::abs(log_ratio + q) / std::log(r21);
  };

  double p = std::abs(log_ratio) / std::log(r21);  // start from q = 0 (exact for constant r)
  for (int i = 0; i < fixed_point_max_iterations; ++i) {
    const double next = iterate(p);
    if (!std::isfinite(next)) break;
    if (std::abs(next - p) <= fixed_point_tolerance * (1.0 + std::abs(next))) return next;
    p = next;
  }

  // Fixed point did not converge (it can oscillate when r32 >> r21): bracket the first root of
  // F(p) = p - iterate(p) on a grid, then bisect.
  auto residual = [&](double p_trial) { return p_trial - iterate(p_trial); };
  const double step = (bisection_order_max - bisection_order_min) / bisection_scan_steps;
  double lo = bisection_order_min;
  double f_lo = residual(lo);
  for (int i = 1; i <= bisection_scan_steps; ++i) {
    double hi = bisection_order_min + i * step;
    const double f_hi = residual(hi);
    if (std::isfinite(f_lo) && std::isfinite(f_hi) && f_lo * f_hi <= 0.0) {
      for (int j = 0; j < 200; ++j) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        const double f_mid = residual(mid);
        if (f_lo * f_mid <= 0.0) {
          hi = mid;
        } else {
          lo = mid;
          f_lo = f_mid;
        }
      }
      return 0.5 * (lo + hi);
    }
    lo = hi;
    f_lo = f_hi;
  }
  return std::nullopt;
}

std::optional<double> fitted_order(const std::vector<double>& h, const std::vector<double>& error) {
  if (h.size() != error.size())
    throw std::invalid_argument("fitted_order: h and error differ in length");
  std::vector<double> x, y;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (h[k] > 0.0 && error[k] > 0.0 && std::isfinite(error[k])) {
      x.push_back(std::log(h[k]));
      y.push_back(std::log(error[k]));
    }
  }
  if (x.size() < 2) return std::nullopt;
  double x_mean = 0.0, y_mean = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    x_mean += x[i];
    y_mean += y[i];
  }
  x_mean /= static_cast<double>(x.size());
  y_mean /= static_cast<double>(y.size());
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - x_mean) * (y[i] - y_mean);
    sxx += (x[i] - x_mean) * (x[i] - x_mean);
  }
  if (!(sxx > 0.0)) return std::nullopt;
  return sxy / sxx;
}

double richardson_extrapolation(double q_coarse, double q_fine, double ratio, double order) {
  return q_fine + (q_fine - q_coarse) / (std::pow(ratio, order) - 1.0);  // [C] eq. (6)
}

std::optional<double> grid_convergence_index(double q_coarse, double q_fine, double ratio,
                                             double order, double safety_factor) {
  const double rp_minus_1 = std::pow(ratio, order) - 1.0;
  if (q_fine == 0.0 || !(rp_minus_1 > 0.0)) return std::nullopt;
  const double relative_change = (q_coarse - q_fine) / q_fine;
  return safety_factor * std::abs(relative_change) / rp_minus_1;  // [R], [C] eq. (8)
}

Series analyse_convergence(std::vector<double> h, std::vector<double> value,
                           const ConvergenceOptions& options, std::string name,
                           std::string parameter) {
  validate(h, value, options);
  const std::size_t n = h.size();
  const std::size_t fine = n - 1;

  Series s;
  s.name = std::move(name);
  s.parameter = std::move(parameter);
  s.h = std::move(h);
  s.value = std::move(value);
  s.reference = options.reference;
  s.expected_order = options.expected_order;
  s.errors_against_richardson = !options.reference;
  s.safety_factor = n >= 3 ? safety_factor_three_levels : safety_factor_two_levels;

  auto ratio = [&](std::size_t k) { return s.h[k - 1] / s.h[k]; };  // r_k, k >= 1
  auto three_level_at = [&](std::size_t k) {                        // levels k-2, k-1, k
    return three_level_order(s.h[k - 2], s.h[k - 1], s.h[k], s.value[k - 2], s.value[k - 1],
                             s.value[k]);
  };

  // Three-level order of the finest levels: independent of any reference [C].
  std::optional<double> richardson_three_level;
  if (n >= 3) {
    s.three_level_order = three_level_at(fine);
    const bool coarse_drop = s.value[fine - 2] > s.value[fine - 1];
    const bool fine_drop = s.value[fine - 1] > s.value[fine];
    if (s.value[fine - 2] != s.value[fine - 1] && s.value[fine - 1] != s.value[fine] &&
        coarse_drop != fine_drop)
      s.notes.push_back("finest three levels converge oscillatorily (differences change sign)");
    if (s.three_level_order) {
      if (*s.three_level_order > 0.0)
        richardson_three_level = richardson_extrapolation(s.value[fine - 1], s.value[fine],
                                                          ratio(fine), *s.three_level_order);
    } else {
      s.notes.push_back(
          "three-level order undefined (equal values on two levels or no positive root)");
    }
  }

  // Errors: against the reference, else against the three-level Richardson value.
  const std::optional<double> target =
      options.reference ? options.reference : richardson_three_level;
  s.error.assign(n, std::nullopt);
  s.relative_error.assign(n, std::nullopt);
  if (target) {
    for (std::size_t k = 0; k < n; ++k) {
      s.error[k] = std::abs(s.value[k] - *target);
      if (*target != 0.0) s.relative_error[k] = *s.error[k] / std::abs(*target);
    }
  } else {
    s.notes.push_back(n < 3 ? "no reference and fewer than 3 levels: errors unknown"
                            : "no reference and no three-level Richardson value: errors unknown");
  }

  // Observed order per level.
  s.observed_order.assign(n, std::nullopt);
  for (std::size_t k = 1; k < n; ++k) {
    if (options.reference) {
      if (s.error[k - 1] && s.error[k])
        s.observed_order[k] = observed_order(*s.error[k - 1], *s.error[k], ratio(k));
    } else if (k >= 2) {
      s.observed_order[k] = three_level_at(k);
    }
  }
  for (std::size_t k = 0; k < n; ++k)
    if (s.error[k] && *s.error[k] == 0.0)
      s.notes.push_back(fmt::format("error is exactly zero at level {}: its orders are null", k));
  for (std::size_t k = 1; k < n; ++k)
    if (s.error[k - 1] && s.error[k] && *s.error[k] > *s.error[k - 1]) {
      s.notes.push_back("errors do not decrease monotonically under refinement");
      break;
    }

  // Least-squares order over the chosen levels, skipping zero and unknown errors.
  std::vector<std::size_t> candidates = options.fit_levels;
  if (candidates.empty())
    for (std::size_t k = 0; k < n; ++k) candidates.push_back(k);
  std::vector<double> fit_h, fit_e;
  for (std::size_t k : candidates) {
    if (!s.error[k]) continue;
    if (*s.error[k] == 0.0) {
      s.zero_error_levels.push_back(k);
      continue;
    }
    s.fit_levels.push_back(k);
    fit_h.push_back(s.h[k]);
    fit_e.push_back(*s.error[k]);
  }
  s.fitted_order = fitted_order(fit_h, fit_e);
  if (!s.fitted_order)
    s.notes.push_back("fewer than 2 levels with a nonzero error: no fitted order");

  // Order for Richardson and GCI: assumed > three-level > two-level against the reference.
  if (options.assumed_order) {
    s.extrapolation_order = options.assumed_order;
    s.extrapolation_order_source = OrderSource::assumed;
  } else if (s.three_level_order) {
    s.extrapolation_order = s.three_level_order;
    s.extrapolation_order_source = OrderSource::three_level;
  } else if (options.reference && s.observed_order[fine]) {
    s.extrapolation_order = s.observed_order[fine];
    s.extrapolation_order_source = OrderSource::two_level_reference;
  }

  if (is_positive(s.extrapolation_order)) {
    const double p = *s.extrapolation_order;
    const double r_fine = ratio(fine);
    s.richardson = richardson_extrapolation(s.value[fine - 1], s.value[fine], r_fine, p);
    s.gci_fine =
        grid_convergence_index(s.value[fine - 1], s.value[fine], r_fine, p, s.safety_factor);
    if (!s.gci_fine) s.notes.push_back("finest value is zero: relative GCI undefined");
    if (n >= 3) {
      s.gci_coarse = grid_convergence_index(s.value[fine - 2], s.value[fine - 1], ratio(fine - 1),
                                            p, s.safety_factor);
      if (s.gci_coarse && is_positive(s.gci_fine)) {
        s.asymptotic_ratio = *s.gci_coarse / (std::pow(r_fine, p) * *s.gci_fine);  // [R]
        s.asymptotic = std::abs(*s.asymptotic_ratio - 1.0) <= options.asymptotic_tolerance;
      }
    }
  } else {
    s.notes.push_back("no positive order for Richardson extrapolation and GCI");
  }
  return s;
}

OrderCheck check_order(const Series& series, double expected_order, double band) {
  OrderCheck check;
  check.observed = series.fitted_order;
  check.expected = expected_order;
  check.band = band;
  check.passed = check.observed && std::abs(*check.observed - expected_order) <= band;
  check.estimate = fmt::format(
      "least-squares fit of log e vs log h over levels {}{}", describe_levels(series.fit_levels),
      series.errors_against_richardson ? " (errors against Richardson)" : "");
  return check;
}

const char* to_string(OrderSource source) {
  switch (source) {
    case OrderSource::assumed:
      return "assumed";
    case OrderSource::three_level:
      return "three-level";
    case OrderSource::two_level_reference:
      return "two-level (reference)";
    case OrderSource::none:
      break;
  }
  return "none";
}

namespace {

nlohmann::json number_or_null(const std::optional<double>& x) {
  if (x && std::isfinite(*x)) return *x;
  return nullptr;
}

nlohmann::json numbers_or_null(const std::vector<std::optional<double>>& xs) {
  auto array = nlohmann::json::array();
  for (const auto& x : xs) array.push_back(number_or_null(x));
  return array;
}

}  // namespace

nlohmann::json to_json(const Series& s) {
  nlohmann::json j;
  j["name"] = s.name;
  j["parameter"] = s.parameter;
  j["h"] = s.h;
  j["value"] = s.value;
  j["reference"] = number_or_null(s.reference);
  j["error"] = numbers_or_null(s.error);
  j["observed_order"] = numbers_or_null(s.observed_order);
  j["fitted_order"] = number_or_null(s.fitted_order);
  j["expected_order"] = number_or_null(s.expected_order);
  j["richardson"] = number_or_null(s.richardson);
  j["gci_fine"] = number_or_null(s.gci_fine);
  j["asymptotic_ratio"] = number_or_null(s.asymptotic_ratio);
  j["asymptotic"] = s.asymptotic ? nlohmann::json(*s.asymptotic) : nlohmann::json(nullptr);
  // Extras beyond RESULT_FORMAT.md (the report ignores keys it does not know).
  j["relative_error"] = numbers_or_null(s.relative_error);
  j["errors_against"] = s.errors_against_richardson ? "richardson" : "reference";
  j["three_level_order"] = number_or_null(s.three_level_order);
  j["extrapolation_order"] = number_or_null(s.extrapolation_order);
  j["extrapolation_order_source"] = to_string(s.extrapolation_order_source);
  j["gci_coarse"] = number_or_null(s.gci_coarse);
  j["safety_factor"] = s.safety_factor;
  j["fit_levels"] = s.fit_levels;
  j["notes"] = s.notes;
  return j;
}

}  // namespace ver
