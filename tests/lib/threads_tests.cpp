// Threads inside a run (docs/model.md §1 "Determinism", lib/dem/core/contact_index.hpp): the whole state
// after any number of steps, and every output file, are the same bit for bit on 1, 2 and 3 threads.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/run.hpp"
#include "test_support.hpp"

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

}  // namespace

TEST_CASE("The state after every step is the same bit for bit on 1, 2 and 3 threads", "[threads]") {
  for (const ThreadCase& tc : kCases) {
    CAPTURE(tc.path);
    const dem::Case c = dem::read_case(test::source(tc.path), tc.sets);
    std::vector<dem::Simulation> sims;
    for (int t = 1; t <= 3; ++t) {
      sims.emplace_back(c.model);
      sims.back().set_threads(t, 1);  // every case on t threads, however small
    }
    REQUIRE(dem::simulation_state(sims[0]) == dem::simulation_state(sims[1]));
    REQUIRE(dem::simulation_state(sims[0]) == dem::simulation_state(sims[2]));
    std::size_t most_contacts = 0;
    bool same = true;
    for (int k = 1; k <= tc.steps && same; ++k) {
      for (auto& s : sims) s.step();
      most_contacts = std::max(most_contacts, sims[0].contact_count());
      if (k % 50 == 0 || k == tc.steps) {
        const std::string one = dem::simulation_state(sims[0]);
        same = one == dem::simulation_state(sims[1]) && one == dem::simulation_state(sims[2]);
        CAPTURE(k);
        CHECK(same);
      }
    }
    CHECK(most_contacts > 0);  // the comparison covered contact forces
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
  CHECK(sim.threads_used() == 1);  // fewer than 4096 elements per thread
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
