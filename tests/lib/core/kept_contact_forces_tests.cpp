// Contact forces kept only by the steps that report them (Simulation::keep_contact_forces; bench/journal.md,
// "Contact forces kept only for the steps that report them"): a step that skips them changes no other bit,
// on 1, 2 and 3 threads; every reader of the forces refuses a step that skipped them; a run keeps them
// wherever its outputs read them, and a signal during a step that skipped them stops the run one step
// later with everything written.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/run.hpp"
#include "../test_support.hpp"

using Catch::Matchers::Contains;

namespace {

struct KeptCase {
  const char* path;
  std::vector<std::string> sets;
  int steps;
};

// Disks settling on walls (disk–disk contacts from about step 700), and a silo of disks at rest from the start.
const std::vector<KeptCase> kCases = {
    {"cases/bench/settle_10k.toml", {"numerics.duration=4e-3"}, 1000},
    {"cases/silo/static_11_12.toml", {"numerics.duration=0.05 s"}, 500},
};

}  // namespace

TEST_CASE("Steps that do not keep the contact forces change no other bit, on 1, 2 and 3 threads", "[threads][outputs]") {
  for (const KeptCase& kc : kCases) {
    const dem::Case c = dem::read_case(test::source(kc.path), kc.sets);
    for (int t = 1; t <= 3; ++t) {
      CAPTURE(kc.path, t);
      dem::Simulation kept(c.model), skipped(c.model);
      kept.set_threads(t, 1);
      skipped.set_threads(t, 1);
      int compared = 0, refused = 0;
      for (int k = 1; k <= kc.steps; ++k) {
        const bool report = k % 50 == 0 || k == kc.steps;
        skipped.keep_contact_forces(report);
        kept.step();
        skipped.step();
        REQUIRE(skipped.contact_forces_current() == report);
        REQUIRE(kept.contact_forces_current());
        if (report) {
          // the whole state: positions, velocities, histories, and the forces of every touching contact
          CAPTURE(k);
          CHECK(dem::simulation_state(kept) == dem::simulation_state(skipped));
          ++compared;
          continue;
        }
        if (k % 10 != 0) continue;
        CHECK(skipped.contact_count() == kept.contact_count());  // a count needs no forces
        std::size_t pair = 0;
        const std::vector<dem::ContactView> cs = kept.contacts();
        while (pair < cs.size() && cs[pair].wall) ++pair;
        if (pair == cs.size()) continue;  // no element–element contact yet
        CHECK_THROWS_AS(skipped.contacts(), std::logic_error);
        CHECK_THROWS_AS(skipped.contact_force_sum(), std::logic_error);
        CHECK_THROWS_WITH(skipped.contact(cs[pair].i, cs[pair].j, false), Contains("were not kept"));
        CHECK_THROWS_WITH(dem::simulation_state(skipped), Contains("were not kept"));
        ++refused;
      }
      CHECK(compared == kc.steps / 50 + (kc.steps % 50 != 0));
      CHECK(refused >= 10);
    }
  }
}

TEST_CASE("A run whose series reads contact forces keeps them at every step", "[outputs]") {
  // No snapshot, picture, probe or stop criterion: only the series asks for the forces (a row every 7
  // steps, and contacts from about step 500).
  const dem::Case c = dem::read_case(test::source("cases/bench/settle_10k.toml"),
                                     {"numerics.duration=2.4e-3", "output.series=[\"t\", \"unbalanced_force_ratio\"]",
                                      "output.every=7"});
  dem::RunOptions o;
  o.out_dir = test::fresh_dir("dem2d_kept_forces", "series");
  const dem::RunResult r = dem::run_case(c, o);
  CHECK(r.status == "completed");
  CHECK(r.steps == 600);
}

TEST_CASE("A signal during a step that did not keep the contact forces stops the run after the next step", "[outputs]") {
  // The bench settle writes no snapshot and reads no force: its steps skip the contact forces, which a
  // stopped run's checkpoint saves. The signal arrives while a step runs (the steps take most of the time).
  const dem::Case c = dem::read_case(test::source("cases/bench/settle_10k.toml"), {"numerics.duration=0.4"});
  dem::RunOptions o;
  o.out_dir = test::fresh_dir("dem2d_kept_forces", "signal");
  std::atomic<bool> done{false};
  std::thread sender([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    if (!done) dem::set_interrupt_signal(SIGTERM);  // as the handler does
  });
  dem::RunResult r;
  try {
    r = dem::run_case(c, o);
  } catch (...) {
    done = true;
    sender.join();
    dem::set_interrupt_signal(0);
    throw;
  }
  done = true;
  sender.join();
  dem::set_interrupt_signal(0);
  REQUIRE(r.status == "interrupted");
  CHECK(r.steps < 100000);
  const dem::Checkpoint ck = dem::read_checkpoint(o.out_dir / "checkpoint.bin");
  CHECK(ck.step == r.steps);
}
