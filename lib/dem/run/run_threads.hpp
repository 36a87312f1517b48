#pragma once
// The threads of a run as summary.json reports them: how many were asked for, how many the process may use
// (core/usable_cores.hpp: affinity mask, cgroup quota), how many ran, what the governor did
// (core/thread_governor.hpp), and, with `run --timings`, where the steps' time went per thread and phase
// (core/step_timings.hpp). No result depends on any of it.
#include <nlohmann/json.hpp>

#include "dem/core/simulation.hpp"

namespace dem {

/// The threads a run takes when `asked` are asked for: at most the usable cores (more would only wait for
/// each other; the results are the same for any number).
int threads_for_run(int asked);

/// summary.json's "threads": asked, usable_cores, used, governed, governor probes and steps below.
nlohmann::json threads_summary(const Simulation& sim, int asked);

/// summary.json's "timings" (run --timings): per thread and phase [s], the serial part of the steps, the pool's
/// waits, wake-ups and sleeps.
nlohmann::json timings_summary(const Simulation& sim);

}  // namespace dem
