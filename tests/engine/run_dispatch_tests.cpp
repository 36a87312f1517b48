// engine/run_dispatch.hpp: run_all gives each request's result to its own slot whatever the order the
// runs finish in (the property the MPI distribution relies on), runs the longest first, and run_here
// reports a refused case and a pending interrupt without running.
#include <catch2/catch.hpp>

#include <csignal>
#include <mutex>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/run.hpp"
#include "engine/run_dispatch.hpp"

namespace {

const std::string kCase = std::string(DEM2D_SOURCE_DIR) + "/cases/oscillator/disk_on_wall.toml";

ver::RunRequest request(double dt) {
  const std::vector<std::string> sets = {fmt::format("numerics.dt={:.17g}", dt)};
  return {kCase, sets, {}, ver::run_cost(dem::read_case(kCase, sets))};
}

}  // namespace

TEST_CASE("run_dispatch: run_all puts every result in its request's slot, longest first", "[engine][dispatch]") {
  const std::vector<double> dts = {4e-5, 1e-5, 2e-5, 5e-6, 8e-5};
  std::vector<ver::RunRequest> reqs;
  for (double dt : dts) reqs.push_back(request(dt));
  REQUIRE(reqs[3].cost > reqs[1].cost);  // steps × elements: Δt = 5e-6 s is the longest
  CHECK(reqs[3].cost == Approx(6e-3 / 5e-6));

  std::vector<ver::RunReply> got(reqs.size());
  std::vector<std::size_t> started;
  std::mutex m;
  ver::run_all(reqs, 1, [&](std::size_t i, ver::RunReply& r) {
    std::lock_guard<std::mutex> l(m);
    started.push_back(i);
    got[i] = r;
  });
  CHECK(started == std::vector<std::size_t>{3, 1, 2, 0, 4});  // one thread: strictly longest first

  std::vector<ver::RunReply> threaded(reqs.size());
  ver::run_all(reqs, 3, [&](std::size_t i, ver::RunReply& r) { threaded[i] = r; });
  for (std::size_t i = 0; i < dts.size(); ++i) {
    const dem::RunResult direct = dem::run_case(dem::read_case(kCase, reqs[i].sets), {});
    INFO("dt = " << dts[i]);
    CHECK(got[i].status == "completed");
    REQUIRE(got[i].probes.at("y_tf").has_value());
    CHECK(*got[i].probes.at("y_tf") == *direct.probes.at("y_tf"));  // bit for bit
    CHECK(*threaded[i].probes.at("y_tf") == *direct.probes.at("y_tf"));
  }
  CHECK(*got[0].probes.at("y_tf") != *got[1].probes.at("y_tf"));  // the runs differ: a mix-up would show
}

TEST_CASE("run_dispatch: run_here reports a refused case and a pending interrupt without running", "[engine][dispatch]") {
  const ver::RunReply refused = ver::run_here({kCase, {"numerics.dt=1e-2"}, {}, 1.0}, {});  // far above the stability limit
  CHECK(refused.status == "case-error");
  CHECK(refused.message.find("dt") != std::string::npos);
  dem::set_interrupt_signal(SIGTERM);
  const ver::RunReply stopped = ver::run_here({kCase, {}, {}, 1.0}, {});
  dem::set_interrupt_signal(0);
  CHECK(stopped.status == "interrupted");
  CHECK(stopped.probes.empty());
}
