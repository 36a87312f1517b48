// A silo's discharge stage (lib/dem/core/discharge.hpp, [discharge] in a case file): the slit wall is
// opened, a disk below the outlet line is removed exactly once (inactive, never renumbered) and stops
// interacting, the discharged count and mass are exact, a saved state with the gate closed restarts
// with the gate's contacts dropped, the keystone of a stalled arch is removed (and only over the slit),
// a restart continues bit for bit, and bad keys name the file, line and key.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "dem/core/discharge.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// A floor A–L, gate L–R, R–B at y = 0 with the slit L–R centred on x = 0; disks of radius r.
std::string tiny_silo(double half_slit, const std::string& disks, const std::string& discharge, double duration,
                      const std::string& series = R"(["t", "e0.y", "e1.y", "active.count", "active.mass"])") {
  std::ostringstream s;
  s << R"([case]
title = "tiny silo"
[physics]
gravity = [0.0, -9.81]
[[material]]
name = "d"
density = 2650.0
[[material]]
name = "w"
[[contact]]
between = ["d", "d"]
kn = 1e6
ks_ratio = 0.25
friction = 0.5
damping_ratio = 0.7
[[contact]]
between = ["d", "w"]
kn = 1e6
ks_ratio = 0.25
friction = 0.5
damping_ratio = 0.7
)" << disks
    << "\n[[wall]]\nname = \"bottom_left\"\nfrom = [-0.06, 0.0]\nto = [" << -half_slit << ", 0.0]\nmaterial = \"w\"\n"
    << "[[wall]]\nname = \"gate\"\nfrom = [" << -half_slit << ", 0.0]\nto = [" << half_slit << ", 0.0]\nmaterial = \"w\"\n"
    << "[[wall]]\nname = \"bottom_right\"\nfrom = [" << half_slit << ", 0.0]\nto = [0.06, 0.0]\nmaterial = \"w\"\n"
    << discharge << "\n[numerics]\nintegrator = \"K19\"\ndt = 1e-5\nduration = " << duration
    << "\n[output]\nseries = " << series << "\nevery = 100\nvtk_every = 0\n";
  return s.str();
}

// disk 0 over the slit (falls through once it is open), disk 1 at rest on the floor beside it
const std::string kTwoDisks = R"(
[[element]]
material = "d"
radius = 0.005
position = [0.0, 0.005]
[[element]]
material = "d"
radius = 0.005
position = [0.04, 0.005]
)";
const std::string kOpen = "[discharge]\nslit = \"gate\"\noutlet_depth = \"1 cm\"\n";

nlohmann::json summary(const fs::path& dir) { return nlohmann::json::parse(test::slurp(dir / "summary.json")); }

std::vector<std::vector<double>> table(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> r;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) r.push_back(std::stod(cell));
    rows.push_back(r);
  }
  return rows;
}

dem::RunResult run(const dem::Case& c, const fs::path& out, dem::RunOptions o = {}) {
  o.out_dir = out;
  return dem::run_case(c, o);
}

}  // namespace

TEST_CASE("A disk below the outlet line is removed exactly once, counted with its mass, and stops interacting",
          "[silo][discharge]") {
  const auto path = test::write_temp("discharge_two.toml",
                                     tiny_silo(0.01, kTwoDisks, kOpen, 0.3,
                                               R"(["t", "e0.y", "e1.y", "discharged.count", "discharged.mass"])"));
  const dem::Case c = dem::read_case(path);
  const auto out = test::fresh_dir("dem2d_unit_discharge", "two");
  const auto r = run(c, out);
  REQUIRE(r.status == "completed");
  const double m0 = c.model.elements.mass[0];
  const auto s = summary(out);
  CHECK(s["discharge"]["discharged"] == 1);
  CHECK(s["discharge"]["remaining"] == 1);
  CHECK(s["discharge"]["discharged_mass"].get<double>() == Approx(m0).epsilon(1e-15));
  CHECK(s["discharge"]["discharged_mass"].get<double>() + s["discharge"]["remaining_mass"].get<double>() ==
        Approx(c.model.elements.mass[0] + c.model.elements.mass[1]).epsilon(1e-15));
  const auto rows = table(out / "series.csv");
  // free fall through the open slit: removed at the first step its centre is 1 cm below the slit,
  // y(t) = 0.005 − g t²/2 (the falling disk touches nothing)
  std::size_t first = rows.size();
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (rows[k][3] == 1.0 && first == rows.size()) first = k;
  REQUIRE(first < rows.size());
  const double t_out = std::sqrt(2.0 * 0.015 / 9.81);
  CHECK(rows[first][0] >= t_out - 1e-3);
  CHECK(rows[first][0] <= t_out + 1e-3 + 100 * 1e-5);
  for (std::size_t k = first; k < rows.size(); ++k) {
    CHECK(rows[k][3] == 1.0);                   // counted once, never again
    CHECK(rows[k][4] == m0);                    // exactly its mass
    CHECK(rows[k][1] == rows[first][1]);        // no longer moves
    CHECK(rows[k][1] < -0.01);                  // it lies below the outlet line
  }
  CHECK(rows.back()[2] == Approx(0.005).margin(1e-4));  // the disk on the floor stays
  // directly: a disk put below the line is removed by the first call, not by the second
  dem::Model m = c.model;
  CHECK_FALSE(dem::may_discharge(m));  // the cheap test the run makes before taking the model mutable
  CHECK(dem::remove_discharged(m) == 0);
  m.elements.y[1] = -0.0101;
  CHECK(dem::may_discharge(m));
  CHECK(dem::remove_discharged(m) == 1);
  CHECK_FALSE(dem::may_discharge(m));  // the removed disk no longer counts
  CHECK(dem::remove_discharged(m) == 0);
  CHECK(m.elements.active[1] == 0);
  CHECK(m.elements.active[0] == 1);
  CHECK(dem::discharged(m).count == 1);
  CHECK(dem::discharged(m).mass == m.elements.mass[1]);
  m.elements.y[0] = -0.0099;  // just above the line: stays
  CHECK(dem::remove_discharged(m) == 0);
}

TEST_CASE("Without a discharge table the gate holds the disk, with one the slit is open", "[silo][discharge]") {
  const dem::Case closed = dem::read_case(test::write_temp("discharge_closed.toml", tiny_silo(0.01, kTwoDisks, "", 0.1)));
  const auto out = test::fresh_dir("dem2d_unit_discharge", "closed");
  REQUIRE(run(closed, out).status == "completed");
  CHECK(table(out / "series.csv").back()[1] == Approx(0.005).margin(1e-4));  // resting on the gate
  const dem::Case no_table =
      dem::read_case(test::write_temp("discharge_q.toml", tiny_silo(0.01, kTwoDisks, "", 0.1, R"(["t", "discharged.count"])")));
  CHECK_THROWS_WITH(dem::check_outputs(no_table), Contains("discharge_q.toml:") && Contains("output.series") &&
                                                      Contains("discharged.count") && Contains("[discharge]"));
  const dem::Case open = dem::read_case(test::write_temp("discharge_open.toml", tiny_silo(0.01, kTwoDisks, kOpen, 0.1)));
  CHECK(open.model.walls[1].open);
  CHECK_FALSE(open.model.walls[0].open);
  CHECK_FALSE(closed.model.walls[1].open);
}

TEST_CASE("A closed-gate state started as a discharge drops the gate's contacts and the disk falls out",
          "[silo][discharge][restart]") {
  const dem::Case closed = dem::read_case(test::write_temp("discharge_closed2.toml", tiny_silo(0.01, kTwoDisks, "", 0.1)));
  const auto a = test::fresh_dir("dem2d_unit_discharge", "closed_state");
  dem::RunOptions oa;
  oa.checkpoint_at_end = true;
  REQUIRE(run(closed, a, oa).status == "completed");
  REQUIRE(std::abs(dem::read_checkpoint(a / "checkpoint.bin").time - 0.1) < 1e-9);
  const dem::Case open = dem::read_case(test::write_temp("discharge_open2.toml", tiny_silo(0.01, kTwoDisks, kOpen, 0.4)));
  dem::RunOptions ob;
  ob.restart = a / "checkpoint.bin";
  ob.restart_other_case = true;
  const auto b = test::fresh_dir("dem2d_unit_discharge", "opened");
  REQUIRE(run(open, b, ob).status == "completed");
  const auto s = summary(b);
  CHECK(s["discharge"]["discharged"] == 1);
  CHECK(s["discharge"]["remaining"] == 1);
  // on two threads (a disk each) the same, bit for bit: the contact index and the threads' shares of the
  // wall slots are made after the gate's slots are dropped (made before, the sweep read the dropped slots)
  dem::RunOptions ob2 = ob;
  ob2.threads = 2;
  ob2.governed = false;
  ob2.min_per_thread = 1;
  const auto b2 = test::fresh_dir("dem2d_unit_discharge", "opened_2threads");
  REQUIRE(run(open, b2, ob2).status == "completed");
  CHECK(summary(b2)["discharge"]["discharged"] == 1);
  CHECK(table(b2 / "series.csv") == table(b / "series.csv"));
  // the same state into the closed case again (same walls): the disk still rests on the gate
  const auto c = test::fresh_dir("dem2d_unit_discharge", "still_closed");
  const dem::Case closed_longer =
      dem::read_case(test::write_temp("discharge_closed3.toml", tiny_silo(0.01, kTwoDisks, "", 0.4)));
  REQUIRE(run(closed_longer, c, ob).status == "completed");
  CHECK(table(c / "series.csv").back()[1] == Approx(0.005).margin(1e-4));
}

namespace {
// Two disks r = 1 cm side by side over a 2.6 cm slit: each rests on a slit corner and pushes on the
// other — a stalled two-disk arch (either alone passes: 2 cm < 2.6 cm). Disk 2 rests on the floor
// outside the slit: never a keystone.
const std::string kArch = R"(
[[element]]
material = "d"
radius = 0.01
position = [-0.01, 0.0096]
[[element]]
material = "d"
radius = 0.01
position = [0.01, 0.0096]
[[element]]
material = "d"
radius = 0.01
position = [0.045, 0.01]
)";
}  // namespace

TEST_CASE("A stalled arch stays without the breaker, and loses its keystone once with it", "[silo][discharge][arch]") {
  const dem::Case stalled = dem::read_case(test::write_temp("arch_stalled.toml", tiny_silo(0.013, kArch, kOpen, 0.5)));
  const auto a = test::fresh_dir("dem2d_unit_discharge", "arch_stalled");
  REQUIRE(run(stalled, a).status == "completed");
  CHECK(summary(a)["discharge"]["discharged"] == 0);  // it is an arch: nothing leaves
  CHECK(summary(a)["discharge"]["keystones_removed"] == 0);
  CHECK(table(a / "series.csv").back()[1] > 0.0);

  // keystone_after must exceed the time the remaining arch disk takes to roll off its corner and fall
  // out (≈ 0.15 s here): with 0.1 s it would be taken as a second keystone while it is still moving
  const std::string breaker = kOpen + "keystone_after = \"0.2 s\"\n";
  const dem::Case broken = dem::read_case(test::write_temp("arch_broken.toml", tiny_silo(0.013, kArch, breaker, 0.8)));
  const auto b = test::fresh_dir("dem2d_unit_discharge", "arch_broken");
  REQUIRE(run(broken, b).status == "completed");
  const auto d = summary(b)["discharge"];
  REQUIRE(d["keystones_removed"] == 1);
  const auto k = d["keystones"][0];
  CHECK(k["time"].get<double>() == Approx(0.2).margin(2e-5));  // 0.2 s after the start without a disk out
  const int key = k["element"].get<int>();
  CHECK((key == 0 || key == 1));
  CHECK(d["discharged"] == 1);   // the other arch disk falls out
  CHECK(d["remaining"] == 1);    // disk 2, beside the slit, is never a keystone
  const double m = broken.model.elements.mass[0];
  CHECK(d["keystone_mass"].get<double>() == m);
  CHECK(d["discharged_mass"].get<double>() + d["keystone_mass"].get<double>() + d["remaining_mass"].get<double>() ==
        Approx(3.0 * m).epsilon(1e-15));

  // A restart in the middle (after the keystone) continues bit for bit, its log included.
  dem::RunOptions oi;
  oi.interrupt_at_step = 21000;  // after the keystone, before the other disk is out
  const auto c1 = test::fresh_dir("dem2d_unit_discharge", "arch_interrupted");
  REQUIRE(run(broken, c1, oi).status == "interrupted");
  dem::RunOptions orr;
  orr.restart = c1 / "checkpoint.bin";
  const auto c2 = test::fresh_dir("dem2d_unit_discharge", "arch_restarted");
  REQUIRE(run(broken, c2, orr).status == "completed");
  CHECK(summary(c2)["discharge"] == d);
  const auto full = table(b / "series.csv"), rest = table(c2 / "series.csv");
  REQUIRE(rest.size() >= 2);
  REQUIRE(rest.size() <= full.size());
  for (std::size_t i = 0; i < rest.size(); ++i) CHECK(rest[i] == full[full.size() - rest.size() + i]);
}

TEST_CASE("Bad discharge keys give file:line: key: what was expected", "[silo][discharge][errors]") {
  auto fails = [](const std::string& table_text, const std::string& key, const std::string& what) {
    const auto path = test::write_temp("discharge_bad.toml", tiny_silo(0.01, kTwoDisks, table_text, 0.1));
    CHECK_THROWS_WITH(dem::read_case(path), Contains("discharge_bad.toml:") && Contains(key) && Contains(what));
  };
  fails("[discharge]\nslit = \"nope\"\noutlet_depth = \"1 cm\"\n", "discharge.slit", "unknown wall \"nope\"");
  fails("[discharge]\nslit = \"gate\"\n", "outlet_depth", "");
  fails("[discharge]\nslit = \"gate\"\noutlet_depth = \"-1 cm\"\n", "discharge.outlet_depth", "");
  fails("[discharge]\nslit = \"gate\"\noutlet_depth = \"1 s\"\n", "discharge.outlet_depth", "");
  fails("[discharge]\nslit = \"gate\"\noutlet_depth = \"1 cm\"\nkeystone_after = \"2 cm\"\n", "discharge.keystone_after", "");
  fails("[discharge]\nslit = \"gate\"\noutlet_depth = \"1 cm\"\nkeystone_afterr = \"2 s\"\n", "keystone_afterr", "");
}

TEST_CASE("open_at opens the gate during the run, and a restart across the opening continues bit for bit",
          "[silo][discharge][restart]") {
  const std::string later = kOpen + "open_at = \"0.1 s\"\n";
  const dem::Case c = dem::read_case(test::write_temp("discharge_open_at.toml", tiny_silo(0.01, kTwoDisks, later, 0.4)));
  CHECK_FALSE(c.model.walls[1].open);
  const auto a = test::fresh_dir("dem2d_unit_discharge", "open_at");
  REQUIRE(run(c, a).status == "completed");
  const auto rows = table(a / "series.csv");  // every 1e-3 s: t, e0.y, e1.y, active.count, active.mass
  CHECK(rows.at(100)[0] == Approx(0.1).margin(1e-9));
  CHECK(rows.at(100)[1] == Approx(0.005).margin(1e-4));   // on the gate until 0.1 s
  CHECK(rows.at(110)[1] < rows.at(100)[1] - 1e-4);        // falling after it
  CHECK(summary(a)["discharge"]["discharged"] == 1);
  for (const std::int64_t at : {5000, 10000, 10001, 12000}) {  // before, at and after the opening
    dem::RunOptions oi;
    oi.interrupt_at_step = at;
    const auto b = test::fresh_dir("dem2d_unit_discharge", "open_at_interrupted");
    REQUIRE(run(c, b, oi).status == "interrupted");
    dem::RunOptions orr;
    orr.restart = b / "checkpoint.bin";
    const auto r = test::fresh_dir("dem2d_unit_discharge", "open_at_restarted");
    REQUIRE(run(c, r, orr).status == "completed");
    const auto rest = table(r / "series.csv");  // its first row is the restart's own (off the output grid)
    REQUIRE(rest.size() >= 2);
    REQUIRE(rest.size() - 1 <= rows.size());
    for (std::size_t i = 1; i < rest.size(); ++i) CHECK(rest[i] == rows[rows.size() - rest.size() + i]);
    CHECK(summary(r)["discharge"] == summary(a)["discharge"]);
  }
}
