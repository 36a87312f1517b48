// One-at-a-time sweeps of a sensitivity study: each output over each parameter's range with the others
// at the base case's values — a figure per output, the range of each sweep (indices.csv, a table).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/sensitivity_study.hpp"

namespace ver::sens {

void analyse_oat(const Plan& plan, Analysis& an) {
  const Sens& s = an.s;
  const std::vector<Run>& runs = plan.runs;
  const std::vector<double>& grid = plan.grid;
  const std::size_t oat_begin = plan.oat_begin;
  auto plain = [](const std::string& x) { return x; };
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t o = 0; o < s.outputs.size(); ++o) {
    nlohmann::json curves = nlohmann::json::array();
    for (std::size_t i = 0; i < s.params.size(); ++i) {
      std::vector<double> xs, ys;
      double ymin = INFINITY, ymax = -INFINITY;
      for (std::size_t g = 0; g < grid.size(); ++g) {
        const double y = runs[oat_begin + 1 + i * grid.size() + g].outputs[o];
        if (!std::isfinite(y)) continue;
        xs.push_back(grid[g]);
        ys.push_back(y);
        ymin = std::min(ymin, y);
        ymax = std::max(ymax, y);
      }
      curves.push_back({{"label", s.params[i].label}, {"x", xs}, {"y", ys}, {"style", "linespoints"}});
      const double range = ys.empty() ? std::nan("") : ymax - ymin;
      rows.push_back({s.outputs[o], s.params[i].label,
                      fmt::format("{} … {}{}", num(s.params[i].low), num(s.params[i].high), s.params[i].log_uniform ? " (log)" : s.params[i].integer ? " (integer)" : ""),
                      num(ys.empty() ? NAN : ys.front()), num(ys.empty() ? NAN : ys.back()), num(range),
                      num(range / std::abs(runs[oat_begin].outputs[o]))});
      an.idx_csv << "oat," << s.outputs[o] << ",\"" << plain(s.params[i].label) << "\",range," << fmt::format("{:.17g},{:.17g},{:.17g},", range, range, range) << "\n";  // deterministic: no sampling error
    }
    an.figures.push_back({{"id", fmt::format("oat_{}", o)},
                          {"title", fmt::format("One-at-a-time sweeps of {} (others at the base case; base value {})", s.outputs[o], num(runs[oat_begin].outputs[o]))},
                          {"xlabel", "position in the parameter's range u (0 = low, 1 = high; log scale for log-uniform)"},
                          {"ylabel", s.outputs[o]}, {"logx", false}, {"logy", false}, {"curves", curves}});
  }
  an.tables.push_back({{"title", "One-at-a-time sweeps: the output at both ends of each range"},
                       {"columns", {"output", "parameter", "range", "at low", "at high", "max − min", "(max − min) / |base|"}},
                       {"rows", rows}});
}

}  // namespace ver::sens
