#pragma once
// An ensemble (study.toml [ensemble]): every variant of a `single` study run as `members` runs that differ
// only by a tiny perturbation of the start (a member number given to one case key, e.g. the jitter seed of
// an ordered fill). A chaotic run (a silo's discharge) is one draw; a claim about it is checked on the
// ensemble: the mean of each probe over the members, its sample standard deviation and the Student-t
// confidence interval of the mean. A check passes only if the whole interval satisfies it.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dem/cases/case_reader.hpp"

namespace ver {

struct Ensemble {
  std::int64_t members = 0;     // runs per variant (≥ 2)
  std::string seed;             // the case key that takes the member number 1 … members
  std::vector<std::string> set; // overrides of every member (e.g. the jitter that the seed places)
  double confidence = 0.95;     // of the interval of the mean
  std::uint32_t line = 0;       // of [ensemble] in the study file
};

/// One probe over the members that gave a value: mean, sample standard deviation, count, and the
/// half-width of the confidence interval of the mean (t_{(1+c)/2, n−1} sd / √n; none below 2 values).
struct EnsembleStat {
  std::optional<double> mean, sd, half_width;
  std::size_t n = 0, members = 0;
  std::optional<double> low() const { return mean && half_width ? std::optional<double>(*mean - *half_width) : std::nullopt; }
  std::optional<double> high() const { return mean && half_width ? std::optional<double>(*mean + *half_width) : std::nullopt; }
};

/// [ensemble] of a study file; none when absent. Refused for a kind other than single (`kind` given).
std::optional<Ensemble> read_ensemble(const dem::TableReader& top, bool single_kind);

/// The overrides of member k (1-based): the ensemble's own, then seed = k.
std::vector<std::string> member_sets(const Ensemble& e, std::int64_t k);

/// The statistics of one probe's values (missing values are counted in `members`, not in `n`).
EnsembleStat ensemble_stat(const std::vector<std::optional<double>>& values, double confidence);

/// Student-t quantile t_{p, dof} (p in (0, 1), dof ≥ 1).
double student_t_quantile(double p, double dof);

/// "m ± h (95 % CI, n = 8, sd s)" for notes and tables.
std::string stat_words(const EnsembleStat& st, double confidence);

/// result.json's `ensemble` entry: members, seed key, overrides, confidence.
nlohmann::json ensemble_json(const Ensemble& e);

}  // namespace ver
