#include <algorithm>

#include <fmt/format.h>

#include "dem/run/interrupt.hpp"
#include "engine/run_cache.hpp"
#include "engine/run_dispatch.hpp"
#include "engine/study_run.hpp"

// kind = "stability": per variant, the stability limit of a parameter (Δt) by bisection between a
// stable and an unstable bound, each probe run with the time-step guard's refusal off; a blow-up is
// "unstable". The limit is the probe "limit" of the variant.

namespace ver {

void run_stability(StudyRun& run) {
  const Study& s = run.s;
  const StudyOptions& opt = run.opt;
  std::vector<std::optional<double>> limits(s.variants.size());
  std::vector<std::string> notes(s.variants.size());
  // Under MPI every variant's bisection runs at once (each waits for one run at a time).
  const int threads = run_distributor() ? std::max<int>(opt.jobs, static_cast<int>(s.variants.size())) : opt.jobs;
  parallel_for(s.variants.size(), threads, [&](std::size_t vi) {
    const Variant& v = s.variants[vi];
    auto stable = [&](double x) {
      std::vector<std::string> sets = s.set;
      sets.insert(sets.end(), v.set.begin(), v.set.end());
      sets.push_back(fmt::format("{}={:.17g}", s.parameter, x));
      sets.push_back("numerics.allow_unstable=true");
      return run.run_one(sets).status != "blow-up";
    };
    double lo = s.low, hi = s.high;
    if (!stable(lo)) {
      limits[vi] = 0.0;
      notes[vi] = fmt::format("unstable already at the lower bound {:.6g}", lo);
      return;
    }
    if (stable(hi)) {
      notes[vi] = fmt::format("stable up to the upper bound {:.6g}", hi);
      return;
    }
    // rel_tol ≥ 1e-12 (study_file.cpp) ends this within ~40 halvings; a signal ends it at once.
    while ((hi - lo) > s.rel_tol * lo) {
      if (dem::interrupt_signal()) throw StudyInterrupted(fmt::format("study {}: interrupted during the bisection", s.name));
      const double mid = 0.5 * (lo + hi);
      (stable(mid) ? lo : hi) = mid;
    }
    limits[vi] = 0.5 * (lo + hi);
  });
  for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {  // probe "limit" for figures and tables
    RunOut r;
    r.probes["limit"] = limits[vi];
    run.finest_runs.push_back(r);
  }
  for (const Check& c : s.checks)
    for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
      if (!applies(c, s.variants[vi])) continue;
      run.add_check(check_label(c, s.variants[vi]), run.reference_of(c, s.variants[vi], 0.0), limits[vi], c, std::nullopt, notes[vi]);
    }
}

}  // namespace ver
