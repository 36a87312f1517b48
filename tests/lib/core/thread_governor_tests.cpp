// The thread governor (lib/dem/core/thread_governor.hpp): fewer threads while the machine is busy, the same
// results bit for bit whatever it decides; the usable cores (usable_cores.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/core/thread_governor.hpp"
#include "dem/core/usable_cores.hpp"
#include "dem/run/checkpoint.hpp"
#include "../test_support.hpp"

namespace {

/// Feeds one window of equal step times (the probe's length while probing) and its wait share.
void window(dem::ThreadGovernor& g, double step_seconds, double wait_share) {
  int steps = 0;
  while (!g.add_step(step_seconds)) REQUIRE(++steps < 100);
  g.window_done(wait_share);
}

}  // namespace

TEST_CASE("The governor keeps every thread while the threads do not wait", "[threads][governor]") {
  dem::ThreadGovernor g;
  g.start(16);
  for (int k = 0; k < 200; ++k) window(g, 1e-3, 0.49);  // just under kWaitShare
  CHECK(g.threads() == 16);
  CHECK(g.probes() == 0);
  CHECK(g.steps_below_most() == 0);
}

TEST_CASE("The governor halves the threads when they wait and half of them make faster steps", "[threads][governor]") {
  dem::ThreadGovernor g;
  g.start(2);
  window(g, 5e-3, 0.9);  // the first two windows: the shares are being balanced, no probe
  CHECK(g.threads() == 2);
  window(g, 5e-3, 0.9);  // waits above kWaitShare: a probe on one thread next
  CHECK(g.threads() == 1);
  window(g, 1e-3, -1.0);  // the probe: faster, kept
  CHECK(g.threads() == 1);
  // back up after kStartHold windows: a probe on 2, slower, so 1 again; the next probe up waits 4x longer
  int windows_to_probe = 0;
  while (g.threads() == 1) {
    window(g, 1e-3, -1.0);
    ++windows_to_probe;
  }
  CHECK(windows_to_probe == dem::ThreadGovernor::kStartHold);
  window(g, 5e-3, 0.9);
  CHECK(g.threads() == 1);
  int next = 0;
  while (g.threads() == 1 && next < 1000) {
    window(g, 1e-3, -1.0);
    ++next;
  }
  CHECK(next == 4 * dem::ThreadGovernor::kStartHold);
}

TEST_CASE("A probe that is not faster returns to the threads before it", "[threads][governor]") {
  dem::ThreadGovernor g;
  g.start(8);
  window(g, 1e-3, 0.9);
  window(g, 1e-3, 0.9);
  REQUIRE(g.threads() == 4);   // probing
  window(g, 1e-3, 0.9);        // as fast as 8 (not faster): back to 8
  CHECK(g.threads() == 8);
  // the next probe down comes only after the hold (4 kStartHold windows after a loss), however much they wait
  for (int k = 1; k < 4 * dem::ThreadGovernor::kStartHold; ++k) {
    window(g, 1e-3, 0.9);
    CHECK(g.threads() == 8);
  }
  window(g, 1e-3, 0.9);
  CHECK(g.threads() == 4);
}

TEST_CASE("A machine that became quiet gets its threads back", "[threads][governor]") {
  dem::ThreadGovernor g;
  g.start(4);
  window(g, 4e-3, 0.9);
  window(g, 4e-3, 0.9);
  window(g, 3e-3, 0.9);  // the probe on 2 threads: faster, kept
  REQUIRE(g.threads() == 2);
  window(g, 3e-3, 0.9);  // waits still high: a probe on 1 thread next
  REQUIRE(g.threads() == 1);
  window(g, 2e-3, -1.0);  // 1 thread: faster, kept
  REQUIRE(g.threads() == 1);
  while (g.threads() == 1) window(g, 2e-3, -1.0);
  REQUIRE(g.threads() == 2);
  window(g, 1e-3, 0.1);  // now 2 threads make faster steps: kept, and later 4 again
  CHECK(g.threads() == 2);
  for (int k = 0; k < 10 && g.threads() == 2; ++k) window(g, 1e-3, 0.1);
  REQUIRE(g.threads() == 4);
  window(g, 0.5e-3, 0.1);
  CHECK(g.threads() == 4);
}

TEST_CASE("A cgroup CPU quota gives its cores rounded up, and no quota gives none", "[threads]") {
  CHECK(dem::cores_of_quota("200000 100000") == 2);
  CHECK(dem::cores_of_quota("150000 100000") == 2);
  CHECK(dem::cores_of_quota("100000 100000") == 1);
  CHECK(dem::cores_of_quota("50000 100000") == 1);
  CHECK(dem::cores_of_quota("1600000 100000") == 16);
  CHECK_FALSE(dem::cores_of_quota("max 100000"));
  CHECK_FALSE(dem::cores_of_quota("-1 100000"));  // cgroup v1: no quota
  CHECK_FALSE(dem::cores_of_quota(""));
  CHECK_FALSE(dem::cores_of_quota("abc 100000"));
  CHECK(dem::usable_cores() >= 1);
}

TEST_CASE("Of several cgroup quotas the smallest binds in any order", "[threads]") {
  CHECK(dem::smallest_quota_cores({"max 100000", "300000 100000", "150000 100000"}) == 2);
  CHECK(dem::smallest_quota_cores({"150000 100000", "300000 100000", "max 100000"}) == 2);
  CHECK(dem::smallest_quota_cores({"800000 100000", "100000 100000", "400000 100000"}) == 1);
  CHECK(dem::smallest_quota_cores({"", "max 100000", "400000 100000"}) == 4);
  CHECK_FALSE(dem::smallest_quota_cores({"max 100000", "", "-1 100000"}));
  CHECK_FALSE(dem::smallest_quota_cores({}));
}

TEST_CASE("Changing the thread count between steps, as the governor does, changes no result bit", "[threads][governor]") {
  struct Switched {
    const char* path;
    std::vector<std::string> sets;
    int steps;
  };
  const std::vector<Switched> cases = {
      {"cases/bench/settle_10k.toml", {"numerics.duration=3.2e-3"}, 800},
      {"cases/beam/mortar_2x8.toml", {"numerics.duration=2e-3"}, 800},
      {"cases/silo/static_11_12.toml", {"numerics.duration=0.05 s"}, 300},
  };
  for (const Switched& sc : cases) {
    CAPTURE(sc.path);
    const dem::Case c = dem::read_case(test::source(sc.path), sc.sets);
    dem::Simulation one(c.model), switched(c.model);
    one.set_threads(1, 1);
    switched.set_threads(3, 1);
    const int pattern[] = {3, 1, 2, 3, 2, 1};
    bool same = true;
    std::size_t most_contacts = 0;
    for (int k = 1; k <= sc.steps && same; ++k) {
      if (k % 7 == 0) switched.hold_threads(pattern[(k / 7) % 6]);  // every 7 steps another count
      one.step();
      switched.step();
      most_contacts = std::max(most_contacts, switched.contact_count());
      if (k % 50 == 0 || k == sc.steps) {
        same = dem::simulation_state(one) == dem::simulation_state(switched);
        CAPTURE(k);
        CHECK(same);
      }
    }
    CHECK(most_contacts > 0);
  }
}
