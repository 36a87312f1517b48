// Running a case (lib/dem/run.hpp): the outputs a run writes, bit-for-bit repeatability, and a blow-up
// that stops the run with a message while keeping what was written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <sstream>

#include "dem/run/run.hpp"

#include "test_support.hpp"
#include "vtp_reader.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using test::slurp;
using test::source;

fs::path fresh_dir(const std::string& name) {
  const auto d = test::fresh_dir("dem2d_unit_run", name);
  return d;
}


dem::RunResult run(const std::string& case_rel, const fs::path& out, const std::vector<std::string>& sets = {}) {
  dem::RunOptions o;
  o.out_dir = out;
  return dem::run_case(dem::read_case(source(case_rel), sets), o);
}

}  // namespace

TEST_CASE("A run writes the series CSV, the JSON summary with provenance, and VTK snapshots", "[run]") {
  const auto out = fresh_dir("outputs");
  const auto r = run("cases/impact/disk_wall.toml", out);
  REQUIRE(r.status == "completed");
  // CSV: a comment with the case and code version, the header, the first row at t = 0, every 10th
  // step, and the last row: 2000 steps / 10 + 1 rows.
  std::ifstream csv(out / "series.csv");
  std::string line;
  std::getline(csv, line);
  CHECK_THAT(line, Contains("# case:") && Contains("disk_wall.toml"));
  std::getline(csv, line);
  CHECK(line == "t,e0.y,e0.vy,e0.fn.floor");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == 201);
  // JSON summary: the case, the overrides, provenance, timing, probes.
  nlohmann::json j;
  std::ifstream(out / "summary.json") >> j;
  CHECK(j["status"] == "completed");
  CHECK(j["steps"] == 2000);
  for (const char* k : {"code_version", "build_type", "date", "machine"}) CHECK(j["provenance"].contains(k));
  CHECK(j["element_steps_per_second"].get<double>() > 0.0);
  CHECK(j["resolved_case"]["numerics"]["dt"] == "1e-5 s");
  CHECK(j["probes"]["e"].is_number());
  // VTK: a first and a last snapshot, listed in the .pvd collection, with contact forces as cells.
  int snapshots = 0;
  for (const auto& f : fs::directory_iterator(out / "vtk")) snapshots += f.path().extension() == ".vtp";
  CHECK(snapshots == 2);
  const std::string pvd = slurp(out / "snapshots.pvd");
  CHECK_THAT(pvd, Contains("snapshot_000000000.vtp") && Contains("snapshot_000002000.vtp"));
  const std::string vtp = slurp(out / "vtk" / "snapshot_000000000.vtp");
  CHECK_THAT(vtp, Contains("<VTKFile type=\"PolyData\"") && Contains("Name=\"normal_force\"") &&
                      Contains("Name=\"radius\""));
}

TEST_CASE("Same inputs give the same outputs, bit for bit", "[run]") {
  const auto a = fresh_dir("repeat_a"), b = fresh_dir("repeat_b");
  // A multi-contact PRE run (a bonded block toppling on a slope) and a disk impact.
  for (const std::string c : {"cases/pre/block_mode.toml", "cases/impact/disk_disk.toml"}) {
    CAPTURE(c);
    const std::vector<std::string> sets = {"numerics.duration=0.005", "output.every=50",
                                           "output.series=[\"t\", \"e0.x\", \"e0.y\", \"e0.phi\", \"energy.total\"]"};
    run(c, a, sets);
    run(c, b, sets);
    const std::string sa = slurp(a / "series.csv"), sb = slurp(b / "series.csv");
    CHECK(sa.size() > 200);
    CHECK(sa == sb);
    if (fs::exists(a / "vtk")) {  // block_mode.toml writes no snapshots
      CHECK(slurp(a / "snapshots.pvd") == slurp(b / "snapshots.pvd"));
      for (const auto& f : fs::directory_iterator(a / "vtk"))
        CHECK(slurp(f.path()) == slurp(b / "vtk" / f.path().filename()));
    }
  }
}

TEST_CASE("A blow-up stops the run with a message and keeps what was written", "[run]") {
  // K19 without damping is unstable at every Δt (docs/references.md §1.5): the guard refuses it, the
  // override lets it run, the energy criterion stops it.
  const auto out = fresh_dir("blowup");
  const std::vector<std::string> sets = {"numerics.integrator=K19", "numerics.dt=1e-3", "output.every=10",
                                         "output.series=[\"t\", \"e0.y\"]"};
  CHECK_THROWS_AS(run("cases/oscillator/bonded_face.toml", out, sets), dem::CaseError);
  auto with = sets;
  with.push_back("numerics.allow_unstable=true");
  with.push_back("numerics.max_step_fraction=1e6");  // the energy criterion (trust_tests.cpp covers the kinematic one)
  const auto r = run("cases/oscillator/bonded_face.toml", out, with);
  CHECK(r.status == "blow-up");
  CHECK_THAT(r.message, Contains("runaway energy") && Contains("stability limit"));
  CHECK(r.steps < 12566);  // stopped before the end
  nlohmann::json j;
  std::ifstream(out / "summary.json") >> j;
  CHECK(j["status"] == "blow-up");
  // The series up to the blow-up is there: one row every 10 steps, plus the first and the last.
  std::ifstream csv(out / "series.csv");
  std::string line;
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows >= static_cast<int>(r.steps / 10));
}

TEST_CASE("The static criterion stops a settled run early", "[run]") {
  const auto out = fresh_dir("settle");
  const auto r = run("tests/lib/cases/settle.toml", out);
  CHECK(r.status == "settled");
  // ζ = 0.7 at ω₀ ≈ 5.6e3 rad/s: the motion decays as e^{−ζω₀t}, far below 1e-15 m/step within 0.1 s
  // of the 1 s asked for, and not before the 1 ms minimum.
  CHECK(r.steps > 100);
  CHECK(r.steps < 10000);
}

TEST_CASE("The after-peak criterion stops a run once the force has dropped by the given fraction", "[run]") {
  // A disk hits the floor (ζ = 0.3, contact ≈ 3.3 ms of the 20 ms asked for): the contact force rises
  // to its peak and falls to zero; with drop = 0.5 the run must end when it has halved, mid-contact.
  const auto out = fresh_dir("after_peak");
  const std::string c = "tests/lib/cases/after_peak.toml";
  const auto r = run(c, out);
  CHECK(r.status == "past peak");
  REQUIRE(r.probes.at("peak"));
  REQUIRE(r.probes.at("last"));
  const double peak = *r.probes.at("peak"), last = *r.probes.at("last");
  CHECK(peak > 0.0);
  CHECK(last <= 0.5 * peak);
  CHECK(last > 0.45 * peak);  // the first step below half the peak, not the end of the contact
  CHECK(r.steps > 140);       // past the peak (≈ 1.3 ms = 130 steps) ...
  CHECK(r.steps < 330);       // ... and before the contact ends (≈ 3.3 ms), long before 2000 steps
  // A smaller drop stops earlier; a criterion that starts after the contact never fires.
  const auto r2 = run(c, fresh_dir("after_peak2"), {"stop.after_peak.drop=0.1"});
  CHECK(r2.status == "past peak");
  CHECK(r2.steps < r.steps);
  const auto r3 = run(c, fresh_dir("after_peak3"), {"stop.after_peak.from=5e-3"});
  CHECK(r3.status == "completed");
  // Wrong input is refused before anything runs.
  CHECK_THROWS_WITH(run(c, out, {"stop.after_peak.drop=1.5"}), Contains("stop.after_peak") && Contains("drop"));
  CHECK_THROWS_WITH(run(c, out, {"stop.after_peak.quantity=e7.fy"}), Contains("stop.after_peak.quantity"));
}

TEST_CASE("A slope probe against another quantity gives dq/dx", "[run]") {
  // e1 flies at constant velocity (0.3, 1.0) m/s: d y / d x = 1/0.3 over any window.
  const std::string c = "tests/lib/cases/after_peak.toml";
  const auto r = run(c, {}, {"stop.after_peak.from=1"});
  REQUIRE(r.probes.at("dy_dx"));
  CHECK_THAT(*r.probes.at("dy_dx"), Catch::Matchers::WithinRel(1.0 / 0.3, 1e-9));
  CHECK_THROWS_WITH(run(c, {}, {"probe.2.against=e1.nothing"}), Contains("against"));
}

TEST_CASE("Snapshots show the crack: each contact line carries its linked segments", "[run][vtk]") {
  // The M-D beam (2 x 8, N = 5) past its peak: some faces keep all 5 links, some lost part of them.
  const auto out = fresh_dir("crack");
  const auto r = run("cases/beam/mortar_2x8.toml", out, {"output.vtk=true", "output.vtk_every=1000"});
  REQUIRE(r.status == "past peak");
  std::vector<fs::path> snaps;
  for (const auto& f : fs::directory_iterator(out / "vtk")) snaps.push_back(f.path());
  REQUIRE(snaps.size() > 3);
  std::sort(snaps.begin(), snaps.end());
  snaps.erase(snaps.begin());  // t = 0: before the first sweep, no contact has its links yet
  auto links_of = [](const fs::path& p) { return test::vtp_array<std::int32_t>(slurp(p), "links"); };
  const auto first = links_of(snaps.front()), last = links_of(snaps.back());
  CHECK(std::count(first.begin(), first.end(), 5) > 0);
  CHECK(std::count_if(first.begin(), first.end(), [](int n) { return n > 1 && n < 5; }) == 0);  // intact early in the loading
  CHECK(std::count_if(last.begin(), last.end(), [](int n) { return n >= 1 && n < 5; }) >
        std::count_if(first.begin(), first.end(), [](int n) { return n >= 1 && n < 5; }));  // broken faces
}
