// Running a case (lib/dem/run.hpp): the outputs a run writes, bit-for-bit repeatability, and a blow-up
// that stops the run with a message while keeping what was written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <sstream>

#include "dem/run/quantities.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"
#include "../vtp_reader.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

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
  // CSV: one header line with each column's unit (no comment: pandas.read_csv defaults read it), the
  // first row at t = 0, every 10th step, and the last row: 2000 steps / 10 + 1 rows.
  std::ifstream csv(out / "series.csv");
  std::string line;
  std::getline(csv, line);
  CHECK(line == "t [s],e0.y [m],e0.vy [m/s],e0.fn.floor [N]");
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
  // the time loop's CPU time: positive, and on one thread not above its wall-clock time (1 ms: clock reads)
  CHECK(j["cpu_seconds"].get<double>() > 0.0);
  CHECK(j["cpu_seconds"].get<double>() <= j["wall_seconds"].get<double>() + 1e-3);
  CHECK(j["case_as_read"]["numerics"]["dt"] == "1e-5 s");  // the TOML after overrides, as written
  CHECK(j["provenance"].contains("compiler"));
  // the resolved case: SI numbers, every default filled in
  const auto& rc = j["resolved_case"];
  CHECK(rc["numerics"]["dt"].get<double>() == Approx(1e-5).epsilon(1e-15));
  CHECK(rc["numerics"]["integrator"] == "K18");
  CHECK(rc["numerics"]["velocity_start"] == "plain");
  REQUIRE(rc["contacts"].size() == 1);
  CHECK(rc["contacts"][0]["onset"] == "increment");
  CHECK(rc["contacts"][0]["end_rule"] == "elastic");
  CHECK(rc["contacts"][0]["kn"].is_number());
  CHECK(rc["elements"]["total_mass"].get<double>() > 0.0);
  CHECK(rc["output"]["series"][1]["unit"] == "m");
  // every probe with its unit
  CHECK(j["probes"]["e"]["value"].is_number());
  CHECK(j["probes"]["e"]["unit"] == "1");
  for (const auto& [name, p] : j["probes"].items()) CHECK_FALSE(p["unit"].get<std::string>().empty());
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
  with.push_back("numerics.max_step_fraction=1e6");  // the energy criterion (run_guards_tests.cpp covers the kinematic one)
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
  const auto r = run("tests/lib/fixtures/settle.toml", out);
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
  const std::string c = "tests/lib/fixtures/after_peak.toml";
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
  CHECK_THROWS_WITH(run(c, out, {"stop.after_peak.quantity=e7.fy"}),
                    StartsWith("--set stop.after_peak.quantity=e7.fy: stop.after_peak.quantity: "));
  // ... at its line when the case file names an element it does not have
  std::string text = slurp(source(c));
  REQUIRE(text.find("quantity = \"e0.fn.floor\", drop") != std::string::npos);
  const fs::path bad = test::write_temp("after_peak_e7.toml", text.replace(text.find("quantity = \"e0.fn.floor\", drop"), 30,
                                                                           "quantity = \"e7.fy\", drop"));
  dem::RunOptions o;
  o.out_dir = out;
  CHECK_THROWS_WITH(dem::run_case(dem::read_case(bad), o), StartsWith(bad.string() + ":57: stop.after_peak.quantity: "));
  CHECK_THROWS_WITH(dem::check_outputs(dem::read_case(bad)), StartsWith(bad.string() + ":57: stop.after_peak.quantity: "));
}

TEST_CASE("A slope probe against another quantity gives dq/dx", "[run]") {
  // e1 flies at constant velocity (0.3, 1.0) m/s: d y / d x = 1/0.3 over any window.
  const std::string c = "tests/lib/fixtures/after_peak.toml";
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

TEST_CASE("Every series and probe quantity of every shipped case has a known unit", "[run][units]") {
  int quantities = 0;
  for (const auto& f : fs::recursive_directory_iterator(source("cases"))) {
    if (f.path().extension() != ".toml") continue;
    CAPTURE(f.path().string());
    const dem::Case c = dem::read_case(f.path());
    for (const auto& q : c.output.series) {
      INFO(q);
      CHECK(dem::quantity_unit(q) != "unknown");
      ++quantities;
    }
    for (const auto& p : c.probes)
      if (!p.quantity.empty()) {
        INFO(p.quantity);
        CHECK(dem::quantity_unit(p.quantity) != "unknown");
        ++quantities;
      }
  }
  CHECK(quantities > 100);
}

TEST_CASE("Every quantity name has its SI unit for the series header and the probes", "[run][units]") {
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"t", "s"}, {"step", "1"}, {"contacts", "1"}, {"energy.kinetic", "J"}, {"energy.total", "J"},
      {"mean_increment", "m"}, {"unbalanced_force_ratio", "1"}, {"e3.x", "m"}, {"e3.y", "m"}, {"e3.phi", "rad"},
      {"e3.vx", "m/s"}, {"e3.vy", "m/s"}, {"e3.omega", "rad/s"}, {"e3.fx", "N"}, {"e3.fy", "N"}, {"e3.moment", "N*m"},
      {"e3.px(1,-1)", "m"}, {"e0.py(0.5,-1)", "m"}, {"e0.gap.floor", "m"}, {"e0.gap.e1", "m"}, {"e0.fn.floor", "N"},
      {"e0.fs.e2", "N"}, {"e0.links.floor", "1"}, {"e0.mobilised.floor", "1"}, {"floor.fx", "N"}, {"floor.fy", "N"}, {"floor.x", "m"},
      {"floor.y", "m"}, {"plate_travel", "m"}, {"plate_dx", "m"}, {"plate_dy", "m"}, {"e0.corner_slide(38.5)", "m"},
      {"left.fn(0,0.0598)", "N"}, {"left.fs(0.1209,0.1814)", "N"}, {"walls.fx", "N"}, {"walls.fy", "N"},
      {"discharged.count", "1"}, {"discharged.mass", "kg"}, {"active.count", "1"}, {"active.mass", "kg"}};
  for (const auto& [name, unit] : expected) {
    INFO(name);
    CHECK(dem::quantity_unit(name) == unit);
  }
  CHECK(dem::quantity_unit("e0.colour") == "unknown");
  CHECK(dem::series_header("e0.vy") == "e0.vy [m/s]");
  CHECK(dem::series_column_name("e0.vy [m/s]") == "e0.vy");
  CHECK(dem::series_column_name("e0.px(1,-1) [m]") == "e0.px(1,-1)");
  CHECK(dem::series_column_name("t") == "t");
}

TEST_CASE("A run given its case by move reports and writes the same as a run given a copy", "[run][memory]") {
  // run_case moves the model into its Simulation (the elements exist once during the run); what the
  // summary reports of the case (counts, total mass) is taken before the move.
  const std::vector<std::string> sets = {"numerics.duration=8e-4", "output.every=50"};  // 200 steps
  dem::Case c = dem::read_case(source("cases/bench/settle_10k.toml"), sets);
  // read_case returns the element arrays without the generators' growth slack.
  CHECK(c.model.elements.x.capacity() == c.model.elements.size());
  CHECK(c.model.elements.active.capacity() == c.model.elements.size());
  const auto a = fresh_dir("by_copy"), b = fresh_dir("by_move");
  dem::RunOptions o;
  o.out_dir = a;
  const dem::RunResult copied = dem::run_case(c, o);
  REQUIRE(c.model.elements.size() == 10000);  // the caller's case is untouched
  o.out_dir = b;
  const dem::RunResult moved = dem::run_case(std::move(c), o);
  REQUIRE(copied.status == "completed");
  REQUIRE(moved.status == "completed");
  const auto& rc = moved.summary["resolved_case"]["elements"];
  CHECK(rc["count"].get<std::size_t>() == 10000);
  CHECK(rc["disks"].get<std::size_t>() == 10000);
  CHECK(rc["total_mass"].get<double>() == Approx(copied.summary["resolved_case"]["elements"]["total_mass"].get<double>()).epsilon(0));
  CHECK(rc["total_mass"].get<double>() > 70.0);  // 10^4 disks of 2650 pi r^2, r = 0.90-1.00 mm: 75.5 kg
  CHECK(moved.summary["resolved_case"] == copied.summary["resolved_case"]);
  CHECK(slurp(a / "series.csv") == slurp(b / "series.csv"));
}
