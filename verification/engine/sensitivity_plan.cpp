// The design of a sensitivity study: which runs (the one-at-a-time grid, Morris trajectories,
// Saltelli's samples on a Sobol' sequence) and the overrides that put each run's parameters at their values.
#include <cmath>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "engine/sensitivity_study.hpp"

namespace ver::sens {

void push_sets(std::vector<std::string>& sets, const Parameter& p, double v) {
  sets.push_back(fmt::format("{}={:.17g}{}", p.path, v, p.angle ? " rad" : ""));
  for (const auto& f : p.also) sets.push_back(fmt::format("{}={:.17g}", f.path, f.scale * std::pow(v, f.exponent)));
}

Run make_run(const Sens& s, const std::string& method, const std::vector<double>& u) {
  Run r;
  r.method = method;
  r.u = u;
  r.sets = s.set;
  for (std::size_t i = 0; i < s.params.size(); ++i)
    if (std::isfinite(u[i])) push_sets(r.sets, s.params[i], value_at(s.params[i], u[i]));
  return r;
}

void check_ranges(const Sens& s) {
  if (!s.function)
    for (const Parameter& p : s.params)
      for (double v : {p.low, p.high}) {
        std::vector<std::string> sets = s.set;
        push_sets(sets, p, v);
        (void)dem::read_case(s.case_file, sets);
      }
}

Plan plan_runs(const Sens& s) {
  const std::size_t d = s.params.size();
  Plan plan;
  std::vector<Run>& runs = plan.runs;
  // one-at-a-time: the base case, then each parameter over its range with the others at the base case's values
  plan.oat_begin = runs.size();
  plan.grid = oat_grid(s.oat_points);
  if (s.oat) {
    runs.push_back(make_run(s, "oat base", std::vector<double>(d, std::nan(""))));
    for (std::size_t i = 0; i < d; ++i)
      for (double u : plan.grid) {
        std::vector<double> x(d, std::nan(""));
        x[i] = u;
        runs.push_back(make_run(s, fmt::format("oat {}", s.params[i].label), x));
      }
  }
  plan.morris_begin = runs.size();
  if (s.morris) {
    plan.traj = morris_trajectories(s.trajectories, d, s.levels, s.seed);
    for (std::size_t t = 0; t < plan.traj.size(); ++t)
      for (const auto& p : plan.traj[t].points) runs.push_back(make_run(s, fmt::format("morris {}", t), p));
  }
  plan.sobol_begin = runs.size();
  if (s.sobol) {
    const SaltelliDesign des = saltelli_design(s.samples, d, s.sobol_seed, s.second_order);
    for (const auto& row : des.a) runs.push_back(make_run(s, "sobol A", row));
    for (const auto& row : des.b) runs.push_back(make_run(s, "sobol B", row));
    for (std::size_t i = 0; i < d; ++i)
      for (const auto& row : des.ab[i]) runs.push_back(make_run(s, fmt::format("sobol AB{}", i + 1), row));
    for (std::size_t i = 0; i < des.ba.size(); ++i)
      for (const auto& row : des.ba[i]) runs.push_back(make_run(s, fmt::format("sobol BA{}", i + 1), row));
  }
  return plan;
}

}  // namespace ver::sens
