// Morris screening of a sensitivity study: the elementary effects of each trajectory, μ*, μ and σ per
// parameter and output (indices.csv, a table, a μ*–σ figure), checked against the exact effects of a
// linear test function.
#include <algorithm>
#include <optional>
#include <cmath>
#include <numbers>
#include <tuple>

#include <fmt/format.h>

#include "engine/sensitivity_study.hpp"

namespace ver::sens {

namespace {

/// μ* per parameter with its bootstrap interval (bars with error bars).
nlohmann::json mu_star_figure(const Sens& s, const MorrisEffects& m, std::size_t o) {
  const std::size_t d = s.params.size();
  nlohmann::json x = nlohmann::json::array(), y = nlohmann::json::array(), lo = nlohmann::json::array(), hi = nlohmann::json::array(),
                 xticks = nlohmann::json::array();
  for (std::size_t i = 0; i < d; ++i) {
    x.push_back(static_cast<double>(i + 1));
    y.push_back(jnum(m.mu_star[i]));
    lo.push_back(jnum(m.mu_star_ci[i].low));
    hi.push_back(jnum(m.mu_star_ci[i].high));
    xticks.push_back({static_cast<double>(i + 1), s.params[i].label});
  }
  nlohmann::json curves = nlohmann::json::array();
  curves.push_back({{"label", "μ*"}, {"x", x}, {"y", y}, {"style", "boxes"}, {"width", 0.4}});
  curves.push_back({{"label", fmt::format("{:.0f} % bootstrap interval ({} resamples of the elementary effects)", 100.0 * s.morris_confidence,
                                          s.morris_resamples)},
                    {"x", x}, {"y", y}, {"ylow", lo}, {"yhigh", hi}, {"style", "errorbars"}, {"colour", "#000000"}});
  return {{"id", fmt::format("morris_mu_star_{}", o)}, {"title", fmt::format("Morris μ* of {} with its bootstrap interval", s.outputs[o])},
          {"xlabel", "parameter"}, {"ylabel", fmt::format("μ* [{} per unit range]", s.outputs[o])}, {"logx", false}, {"logy", false},
          {"curves", curves}, {"xticks", xticks}, {"xrange", {0.5, static_cast<double>(d) + 0.5}}};
}

}  // namespace

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
    const MorrisEffects m = morris_effects(traj, f, d, s.morris_resamples, s.morris_confidence);
    nlohmann::json curves = nlohmann::json::array(), labels = nlohmann::json::array();
    for (std::size_t i = 0; i < d; ++i) {
      // The exact μ* where the function has one for this input (a linear model: not for a non-uniform input).
      const std::optional<double> exact_mu_star = i < exact.morris_mu_star.size() && !std::isnan(exact.morris_mu_star[i])
                                                      ? std::optional<double>(exact.morris_mu_star[i]) : std::nullopt;
      if (std::isfinite(m.mu_star[i]) && std::isfinite(m.sigma[i]))
        labels.push_back({{"x", m.mu_star[i]}, {"y", m.sigma[i]}, {"text", s.params[i].label}});
      rows.push_back({s.outputs[o], s.params[i].label, num(m.mu_star[i]),
                      fmt::format("[{}, {}]", num(m.mu_star_ci[i].low), num(m.mu_star_ci[i].high)), num(m.mu_star_conf[i]), num(m.mu[i]),
                      num(m.sigma[i]), std::to_string(m.effects[i]), exact_mu_star ? num(*exact_mu_star) : ""});
      curves.push_back({{"label", s.params[i].label}, {"x", {jnum(m.mu_star[i])}}, {"y", {jnum(m.sigma[i])}}, {"style", "points"}});
      const std::string mu_star_exact = exact_mu_star ? fmt::format("{:.17g}", *exact_mu_star) : std::string();
      for (const auto& [index, iv, ex] : {std::tuple{"mu_star", m.mu_star_ci[i], mu_star_exact}, std::tuple{"mu", m.mu_ci[i], std::string()},
                                          std::tuple{"sigma", m.sigma_ci[i], std::string()}})
        an.idx_csv << "morris," << s.outputs[o] << ",\"" << s.params[i].label << "\"," << index << ","
                   << fmt::format("{:.17g},{:.17g},{:.17g},", iv.estimate, iv.low, iv.high) << ex << "\n";
      if (s.function && s.noise_sd > 0.0 && exact_mu_star == 0.0) {
        // An inert input of a noisy function: its |EE| is |ε' − ε|/Δ, ε ~ N(0, σ²/R): μ* = 2σ / (Δ √(π R)).
        const double floor = 2.0 * s.noise_sd / (morris_delta(s.levels) * std::sqrt(std::numbers::pi * static_cast<double>(s.replicates.size())));
        const Interval& iv = m.mu_star_ci[i];
        an.add_check(fmt::format("Morris μ* of the inert {} = the noise floor ({} + noise σ = {}, R = {})", s.params[i].label, s.function->name,
                                 num(s.noise_sd), s.replicates.size()),
                     floor, iv.estimate, std::abs(iv.estimate - floor), floor < iv.estimate ? iv.estimate - iv.low : iv.high - iv.estimate,
                     fmt::format("the {:.0f} % bootstrap interval of μ* must contain 2σ/(Δ√(πR))", 100.0 * s.morris_confidence),
                     floor >= iv.low && floor <= iv.high, fmt::format("interval [{}, {}]", num(iv.low), num(iv.high)));
      }
      if (exact_mu_star && s.noise_sd == 0.0) {
        const double e = std::abs(m.mu_star[i] - *exact_mu_star);
        const double tol = 1e-9 * std::max(1.0, *exact_mu_star);
        an.add_check(fmt::format("Morris μ* of {} ({})", s.params[i].label, s.function->name), *exact_mu_star,
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
    an.figures.push_back(mu_star_figure(s, m, o));
  }
  an.tables.push_back({{"title", fmt::format("Morris elementary effects (unit coordinates: per full range; {} trajectories, {} levels, Δ = {:.4g})",
                                             s.trajectories, s.levels, morris_delta(s.levels))},
                       {"columns", {"output", "parameter", "μ*", fmt::format("{:.0f} % bootstrap interval", 100.0 * s.morris_confidence),
                                    "μ*_conf (SALib)", "μ", "σ", "effects", "exact μ*"}},
                       {"rows", rows}});
}

}  // namespace ver::sens
