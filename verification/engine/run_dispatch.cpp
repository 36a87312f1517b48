#include "engine/run_dispatch.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "dem/cases/case_file.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/run.hpp"
#include "engine/progress.hpp"
#include "engine/run_cache.hpp"

namespace ver {

namespace {
RunDistributor* g_distributor = nullptr;
}

double run_cost(const dem::Case& c) {
  const dem::Numerics& n = c.model.numerics;
  const double steps = n.dt > 0.0 ? std::ceil(n.duration / n.dt - 1e-9) : 1.0;  // as `dem2d check` counts them
  return std::max(1.0, steps) * std::max<double>(1.0, static_cast<double>(c.model.elements.size()));
}

RunReply run_here(const RunRequest& req, const std::filesystem::path& out_dir) {
  if (dem::interrupt_signal() != 0) return {"interrupted", "interrupted before the run started", 0.0, {}};
  try {
    dem::RunOptions o;
    o.out_dir = out_dir;
    const dem::RunResult r = dem::run_case(dem::read_case(req.case_file, req.sets), o);
    const double per_step = r.steps > 0 ? r.wall_seconds / static_cast<double>(r.steps) : 0.0;
    return {r.status, r.message, r.element_steps_per_second, r.probes, per_step};
  } catch (const dem::CaseError& e) {
    return {"case-error", e.what(), 0.0, {}};
  }
}

void set_run_distributor(RunDistributor* d) { g_distributor = d; }
RunDistributor* run_distributor() { return g_distributor; }

void run_all(const std::vector<RunRequest>& reqs, int jobs, const RunDone& done_here) {
  if (reqs.empty()) return;
  Progress* progress = current_progress();
  if (progress) progress->planned(reqs.size());
  // Each finished run is told to the progress line; its time is the work over its speed.
  const RunDone done = [&](std::size_t i, RunReply& r) {
    const std::vector<std::string> sets = reqs[i].sets;
    const std::string status = r.status;
    const double seconds = r.eps > 0.0 ? reqs[i].cost / r.eps : std::nan("");
    done_here(i, r);
    if (progress) progress->finished(status, seconds, sets);
  };
  if (g_distributor) {
    g_distributor->run(reqs, done);
    return;
  }
  // Longest first (ties: in the order given), so that a long run does not start last.
  std::vector<std::size_t> order(reqs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return reqs[a].cost > reqs[b].cost; });
  parallel_for(order.size(), jobs, [&](std::size_t k) {
    const std::size_t i = order[k];
    RunReply r = run_here(reqs[i], reqs[i].out);
    done(i, r);
  });
}

}  // namespace ver
