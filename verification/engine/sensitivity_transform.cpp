#include "engine/sensitivity_transform.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ver::sens {

Transform parse_transform(const std::string& name) {
  if (name == "none") return Transform::none;
  if (name == "log") return Transform::log;
  if (name == "rank") return Transform::rank;
  throw std::invalid_argument("expected \"none\", \"log\" or \"rank\", got \"" + name + "\"");
}

std::string transform_name(Transform t) { return t == Transform::log ? "log" : t == Transform::rank ? "rank" : "none"; }

std::string transformed_label(Transform t, const std::string& output) {
  return t == Transform::log ? "ln(" + output + ")" : t == Transform::rank ? "rank(" + output + ")" : output;
}

void apply_transform(Transform t, std::vector<double>& fa, std::vector<double>& fb, std::vector<std::vector<double>>& fab,
                     std::vector<std::vector<double>>& fba) {
  std::vector<double*> all;
  for (double& y : fa) all.push_back(&y);
  for (double& y : fb) all.push_back(&y);
  for (auto& c : fab)
    for (double& y : c) all.push_back(&y);
  for (auto& c : fba)
    for (double& y : c) all.push_back(&y);
  if (t == Transform::log) {
    for (double* y : all) *y = *y > 0.0 ? std::log(*y) : std::nan("");
  } else if (t == Transform::rank) {
    std::vector<double*> finite;
    for (double* y : all)
      if (std::isfinite(*y)) finite.push_back(y);
    std::stable_sort(finite.begin(), finite.end(), [](const double* a, const double* b) { return *a < *b; });
    std::vector<double> rank(finite.size());
    for (std::size_t k = 0; k < finite.size();) {  // ties: the mean of the ranks k+1 … e
      std::size_t e = k;
      while (e < finite.size() && *finite[e] == *finite[k]) ++e;
      const double r = 0.5 * (static_cast<double>(k + 1) + static_cast<double>(e));
      for (std::size_t q = k; q < e; ++q) rank[q] = r;
      k = e;
    }
    for (std::size_t k = 0; k < finite.size(); ++k) *finite[k] = rank[k];
  }
}

}  // namespace ver::sens
