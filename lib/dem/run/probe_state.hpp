#pragma once
// A probe during a run: its accumulators, sampled after every step, and its value at the end
// (value, max, min, mean, time_of_*, crossing, slope, restitution, contact_duration; case_file.hpp
// ProbeSpec says what each measures). The accumulators are saved in checkpoints (loop_state.hpp).
#include <cstdint>
#include <map>
#include <string>
#include <optional>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/quantities.hpp"

namespace dem {

/// Tracks one probe during the run.
struct ProbeState {
  const ProbeSpec* spec = nullptr;
  QuantityFn q;
  double prev_t = 0.0, prev_v = 0.0;
  std::optional<double> value;
  double extreme = 0.0;
  bool have_extreme = false;
  double vn_prev = 0.0;  // normal relative velocity of the state before this step (approach positive)
  double extreme_t = 0.0;                                    // time_of_max / time_of_min
  double st = 0.0, sq = 0.0, stt = 0.0, stq = 0.0, sn = 0.0;  // slope: least-squares sums; mean: sq, sn
  std::optional<double> crossing;
  // restitution: the first contact event; duration: steps with force
  Vec2 n_prev, n_in;     // contact normal of the state before this step, and at the first touch
  double vn_in = 0.0, vn_out = 0.0;
  bool touched = false, separated = false;
  QuantityFn x;                                               // slope `against`: abscissa (else t)
  double x0 = 0.0;                                            //   its first value in the window
  std::int64_t force_steps = 0;
  bool in_contact = false;
};

/// The case's probes at the start of the run (their quantities compiled against sim's model, the first
/// sample taken). Throws CaseError for a slope's `against` that is no quantity.
std::vector<ProbeState> start_probes(const Case& c, const Simulation& sim);

/// Samples a probe after a step.
void sample_probe(ProbeState& p, const Simulation& sim);

/// A probe's value at the end of the run; none when it has none (or it is not a finite number), and for
/// a ratio (ratio_results).
std::optional<double> probe_result(const ProbeState& p, const Simulation& sim);

/// The ratio probes' values from the other probes' results (none if either part has none, the
/// denominator is 0 or the quotient is not finite).
void ratio_results(const std::vector<ProbeState>& probes, std::map<std::string, std::optional<double>>& results);

}  // namespace dem
