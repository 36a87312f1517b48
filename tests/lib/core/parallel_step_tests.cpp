// Threads inside a run (docs/model.md §1 "Determinism", lib/dem/core/contact_index.hpp): the whole state
// after any number of steps, and every output file, are the same bit for bit on 1, 2 and 3 threads.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/core/worker_threads.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/run.hpp"
#include "../test_support.hpp"

namespace {

struct ThreadCase {
  const char* path;
  std::vector<std::string> sets;
  int steps;
};

// Disks with walls (contacts form from about step 500), a bonded PRE lattice with disks and a driven
// platen, PRE with base friction, a preloaded PRE, a silo of disks.
const std::vector<ThreadCase> kCases = {
    {"cases/bench/settle_10k.toml", {"numerics.duration=3.2e-3"}, 800},
    {"cases/beam/mortar_2x8.toml", {"numerics.duration=2e-3"}, 4000},
    {"cases/base_friction/mc_topple_75pre.toml", {"numerics.duration=0.5 s"}, 400},
    {"cases/pre/small_rotation.toml", {}, 400},
    {"cases/silo/static_11_12.toml", {"numerics.duration=0.05 s"}, 500},
    // spatial reordering at every rebuild (spatial_order.hpp): the order does not depend on the threads
    {"cases/silo/static_11_12.toml", {"numerics.duration=0.05 s", "numerics.reorder_every=1"}, 500},
};

/// Steps a case on 1, 2 and 3 threads side by side (every case on t threads, however small); every `every`
/// steps and at the end the whole states must be the same bits, and `also(sims)` adds its checks there.
/// Contacts must have formed (the comparison covered contact forces and histories).
template <class Also>
std::vector<dem::Simulation> same_on_1_2_3_threads(const ThreadCase& tc, int every, Also&& also) {
  const dem::Case c = dem::read_case(test::source(tc.path), tc.sets);
  std::vector<dem::Simulation> sims;
  for (int t = 1; t <= 3; ++t) {
    sims.emplace_back(c.model);
    sims.back().set_threads(t, 1);
  }
  REQUIRE(dem::simulation_state(sims[0]) == dem::simulation_state(sims[1]));
  REQUIRE(dem::simulation_state(sims[0]) == dem::simulation_state(sims[2]));
  std::size_t most_contacts = 0;
  bool same = true;
  for (int k = 1; k <= tc.steps && same; ++k) {
    for (auto& s : sims) s.step();
    most_contacts = std::max(most_contacts, sims[0].contact_count());
    if (k % every == 0 || k == tc.steps) {
      const std::string one = dem::simulation_state(sims[0]);
      same = one == dem::simulation_state(sims[1]) && one == dem::simulation_state(sims[2]);
      CAPTURE(k);
      CHECK(same);
      also(sims);
    }
  }
  CHECK(most_contacts > 0);
  return sims;
}

}  // namespace

TEST_CASE("The state after every step is the same bit for bit on 1, 2 and 3 threads", "[threads]") {
  for (const ThreadCase& tc : kCases) {
    CAPTURE(tc.path);
    same_on_1_2_3_threads(tc, 50, [](const std::vector<dem::Simulation>&) {});
  }
}

TEST_CASE("Every output file of a run is the same bit for bit on 1 and 3 threads", "[threads]") {
  for (const char* path : {"cases/beam/mortar_3pt.toml", "cases/silo/static_11_12.toml"}) {
    CAPTURE(path);
    const dem::Case c = dem::read_case(test::source(path), {"numerics.duration=2e-3"});
    std::vector<std::filesystem::path> outs;
    for (int t : {1, 3}) {
      dem::RunOptions o;
      o.out_dir = test::fresh_dir("dem2d_threads", std::string(std::filesystem::path(path).stem()) + "_t" + std::to_string(t));
      o.threads = t;
      o.governed = false;  // exactly t threads (the governor would choose by the machine's load)
      o.min_per_thread = 1;
      const dem::RunResult r = dem::run_case(c, o);
      REQUIRE(r.status == "completed");
      outs.push_back(o.out_dir);
    }
    CHECK(test::slurp(outs[0] / "series.csv") == test::slurp(outs[1] / "series.csv"));
    int files = 0;
    for (const auto& f : std::filesystem::recursive_directory_iterator(outs[0] / "vtk")) {
      if (!f.is_regular_file()) continue;
      ++files;
      CAPTURE(f.path().string());
      CHECK(test::slurp(f.path()) == test::slurp(outs[1] / std::filesystem::relative(f.path(), outs[0])));
    }
    CHECK(files > 0);
  }
}

TEST_CASE("A silo discharge (disks removed, a wall opened, keystones) is the same bit for bit on 1 and 3 threads", "[threads]") {
  // The gate opens at t = 0 and the unsettled fill pours out: elements turn inactive and their slots
  // empty mid-run, which the per-element sums must skip the same way on any number of threads.
  const dem::Case c = dem::read_case(test::source("cases/silo/fill_discharge_17_18.toml"),
                                     {"discharge.open_at=0 s", "numerics.duration=0.4 s", "output.vtk=false",
                                      "output.pictures=false", "output.picture_every=0 s"});
  std::vector<std::filesystem::path> outs;
  std::vector<double> discharged;
  for (int t : {1, 3}) {
    dem::RunOptions o;
    o.out_dir = test::fresh_dir("dem2d_threads", "discharge_t" + std::to_string(t));
    o.threads = t;
    o.governed = false;
    o.min_per_thread = 1;
    const dem::RunResult r = dem::run_case(c, o);
    REQUIRE(r.status == "completed");
    outs.push_back(o.out_dir);
  }
  const std::string a = test::slurp(outs[0] / "series.csv"), b = test::slurp(outs[1] / "series.csv");
  CHECK(a == b);
  // the run did discharge: the last row's discharged.count (second column) is positive
  const std::string last = a.substr(a.rfind('\n', a.size() - 2) + 1);
  const double count = std::stod(last.substr(last.find(',') + 1));
  CHECK(count > 0.0);
}

TEST_CASE("A thread count below one means one thread, and small runs use fewer threads", "[threads]") {
  dem::Simulation sim(dem::read_case(test::source("cases/beam/mortar_2x8.toml")).model);
  const std::size_t n = sim.model().elements.size();
  REQUIRE(n >= 16);
  sim.set_threads(0);
  CHECK(sim.threads() == 1);
  sim.set_threads(-3);
  CHECK(sim.threads() == 1);
  sim.set_threads(4);
  CHECK(sim.threads() == 4);
  CHECK(sim.threads_used() == 1);  // fewer than 1024 elements per thread
  sim.set_threads(4, 1);
  CHECK(sim.threads_used() == 4);
  sim.set_threads(4, n / 2);
  CHECK(sim.threads_used() == 2);
}

TEST_CASE("The kinematic blow-up test finds the same element on 1, 2 and 3 threads", "[threads][trust]") {
  // 12 free disks far apart, no gravity, no contacts; their step increments v Δt relative to r = 1 cm
  // are set by their velocities. max_step_fraction 0.25: (|Δx|/r)² above 0.0625 is an overstep.
  auto run = [](const std::vector<double>& vx, int threads) {
    dem::Model m = test::make_model({{"disk", 1000.0}}, 1e-3);
    test::set_law(m, 0, 0, test::linear_law(1e6, 0.0, 0.0, 0.0, 0.0));
    m.numerics.max_step_fraction = 0.25;
    for (std::size_t k = 0; k < vx.size(); ++k) {
      const std::size_t i = dem::add_element(m, dem::Shape::disk, 0, 0.01, {1.0 * static_cast<double>(k), 0.0});
      m.elements.mass[i] = m.elements.inertia[i] = 1.0;
      m.elements.inv_mass[i] = m.elements.inv_inertia[i] = 1.0;
      m.elements.vx[i] = vx[i];
    }
    dem::Simulation sim(m);
    sim.set_threads(threads, 1);
    sim.step();
    return sim.overstep();
  };
  const double nan = std::nan("");
  // v Δt / r: 0.1 (below), 0.3 and 0.5 (above); two equal largest (the first counts), a NaN (counts first)
  const std::vector<std::vector<double>> rows = {
      {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1},         // none
      {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 3, 1},         // element 10, in the last share
      {1, 3, 1, 1, 1, 5, 1, 1, 5, 1, 3, 1},         // 5 and 8 equally fast: 5
      {1, 3, 1, 1, 1, 5, 1, 1, 1, nan, 3, -7},      // the NaN at 9, although 11 moved farther
      {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2.5000001}, // just above, the last element
      {1, 1, 1, -nan, 1, 1, 1, 1, 1, 1, 1, 1},      // only a NaN (with its sign bit set)
  };
  const std::vector<std::size_t> expected = {dem::Simulation::Overstep::npos, 10, 5, 9, 11, 3};
  for (std::size_t r = 0; r < rows.size(); ++r) {
    CAPTURE(r);
    for (int t = 1; t <= 3; ++t) {
      CAPTURE(t);
      const dem::Simulation::Overstep o = run(rows[r], t);
      CHECK(o.index == expected[r]);
      if (r == 1) CHECK_THAT(o.fraction2, Catch::Matchers::WithinRel(0.09, 1e-12));  // (3 · 1e-3 / 0.01)²
    }
  }
}

TEST_CASE("Measured times move the boundaries between the threads' shares towards equal work", "[threads]") {
  // 1024 elements without slots (work 1 each): two shares of 512. Thread 0 took twice as long per
  // element: its elements weigh 2, thread 1's 1, total 3 × 512, so the boundary moves to 1.5 × 512 / 2 = 384.
  const std::vector<dem::SlotPair> none;
  const std::vector<dem::FaceSlot> no_faces;
  const std::vector<dem::LinearSlot> no_walls;
  dem::ThreadShares s;
  s.build(2, 1024, none, no_faces, no_walls, no_faces);
  REQUIRE(s.first == std::vector<std::uint32_t>{0, 512, 1024});
  s.balance({2.0, 1.0}, none, no_faces, no_walls, no_faces, false);
  CHECK(s.first == std::vector<std::uint32_t>{0, 384, 1024});
  // the next build (after a rebuild) keeps the measured rates per element range
  s.build(2, 1024, none, no_faces, no_walls, no_faces);
  CHECK(s.first == std::vector<std::uint32_t>{0, 384, 1024});
  // an equal cost per element brings it back; a thread without time takes the mean rate
  s.balance({384.0, 640.0}, none, no_faces, no_walls, no_faces, false);
  CHECK(s.first == std::vector<std::uint32_t>{0, 512, 1024});
  s.balance({0.0, 1.0}, none, no_faces, no_walls, no_faces, false);
  CHECK(s.first == std::vector<std::uint32_t>{0, 512, 1024});
  // thread 1 three times slower: 512 + (2 − 1) / (3/512) elements, 682
  s.forget_rates();
  s.balance({1.0, 3.0}, none, no_faces, no_walls, no_faces, false);
  CHECK(s.first == std::vector<std::uint32_t>{0, 682, 1024});
  // three threads: the shared elements are those of a fresh division at the same boundaries
  std::vector<dem::SlotPair> pairs;
  for (std::uint32_t i = 0; i + 7 < 1024; i += 3) pairs.push_back({i, i + 7});
  s.forget_rates();
  s.build(3, 1024, pairs, no_faces, no_walls, no_faces);
  s.balance({1.0, 2.0, 4.0}, pairs, no_faces, no_walls, no_faces, false);
  // work 1:2:4 per unit of estimate: the boundaries move to about 5/9 and 29/36 of the estimate (569, 825)
  CHECK(s.first[1] > 540);
  CHECK(s.first[1] < 600);
  CHECK(s.first[2] > 800);
  CHECK(s.first[2] < 850);
  for (std::uint32_t e = 0; e < 1024; ++e) {
    bool shared = false;
    for (const dem::SlotPair& p : pairs) {
      const auto owner = [&](std::uint32_t k) { return k < s.first[1] ? 0 : k < s.first[2] ? 1 : 2; };
      if (p.j == e && owner(p.i) != owner(p.j)) shared = true;
    }
    CAPTURE(e);
    CHECK((s.shared[e] != 0) == shared);
  }
}

TEST_CASE("Moving the boundaries between the threads' shares between steps changes no result bit", "[threads]") {
  // Any split gives the same sums: the shares of 2 and 3 threads are moved every few steps to arbitrary
  // places (as the measured-time balance does), also in steps with a rebuild, and compared with 1 thread.
  std::int64_t most_rebuilds = 0;
  for (const ThreadCase& tc : {kCases[0], kCases[1], kCases[4]}) {
    CAPTURE(tc.path);
    const dem::Case c = dem::read_case(test::source(tc.path), tc.sets);
    std::vector<dem::Simulation> sims;
    for (int t = 1; t <= 3; ++t) {
      sims.emplace_back(c.model);
      sims.back().set_threads(t, 1);
    }
    const int steps = std::min(tc.steps, 800);
    bool same = true, moved = false;
    for (int k = 1; k <= steps && same; ++k) {
      for (auto& s : sims) s.step();
      if (k % 3 == 0) {
        const double a = 1.0 + (k * 7 % 11), b = 1.0 + (k * 5 % 13), d = 1.0 + (k % 4);
        const std::vector<std::uint32_t> before = sims[2].share_bounds();
        sims[1].balance_threads({a, b});
        sims[2].balance_threads({a, b, d});
        moved = moved || sims[2].share_bounds() != before;
      }
      if (k % 50 == 0 || k == steps) {
        const std::string one = dem::simulation_state(sims[0]);
        same = one == dem::simulation_state(sims[1]) && one == dem::simulation_state(sims[2]);
        CAPTURE(k);
        CHECK(same);
      }
    }
    CHECK(moved);
    CHECK(sims[1].balances() > 0);
    most_rebuilds = std::max(most_rebuilds, sims[0].rebuilds());
  }
  CHECK(most_rebuilds > 2);  // the moved shares also met rebuilds (the silo)
}

TEST_CASE("The rebuild test made by the last step's integration rebuilds at the very steps of a test made at the start", "[threads]") {
  // A step takes its rebuild test from the previous step's integration (static walls), and skips it while
  // the travel bound shows that no element can have moved far enough (Simulation::travel_); a mutable
  // model() makes the step test by itself at its start, every element, as before, and voids the bound.
  // Both must rebuild at the same steps with the same results, on 1 and on 2 threads. Cases: the silo at
  // rest, from step 100 without its first ten disks (removed: the pass with a select, their old increments
  // out of the bound); the same reordered at every rebuild; the falling rows of the bench settle (10 ms).
  const ThreadCase tc = GENERATE(ThreadCase(kCases[4]), ThreadCase(kCases[5]),  // copies: a reference would dangle
                                 ThreadCase{"cases/bench/settle_10k.toml", {"numerics.duration=10e-3"}, 2500});
  const bool silo = std::string(tc.path).find("silo") != std::string::npos;
  const dem::Case c = dem::read_case(test::source(tc.path), tc.sets);
  for (int threads : {1, 2}) {
    CAPTURE(tc.path, tc.sets.size(), threads);
    dem::Simulation fused(c.model), own(c.model);
    fused.set_threads(threads, 1);
    own.set_threads(threads, 1);
    bool same = true;
    for (int k = 1; k <= tc.steps && same; ++k) {
      own.model();  // may have changed: test at the start of the step, exactly (the integration's is unused)
      if (silo && k == 100)
        for (dem::Simulation* s : {&fused, &own})
          for (std::size_t i = 0; i < 10; ++i) s->model().elements.active[i] = 0;
      fused.step();
      own.step();
      same = fused.rebuilds() == own.rebuilds();
      CAPTURE(k);
      CHECK(same);
    }
    CHECK(own.rebuilds() > 2);
    // the bound skipped the tests over at least a third of the steps (2 threads: two ranges per thread)
    CHECK(fused.rebuild_tests_skipped() > tc.steps / 3);
    CHECK(dem::simulation_state(fused) == dem::simulation_state(own));
  }
}

TEST_CASE("Rebuilds at almost every step give the same candidates and slots bit for bit on 1, 2 and 3 threads", "[threads]") {
  // A skin far below the step's displacements makes nearly every step rebuild: the candidates are collected
  // by element ranges and joined, the slot lists merged by ranges (slots moving forward, backward and across
  // the ranges' boundaries), inside the step's job (a driven platen: the step tests by itself) and as a job
  // of its own (static walls: the last step's integration tested), with and without spatial reordering.
  // simulation_state holds the candidates, every slot with its history, and the elements.
  const std::vector<ThreadCase> cases = {
      {"cases/bench/settle_10k.toml", {"numerics.duration=3.2e-3", "numerics.skin=1e-7"}, 800},
      {"cases/beam/mortar_2x8.toml", {"numerics.duration=2e-3", "numerics.skin=1e-9"}, 1500},
      {"cases/silo/static_11_12.toml",
       {"numerics.duration=0.05 s", "numerics.skin=1e-7", "numerics.reorder_every=3"},
       500},
  };
  for (const ThreadCase& tc : cases) {
    CAPTURE(tc.path);
    const auto sims = same_on_1_2_3_threads(tc, 25, [](const std::vector<dem::Simulation>& at) {
      for (std::size_t t = 1; t < at.size(); ++t) {  // summed in chunks that do not depend on the threads
        const dem::Energies a = at[0].energies(), b = at[t].energies();
        CHECK((a.kinetic == b.kinetic && a.potential == b.potential && a.elastic == b.elastic));
      }
    });
    CHECK(sims[0].rebuilds() > tc.steps / 2);  // the rebuilds were frequent
    for (auto& s : sims) CHECK(s.rebuilds() == sims[0].rebuilds());
  }
}

TEST_CASE("wait_earlier waits for what the threads before the caller wrote, and not for the threads after it",
          "[threads]") {
  using namespace std::chrono_literals;
  for (int nt : {2, 3, 4}) {
    dem::WorkerThreads pool(nt);
    for (int job = 0; job < 30; ++job) {
      std::vector<int> written(static_cast<std::size_t>(nt), -1);  // plain ints: published by signal/wait
      std::vector<std::vector<int>> seen(static_cast<std::size_t>(nt));
      std::atomic<int> past_wait{0};
      bool timed_out = false;
      auto body = [&](int t) {
        const auto k = static_cast<std::size_t>(t);
        // the earlier the thread, the later it writes: a thread that does not wait reads -1
        std::this_thread::sleep_for(std::chrono::microseconds(300 * (nt - 1 - t)));
        if (t == nt - 1) {  // the last thread signals only once every other thread is past its wait
          const auto give_up = std::chrono::steady_clock::now() + 2s;
          while (past_wait.load() < nt - 1 && !timed_out) timed_out = std::chrono::steady_clock::now() > give_up;
        }
        written[k] = job;
        pool.signal_done(t);
        pool.wait_earlier(t);
        for (int s = 0; s < t; ++s) seen[k].push_back(written[static_cast<std::size_t>(s)]);
        ++past_wait;
      };
      pool.run(body);
      CAPTURE(nt, job);
      CHECK_FALSE(timed_out);  // a wait for a later thread would have held the others until the time-out
      for (int t = 0; t < nt; ++t) CHECK(seen[static_cast<std::size_t>(t)] == std::vector<int>(static_cast<std::size_t>(t), job));
    }
  }
}
