// An ensemble study's runs (study_ensemble.hpp): each variant once per member, then folded into one
// run per variant whose probes are the members' means, with each probe's interval in
// run.ensemble_stats, every member in members.csv and a table of the checked probes' intervals (the
// ensemble's noise floor) in the report.
#include <algorithm>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dem/run/output_files.hpp"
#include "engine/study_run.hpp"

namespace ver {

std::vector<Planned> member_plan(const StudyRun& run, const std::vector<Planned>& per_variant) {
  const Ensemble& e = *run.s.ensemble;
  std::vector<Planned> plan;
  for (const Planned& p : per_variant)
    for (std::int64_t k = 1; k <= e.members; ++k) {
      Planned m{p.sets, k == 1 ? p.out : std::filesystem::path{}};  // member 1 feeds the figures
      const std::vector<std::string> extra = member_sets(e, k);
      m.sets.insert(m.sets.end(), extra.begin(), extra.end());
      plan.push_back(m);
    }
  return plan;
}

namespace {

/// members.csv: every member's status and every probe (each named once, in name order; a probe a member
/// lacks is empty).
void write_members_csv(const StudyRun& run, const std::vector<RunOut>& runs) {
  const Study& s = run.s;
  const auto nm = static_cast<std::size_t>(s.ensemble->members);
  std::set<std::string> names;
  for (const auto& r : runs)
    for (const auto& [name, value] : r.probes) names.insert(name);
  std::ostringstream csv;
  csv << "variant,member,status";
  for (const auto& name : names) csv << "," << name;
  csv << "\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    csv << '"' << s.variants[k / nm].label << "\"," << k % nm + 1 << "," << runs[k].status;
    for (const auto& name : names) csv << "," << fmt_value(probe_of(runs[k], name));
    csv << "\n";
  }
  dem::write_file_atomic(run.out / "members.csv", csv.str(), false);
}

/// The table of every checked probe's mean ± interval per variant: how far one run is from the mean.
void interval_table(StudyRun& run) {
  const Study& s = run.s;
  std::vector<std::string> probes;
  for (const auto& c : s.checks)
    if (std::find(probes.begin(), probes.end(), c.probe) == probes.end()) probes.push_back(c.probe);
  nlohmann::json columns = {"variant"}, rows = nlohmann::json::array();
  for (const auto& p : probes) columns.push_back(p);
  for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
    nlohmann::json row = {s.variants[vi].label};
    for (const auto& p : probes) {
      const EnsembleStat& st = run.ensemble_stats[vi].at(p);
      row.push_back(st.mean && st.half_width ? fmt::format("{:.4g} ± {:.2g} (sd {:.2g}, n = {})", *st.mean, *st.half_width, *st.sd, st.n)
                                             : fmt_value(st.mean));
    }
    rows.push_back(row);
  }
  run.tables.push_back({{"title", fmt::format("Ensemble of {} members per variant ({}, the member number as {}): each checked "
                                              "probe's mean ± the half-width of its {:g} % confidence interval, and the "
                                              "members' standard deviation (the spread of a single run)",
                                              s.ensemble->members, s.ensemble->set.empty() ? std::string("no other override")
                                                                                          : fmt::format("{}", fmt::join(s.ensemble->set, ", ")),
                                              s.ensemble->seed, 100.0 * s.ensemble->confidence)},
                        {"columns", columns}, {"rows", rows}});
}

}  // namespace

std::vector<RunOut> fold_members(StudyRun& run, const std::vector<RunOut>& runs) {
  const Study& s = run.s;
  const auto nm = static_cast<std::size_t>(s.ensemble->members);
  write_members_csv(run, runs);
  std::vector<RunOut> folded;
  for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
    std::set<std::string> names;
    for (const auto& c : s.checks) names.insert(c.probe);
    for (std::size_t k = 0; k < nm; ++k)
      for (const auto& [name, v] : runs[vi * nm + k].probes) names.insert(name);
    RunOut out;
    out.status = runs[vi * nm].status;
    std::map<std::string, EnsembleStat> stats;
    for (const auto& name : names) {
      std::vector<std::optional<double>> values;
      for (std::size_t k = 0; k < nm; ++k) values.push_back(probe_of(runs[vi * nm + k], name));
      stats[name] = ensemble_stat(values, s.ensemble->confidence);
      out.probes[name] = stats[name].mean;
    }
    double eps = 0.0, per_step = 0.0;
    for (std::size_t k = 0; k < nm; ++k) {
      const RunOut& m = runs[vi * nm + k];
      eps += m.eps / static_cast<double>(nm);
      per_step += m.seconds_per_step / static_cast<double>(nm);
      if (m.status == "blow-up" && out.status != "blow-up") {  // a blown-up member is said, not averaged away
        out.status = m.status;
        out.message = fmt::format("member {}: {}", k + 1, m.message);
      }
    }
    out.eps = eps;
    out.seconds_per_step = per_step;
    folded.push_back(out);
    run.ensemble_stats.push_back(std::move(stats));
  }
  interval_table(run);
  return folded;
}

}  // namespace ver
