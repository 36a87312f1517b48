#pragma once
// The run loop's own state (run.cpp): the blow-up bound and the energy scale it is made of, the settle
// window, the peak so far, a silo discharge's clock and keystones; packed into numbers for checkpoints
// (checkpoint.hpp) together with the probes' accumulators (probe_state.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "dem/core/model.hpp"
#include "dem/run/probe_state.hpp"

namespace dem {

/// The energy scale of a run (what the blow-up bound is made of) [J]: the kinetic and elastic energy
/// after the first step `e1`, plus the work gravity can do over the region the elements can reach, plus
/// the work the drives can do.
struct EnergyScale {
  double total = 0.0, gravity_work = 0.0, drive_work = 0.0, drop = 0.0;
};
EnergyScale energy_scale(const Model& m, double e1);

// The run loop's own state, for checkpoints: the blow-up bound and the settle window, then per probe
// its accumulators. Every member of ProbeState that changes during a run must be listed here, or a
// restart is no longer bit for bit (tests/lib/run/output_files_tests.cpp).
struct LoopState {
  double energy_limit = 0.0, potential0 = 0.0;
  EnergyScale scale;
  std::int64_t quiet_steps = 0;
  double peak_so_far = 0.0;  // [stop] after_peak: the largest |q| so far
  // [discharge]: the time of the last removal (a disk out, or a keystone), and every keystone removed
  double last_release = 0.0;
  bool slit_opened = false;  // open_at reached (the case's wall is closed until then)
  struct Keystone {
    double t = 0.0, element = 0.0, x = 0.0, y = 0.0;
  };
  std::vector<Keystone> keystones;
};

/// The loop's state and the probes' accumulators as numbers (a checkpoint's `loop`).
std::vector<double> loop_state(const LoopState& l, const std::vector<ProbeState>& probes);
/// The inverse of loop_state(); throws CaseError, naming `what` (the checkpoint file), when the numbers do
/// not fit the case's probes or a count or flag is not a whole number in its range.
void restore_loop_state(const std::vector<double>& v, LoopState& l, std::vector<ProbeState>& probes,
                        const std::string& what);

}  // namespace dem
