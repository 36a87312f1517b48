#include "engine/study_ensemble.hpp"

#include <cmath>

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

namespace ver {

std::optional<Ensemble> read_ensemble(const dem::TableReader& top, bool single_kind) {
  const toml::table* t = top.table("ensemble");
  if (!t) return std::nullopt;
  if (!single_kind) top.fail("ensemble", "an [ensemble] needs kind = \"single\" (each variant run as members)");
  dem::TableReader r(*t, "ensemble", top.file(), "verification/README.md");
  Ensemble e;
  e.members = r.integer("members", 2, 1000);
  e.seed = r.string("seed");
  if (e.seed.empty() || e.seed.find('=') != std::string::npos)
    r.fail("seed", "expected the case key that takes the member number, e.g. \"arrangement.0.seed\"");
  e.set = r.strings("set");
  e.confidence = r.number_in("confidence", 0.5, 0.999, 0.95);
  e.line = t->source().begin.line;
  r.finish();
  return e;
}

std::vector<std::string> member_sets(const Ensemble& e, std::int64_t k) {
  std::vector<std::string> sets = e.set;
  sets.push_back(fmt::format("{}={}", e.seed, k));
  return sets;
}

double student_t_quantile(double p, double dof) {
  return boost::math::quantile(boost::math::students_t_distribution<double>(dof), p);
}

EnsembleStat ensemble_stat(const std::vector<std::optional<double>>& values, double confidence) {
  EnsembleStat st;
  st.members = values.size();
  double sum = 0.0;
  for (const auto& v : values)
    if (v) sum += *v, ++st.n;
  if (st.n == 0) return st;
  const double mean = sum / static_cast<double>(st.n);
  st.mean = mean;
  if (st.n < 2) return st;
  double ss = 0.0;
  for (const auto& v : values)
    if (v) ss += (*v - mean) * (*v - mean);
  const double n = static_cast<double>(st.n);
  st.sd = std::sqrt(ss / (n - 1.0));
  st.half_width = student_t_quantile(0.5 + confidence / 2.0, n - 1.0) * *st.sd / std::sqrt(n);
  return st;
}

std::string stat_words(const EnsembleStat& st, double confidence) {
  if (!st.mean) return fmt::format("no member of {} gave a value", st.members);
  std::string missing = st.n < st.members ? fmt::format(", {} of {} gave none", st.members - st.n, st.members) : "";
  if (!st.half_width) return fmt::format("{:.4g} (one member{})", *st.mean, missing);
  return fmt::format("{:.4g} ± {:.2g} ({:g} % CI of the mean, n = {}, sd {:.2g}{})", *st.mean, *st.half_width,
                     100.0 * confidence, st.n, *st.sd, missing);
}

nlohmann::json ensemble_json(const Ensemble& e) {
  return {{"members", e.members}, {"seed", e.seed}, {"set", e.set}, {"confidence", e.confidence}};
}

}  // namespace ver
