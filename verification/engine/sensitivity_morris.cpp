// Morris screening of a sensitivity study: the elementary effects of each trajectory, μ*, μ and σ per
// parameter and output (indices.csv, a table, a μ*–σ figure), checked against the exact effects of a
// linear test function.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/sensitivity_study.hpp"

namespace ver::sens {

void analyse_morris(const Plan& plan, const ExactIndices& exact, Analysis& an) {
  const Sens& s = an.s;
  const std::vector<MorrisTrajectory>& traj = plan.traj;
  const std::size_t d = s.params.size();
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t o = 0; o < s.outputs.size(); ++o) {
    std::vector<std::vector<double>> f(traj.size());
    std::size_t k = plan.morris_begin;
    for (std::size_t t = 0; t < traj.size(); ++t)
      for (std::size_t p = 0; p < traj[t].points.size(); ++p) f[t].push_back(plan.runs[k++].outputs[o]);
    const MorrisEffects m = morris_effects(traj, f, d);
    nlohmann::json curves = nlohmann::json::array(), labels = nlohmann::json::array();
    for (std::size_t i = 0; i < d; ++i) {
      if (std::isfinite(m.mu_star[i]) && std::isfinite(m.sigma[i]))
        labels.push_back({{"x", m.mu_star[i]}, {"y", m.sigma[i]}, {"text", s.params[i].label}});
      rows.push_back({s.outputs[o], s.params[i].label, num(m.mu_star[i]), num(m.mu[i]), num(m.sigma[i]),
                      std::to_string(m.effects[i]), exact.morris_mu_star.empty() ? "" : num(exact.morris_mu_star[i])});
      curves.push_back({{"label", s.params[i].label}, {"x", {jnum(m.mu_star[i])}}, {"y", {jnum(m.sigma[i])}}, {"style", "points"}});
      an.idx_csv << "morris," << s.outputs[o] << ",\"" << s.params[i].label << "\",mu_star," << fmt::format("{:.17g}", m.mu_star[i]) << ",,,"
                 << (exact.morris_mu_star.empty() ? std::string() : fmt::format("{:.17g}", exact.morris_mu_star[i])) << "\n";
      an.idx_csv << "morris," << s.outputs[o] << ",\"" << s.params[i].label << "\",mu," << fmt::format("{:.17g}", m.mu[i]) << ",,,\n";
      an.idx_csv << "morris," << s.outputs[o] << ",\"" << s.params[i].label << "\",sigma," << fmt::format("{:.17g}", m.sigma[i]) << ",,,\n";
      if (!exact.morris_mu_star.empty()) {
        const double e = std::abs(m.mu_star[i] - exact.morris_mu_star[i]);
        const double tol = 1e-9 * std::max(1.0, exact.morris_mu_star[i]);
        an.add_check(fmt::format("Morris μ* of {} ({})", s.params[i].label, s.function->name), exact.morris_mu_star[i],
                     m.mu_star[i], e, tol, "linear model: every elementary effect is exactly c_i (high − low); round-off only",
                     e <= tol, "");
        an.add_check(fmt::format("Morris σ of {} ({})", s.params[i].label, s.function->name), 0.0, m.sigma[i],
                     std::abs(m.sigma[i]), tol, "linear model: all elementary effects equal, σ = 0; round-off only",
                     std::abs(m.sigma[i]) <= tol, "");
      }
    }
    an.figures.push_back({{"id", fmt::format("morris_{}", o)},
                          {"title", fmt::format("Morris screening of {}: μ* against σ ({} trajectories, {} levels)", s.outputs[o], s.trajectories, s.levels)},
                          {"xlabel", fmt::format("μ* [{} per unit range]", s.outputs[o])}, {"ylabel", fmt::format("σ [{} per unit range]", s.outputs[o])},
                          {"logx", false}, {"logy", false}, {"curves", curves}, {"labels", labels}});
  }
  an.tables.push_back({{"title", fmt::format("Morris elementary effects (unit coordinates: per full range; {} trajectories, {} levels, Δ = {:.4g})",
                                             s.trajectories, s.levels, morris_delta(s.levels))},
                       {"columns", {"output", "parameter", "μ*", "μ", "σ", "effects", "exact μ*"}},
                       {"rows", rows}});
}

}  // namespace ver::sens
