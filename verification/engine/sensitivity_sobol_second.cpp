// Second-order Sobol' indices of a sensitivity study ([sobol] second_order = true): S_ij with bootstrap
// intervals from the runs of A, B, AB_i and BA_i (sensitivity_second_order.hpp) — table rows,
// indices.csv rows (parameter "label_i:label_j", index S2) and, for a test function with exact S_ij,
// two checks per pair: the interval contains the exact value, and |S_ij − exact| is within the declared
// second_order_tolerance.
#include <cmath>

#include <fmt/format.h>

#include "engine/sensitivity_second_order.hpp"
#include "engine/sensitivity_study.hpp"

namespace ver::sens {

void second_order_rows(const DesignOutputs& y, const ExactIndices& exact, const std::string& yname, const std::string& tsuffix,
                       nlohmann::json& rows, Analysis& an) {
  const Sens& s = an.s;
  const std::vector<SecondOrderIndex> s2 = sobol_second_order(y.fa, y.fb, y.fab, y.fba, s.resamples, s.confidence);
  for (const SecondOrderIndex& p : s2) {
    const std::string pair = s.params[p.i].label + ":" + s.params[p.j].label;
    const bool known = !exact.second.empty();
    const double ex = known ? exact.second[p.i][p.j] : std::nan("");
    rows.push_back({yname, pair, num(p.s2.estimate), fmt::format("[{}, {}]", num(p.s2.low), num(p.s2.high)), known ? num(ex) : ""});
    an.idx_csv << "sobol," << yname << ",\"" << pair << "\",S2," << fmt::format("{:.17g},{:.17g},{:.17g},", p.s2.estimate, p.s2.low, p.s2.high)
               << (known ? fmt::format("{:.17g}", ex) : std::string()) << "\n";
    if (!known || !s.function) continue;
    const std::string q = fmt::format("S2_{}{} of {} ({}, N = {}{})", p.i + 1, p.j + 1, pair, s.function->name, s.samples, tsuffix);
    const double e = std::abs(p.s2.estimate - ex);
    const double half = ex < p.s2.estimate ? p.s2.estimate - p.s2.low : p.s2.high - p.s2.estimate;
    an.add_check(q + ": interval", ex, p.s2.estimate, e, half,
                 fmt::format("the {:.0f} % bootstrap interval ({} resamples of the N rows) must contain the exact value", 100.0 * s.confidence,
                             s.resamples),
                 ex >= p.s2.low && ex <= p.s2.high, fmt::format("interval [{}, {}]", num(p.s2.low), num(p.s2.high)));
    if (s.second_order_tolerance)
      an.add_check(q, ex, p.s2.estimate, e, *s.second_order_tolerance, s.second_order_reason, e <= *s.second_order_tolerance, "");
  }
}

}  // namespace ver::sens
