#include "dem/run/run_threads.hpp"

#include <algorithm>

#include "dem/core/usable_cores.hpp"

namespace dem {

int threads_for_run(int asked) { return std::max(1, std::min(asked, usable_cores())); }

nlohmann::json threads_summary(const Simulation& sim, int asked) {
  const ThreadGovernor& g = sim.governor();
  return {{"asked", asked},
          {"usable_cores", usable_cores()},
          {"used", sim.threads()},
          {"governor_probes", g.probes()},
          {"steps_on_fewer_threads", g.steps_below_most()}};
}

nlohmann::json timings_summary(const Simulation& sim) {
  const StepTimings t = sim.step_timings();
  const std::vector<PoolThreadTimes> pool = sim.pool_times();
  // thread 0's time inside step() that no job and no phase holds (on one thread there are no jobs)
  double serial = t.step_wall - t.step_jobs;
  if (pool.empty() && !t.threads.empty())
    serial -= t.threads[0].rebuild + t.threads[0].sweep + t.threads[0].integrate + t.threads[0].gather;
  nlohmann::json threads = nlohmann::json::array();
  for (std::size_t k = 0; k < t.threads.size(); ++k) {
    const PhaseTimes& p = t.threads[k];
    const PoolThreadTimes w = k < pool.size() ? pool[k] : PoolThreadTimes{};
    threads.push_back({{"rebuild", p.rebuild},
                       {"sweep", p.sweep},
                       {"integrate", p.integrate},
                       {"gather", p.gather},
                       {"wait", w.wait},
                       {"wake", w.wake},
                       {"sleeps", w.sleeps}});
  }
  return {{"steps", t.steps},
          {"rebuilds", t.rebuilds},
          {"step_wall", t.step_wall},
          {"step_jobs", t.step_jobs},
          {"step_serial", serial},
          {"rebuild_cells", t.rebuild_serial},
          {"per_thread", threads},
          {"units", "s (sleeps: count)"},
          {"phases", "rebuild (inside the step: test, cells, candidates, merges, index), sweep (contact laws), "
                     "integrate (K17-K19 and the next rebuild test), gather (the shared elements' sums), wait "
                     "(barriers, the threads before, thread 0: the job's end), wake (job start to worker start); "
                     "step_serial: thread 0 outside the jobs inside step()"}};
}

}  // namespace dem
