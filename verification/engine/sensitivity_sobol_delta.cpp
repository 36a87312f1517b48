// Borgonovo's δ in a sensitivity study (`[sobol] delta = true`): from the runs the Sobol' design
// already makes, the rows of A and B (independent points of the inputs' distribution), each output's
// δ_i with its bias-reduced bootstrap interval (sensitivity_delta.hpp) — a table, indices.csv rows and,
// for the Ishigami function, the check against the reference δ_i computed by quadrature
// (reference/ref/ishigami_delta.hpp).
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "engine/sensitivity_delta.hpp"
#include "engine/sensitivity_study.hpp"
#include "ref/ishigami_delta.hpp"

namespace ver::sens {

void analyse_delta(const Plan& plan, Analysis& an) {
  const Sens& s = an.s;
  const std::size_t d = s.params.size(), n = s.samples;
  std::vector<double> exact;  // Ishigami: quadrature with 100 nodes and 1000 cells (≤ 0.003 from the converged values, README)
  if (s.function && s.function->name == "ishigami") {
    const auto e = ref::ishigami_delta(s.function->coefficients.at(0), s.function->coefficients.at(1), 100, 1000);
    exact.assign(e.begin(), e.end());
  }
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t o = 0; o < s.outputs.size(); ++o) {
    std::vector<std::vector<double>> x(d);
    std::vector<double> y;
    for (std::size_t j = 0; j < 2 * n; ++j) {  // A then B
      const Run& r = plan.runs[plan.sobol_begin + j];
      for (std::size_t i = 0; i < d; ++i) x[i].push_back(r.u[i]);
      y.push_back(r.outputs[o]);
    }
    const std::vector<Interval> kernel = borgonovo_delta(x, y, s.delta_resamples, s.confidence);
    const std::vector<Interval> delta = histogram_delta(x, y, s.delta_resamples, s.confidence);
    for (std::size_t i = 0; i < d; ++i) {
      const Interval& iv = delta[i];
      rows.push_back({s.outputs[o], s.params[i].label, num(iv.estimate), fmt::format("[{}, {}]", num(iv.low), num(iv.high)),
                      num(kernel[i].estimate), fmt::format("[{}, {}]", num(kernel[i].low), num(kernel[i].high)), exact.empty() ? "" : num(exact[i])});
      for (const auto& [index, v] : {std::pair{"delta", iv}, std::pair{"delta_kernel", kernel[i]}})
        an.idx_csv << "delta," << s.outputs[o] << ",\"" << s.params[i].label << "\"," << index << ","
                   << fmt::format("{:.17g},{:.17g},{:.17g},", v.estimate, v.low, v.high)
                   << (exact.empty() ? std::string() : fmt::format("{:.17g}", exact[i])) << "\n";
      if (!exact.empty() && s.delta_tolerance) {
        const double e = std::abs(iv.estimate - exact[i]);
        an.add_check(fmt::format("Borgonovo δ_{} of {} (histogram estimator, {}, {} points)", i + 1, s.params[i].label, s.function->name, 2 * n), exact[i],
                     iv.estimate, e, *s.delta_tolerance, s.delta_reason, e <= *s.delta_tolerance,
                     fmt::format("interval [{}, {}]", num(iv.low), num(iv.high)));
      }
    }
  }
  an.tables.push_back({{"title", fmt::format("Borgonovo's moment-independent δ over the {} rows of A and B: by histograms (this project's, "
                                             "sensitivity_delta.hpp) and by kernel densities (Plischke, Borgonovo & Smith 2013, as SALib; biased "
                                             "low where the densities are sharp, findings F15); bias-reduced bootstrap, {} resamples, {:.0f} % intervals",
                                             2 * n, s.delta_resamples, 100.0 * s.confidence)},
                       {"columns", {"output", "parameter", "δ (histogram)", "interval", "δ (kernel, SALib)", "interval", "reference δ"}}, {"rows", rows}});
}

}  // namespace ver::sens
