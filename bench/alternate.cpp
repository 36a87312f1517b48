// dem2d_alternate: two dem2d runs interleaved inside one process, a block of steps of one, then a block of
// the other, and so on, each block timed on its own (bench/journal.md, "Ratios interleaved block by block").
//
//   dem2d_alternate A.toml[@THREADS] B.toml[@THREADS] [--block 50] [--steps N] [--set key=value ...] [--json FILE]
//                   [--min-per-thread 4096]
//
// What it is for: a ratio of two dem2d runs (2 threads against 1 on the same case; a PRE lattice with faces
// of N = 5 segments against N = 1) on a machine whose speed drifts by tens of per cent from one second to the
// next. Separate runs, even interleaved, then compare different moments of the machine; here both sides
// meet the same moments, a few milliseconds apart, and the ratio of each pair of blocks is taken. The
// median of those ratios and their quartiles are printed, with the ratio of the two sides' total times.
//
// Each side is a Simulation built from its case as `dem2d run` builds it, stepping with the contact forces
// kept only at the end (as a run without outputs). Only the steps count: no series, probes or stop criteria,
// and no discharge (a case with [discharge] is refused). If both sides run the same case with the same
// overrides (threads aside), or with --compare, their final states (positions, rotations, velocities) are
// compared bit for bit and a difference is an error (exit 1): results must not depend on the thread count,
// nor on what --compare is asked to vouch for (the skin: when the neighbour lists are rebuilt). The arrays
// are compared index by index: with numerics.reorder_every > 0 a change of skin reorders the elements at
// other steps, and the states then read as different.
// The ratio printed is time of A / time of B per block: the speed ratio B / A when both sides have the same
// number of elements (2 threads against 1; PRE lattices of one size).
// Exit status: 0; 1 (the states differ); 2 (a wrong run spec or case, printed with its file:line); 3 (a
// blow-up: an element moved more than numerics.max_step_fraction of its radius, or NaN, as dem2d run
// stops); CLI11's own codes for an unknown option.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "block_ratios.hpp"
#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"

namespace {

struct Side {
  std::string spec;  // as given: CASE[@THREADS]
  std::string path;
  int threads = 1;
  std::unique_ptr<dem::Simulation> sim;
  std::size_t elements = 0;
  double seconds = 0.0;  // wall-clock time of its blocks
  std::vector<double> block_seconds;
};

// "case.toml@2" → ("case.toml", 2); "case.toml" → ("case.toml", 1).
bool parse_spec(Side& s, std::string& error) {
  s.path = s.spec;
  const auto at = s.spec.rfind('@');
  if (at == std::string::npos) return true;
  s.path = s.spec.substr(0, at);
  const std::string t = s.spec.substr(at + 1);
  char* end = nullptr;
  const long n = std::strtol(t.c_str(), &end, 10);
  if (t.empty() || *end != '\0' || n < 1 || n > 1024) {
    error = fmt::format("{}: expected CASE or CASE@THREADS with THREADS a whole number from 1 to 1024, got '{}'", s.spec, t);
    return false;
  }
  s.threads = static_cast<int>(n);
  return true;
}

bool same_state(const dem::Simulation& a, const dem::Simulation& b) {
  const dem::Elements& x = a.model().elements;
  const dem::Elements& y = b.model().elements;
  auto same = [](const std::vector<double>& p, const std::vector<double>& q) {
    return p.size() == q.size() && std::memcmp(p.data(), q.data(), p.size() * sizeof(double)) == 0;
  };
  return same(x.x, y.x) && same(x.y, y.y) && same(x.phi, y.phi) && same(x.vx, y.vx) && same(x.vy, y.vy) &&
         same(x.omega, y.omega) && x.active == y.active;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dem2d_alternate: two dem2d runs interleaved block by block in one process; the ratio of their speeds"};
  std::vector<std::string> specs;
  long block = 50;
  long steps = 0;
  std::vector<std::string> overrides, overrides_side[2];
  bool compare = false;
  std::string json_path;
  std::size_t min_per_thread = 4096;
  app.add_option("runs", specs, "two runs: CASE[@THREADS] CASE[@THREADS] (threads default 1)")->required()->expected(2);
  app.add_option("--block", block, "steps per block (default 50)")->check(CLI::Range(1L, 1000000L));
  app.add_option("--steps", steps, "steps of each run (default: the case's duration / dt; the smaller of the two)")
      ->check(CLI::Range(1L, 1000000000L));
  app.add_option("--set", overrides, "key=value override, applied to both cases");
  app.add_option("--set-a", overrides_side[0], "key=value override of A only");
  app.add_option("--set-b", overrides_side[1], "key=value override of B only");
  app.add_flag("--compare", compare,
               "compare the final states bit for bit even if the cases or overrides differ (a change that must not "
               "change results, e.g. numerics.skin)");
  app.add_option("--json", json_path, "also write the result as JSON to this file");
  app.add_option("--min-per-thread", min_per_thread,
                 "elements per thread at least, as dem2d run's (default 4096; tests: 1)")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  std::error_code ec_old;
  if (!json_path.empty()) std::filesystem::remove(json_path, ec_old);  // never a stale result if this run fails

  Side side[2];
  std::int64_t total = 0;
  try {
    for (int k = 0; k < 2; ++k) {
      Side& s = side[k];
      s.spec = specs[static_cast<std::size_t>(k)];
      std::string error;
      if (!parse_spec(s, error)) {
        fmt::print(stderr, "dem2d_alternate: {}\n", error);
        return 2;
      }
      std::vector<std::string> all = overrides;
      all.insert(all.end(), overrides_side[k].begin(), overrides_side[k].end());
      dem::Case c = dem::read_case(s.path, all);
      dem::check_outputs(c);
      dem::check_case(c);  // the time-step guard and the initial overlaps, as `dem2d run`
      if (c.model.discharge.enabled) {
        fmt::print(stderr, "dem2d_alternate: {}: [discharge] is not supported (the run loop removes the disks)\n", s.path);
        return 2;
      }
      const dem::Numerics& n = c.model.numerics;
      const auto case_steps = static_cast<std::int64_t>(std::llround(std::ceil(n.duration / n.dt - 1e-9)));
      total = k == 0 ? case_steps : std::min(total, case_steps);
      s.sim = std::make_unique<dem::Simulation>(std::move(c.model));
      s.sim->set_threads(s.threads, min_per_thread);
      s.sim->keep_contact_forces(false);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", e.what());
    return 2;
  }
  if (steps > 0) total = steps;
  if (total < 1) {
    fmt::print(stderr, "dem2d_alternate: numerics.duration / numerics.dt gives no step to run (--steps N)\n");
    return 2;
  }
  std::error_code ec0, ec1;
  const bool same_path = std::filesystem::weakly_canonical(side[0].path, ec0) == std::filesystem::weakly_canonical(side[1].path, ec1);
  const bool same_case = compare || (same_path && overrides_side[0] == overrides_side[1]);

  // Blocks: A, B, A, B, …; which side starts alternates from pair to pair (a side that always ran second
  // would always meet caches warmed by the other).
  using clock = std::chrono::steady_clock;
  try {
    for (std::int64_t done = 0; done < total;) {
      const std::int64_t n = std::min<std::int64_t>(block, total - done);
      const bool last = done + n == total;
      const int first = static_cast<int>((done / block) % 2);
      for (int q = 0; q < 2; ++q) {
        Side& s = side[(first + q) % 2];
        const auto t0 = clock::now();
        for (std::int64_t i = 0; i < n; ++i) {
          if (last && i + 1 == n) s.sim->keep_contact_forces(true);
          s.sim->step();
        }
        const double secs = std::chrono::duration<double>(clock::now() - t0).count();
        s.seconds += secs;
        s.block_seconds.push_back(secs);
        // the blow-up test of dem2d run (its kinematic part), once per block: timings of a run that blew up
        // mean nothing
        if (const dem::Simulation::Overstep o = s.sim->overstep(); o.index != dem::Simulation::Overstep::npos) {
          fmt::print(stderr, "dem2d_alternate: {}: blow-up by step {}: element {} moved {:.4g} of its radius in one step\n",
                     s.spec, s.sim->steps(), s.sim->id_of(o.index), std::sqrt(o.fraction2));
          return 3;
        }
      }
      done += n;
    }
  } catch (const std::exception& e) {  // e.g. too many contact slots for the contact index
    fmt::print(stderr, "dem2d_alternate: {}\n", e.what());
    return 2;
  }

  for (Side& s : side) {
    s.elements = 0;
    for (auto a : s.sim->model().elements.active) s.elements += a;
  }
  const bench::BlockRatios br = bench::block_ratios(side[0].block_seconds, side[1].block_seconds);
  const double median = br.median, q1 = br.q1, q3 = br.q3;
  const double total_ratio = side[0].seconds / side[1].seconds;
  nlohmann::json j;
  j["block"] = block;
  j["steps"] = total;
  j["pairs"] = br.pairs;
  for (int k = 0; k < 2; ++k) {
    const Side& s = side[k];
    j[k == 0 ? "a" : "b"] = {{"run", s.spec},
                             {"threads", s.threads},
                             {"threads_used", s.sim->threads_used()},
                             {"elements", s.elements},
                             {"seconds", s.seconds},
                             {"element_steps_per_second", static_cast<double>(s.elements) * static_cast<double>(total) / s.seconds}};
  }
  j["speed_ratio_b_over_a"] = {{"median", median}, {"q1", q1}, {"q3", q3}, {"of_totals", total_ratio}};
  j["provenance"] = dem::provenance();
  fmt::print("A  {}: {:.2f} M element-steps/s ({} elements, {:.3f} s)\n", side[0].spec,
             j["a"]["element_steps_per_second"].get<double>() / 1e6, side[0].elements, side[0].seconds);
  fmt::print("B  {}: {:.2f} M element-steps/s ({} elements, {:.3f} s)\n", side[1].spec,
             j["b"]["element_steps_per_second"].get<double>() / 1e6, side[1].elements, side[1].seconds);
  fmt::print("speed B / A over {} pairs of {}-step blocks: median {:.3f} (quartiles {:.3f} … {:.3f}); of the totals {:.3f}\n",
             br.pairs, block, median, q1, q3, total_ratio);
  int status = 0;
  if (same_case) {
    const bool same = same_state(*side[0].sim, *side[1].sim);
    j["final_states_identical"] = same;
    fmt::print("final states {}\n", same ? "identical bit for bit" : "DIFFER (the same case, threads aside, or --compare)");
    if (!same) status = 1;
  }
  if (!json_path.empty()) {
    try {
      dem::write_file_atomic(json_path, j.dump(2) + "\n");  // whole or not at all
    } catch (const std::exception& e) {
      fmt::print(stderr, "dem2d_alternate: {}\n", e.what());
      return 2;
    }
  }
  return status;
}
