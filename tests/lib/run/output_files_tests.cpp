// Outputs that lose no work and show no stale results (lib/dem/run/output_files.hpp, interrupt.hpp,
// checkpoint.hpp): a restart from a checkpoint continues bit for bit like the uninterrupted run (disks
// with contacts and a driven disk, a bonded PRE pair whose links break, moving walls); a checkpoint of
// another case is refused, or taken as the start of a new case on request; an interrupted run writes
// everything with status "interrupted"; an output folder never mixes two runs; write errors throw.
#include <catch2/catch.hpp>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/resource.h>
#include <thread>
#include <atomic>
#include <vector>

#include "dem/run/checkpoint.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using test::slurp;
using test::source;

fs::path fresh_dir(const std::string& name) {
  const auto d = test::fresh_dir("dem2d_unit_outputs", name);
  return d;
}


/// The data rows of a series.csv (without the header line).
std::vector<std::string> rows(const fs::path& csv) {
  std::ifstream in(csv);
  std::vector<std::string> out;
  std::string line;
  bool header = false;
  while (std::getline(in, line)) {
    if (!header) {
      header = true;
      continue;
    }
    out.push_back(line);
  }
  return out;
}

nlohmann::json summary(const fs::path& dir) { return nlohmann::json::parse(slurp(dir / "summary.json")); }

dem::RunResult run(const dem::Case& c, const fs::path& out, dem::RunOptions o = {}) {
  o.out_dir = out;
  return dem::run_case(c, o);
}

struct RestartCase {
  const char* file;
  std::int64_t interrupt_at;  // a multiple of output.every: the uninterrupted run has a row there
  std::int64_t every;         // output.every of the case
};

}  // namespace

TEST_CASE("A restart from a checkpoint continues bit for bit like the uninterrupted run", "[outputs][restart]") {
  const RestartCase rc = GENERATE(RestartCase{"tests/lib/fixtures/restart_disks.toml", 5400, 200},
                                  RestartCase{"tests/lib/fixtures/restart_rolling.toml", 5400, 200},
                                  RestartCase{"tests/lib/fixtures/restart_pre_break.toml", 200, 20},
                                  RestartCase{"tests/lib/fixtures/restart_belt.toml", 700, 100},
                                  RestartCase{"tests/lib/fixtures/restart_plate.toml", 1500, 100});
  INFO(rc.file);
  const std::string stem = fs::path(rc.file).stem().string();
  // The PRE pair breaks its links on both sides of the checkpoint: its bond-break log is compared too.
  const std::vector<std::string> sets =
      stem == "restart_pre_break" ? std::vector<std::string>{"output.bond_breaks=true"} : std::vector<std::string>{};
  const dem::Case c = dem::read_case(source(rc.file), sets);
  // A: uninterrupted, with a checkpoint of the final state.
  const auto a = fresh_dir(stem + "_a");
  dem::RunOptions oa;
  oa.checkpoint_at_end = true;
  const auto ra = run(c, a, oa);
  REQUIRE(ra.status == "completed");
  // B: stopped after step N as by SIGTERM: everything written, a checkpoint at N.
  const auto b = fresh_dir(stem + "_b");
  dem::RunOptions ob;
  ob.interrupt_at_step = rc.interrupt_at;
  const auto rb = run(c, b, ob);
  REQUIRE(rb.status == "interrupted");
  REQUIRE(rb.steps == rc.interrupt_at);
  CHECK(summary(b)["status"] == "interrupted");
  CHECK(summary(b)["checkpoint"]["step"] == rc.interrupt_at);
  // C: restarted from B's checkpoint, to the end.
  const auto cdir = fresh_dir(stem + "_c");
  dem::RunOptions oc;
  oc.restart = b / "checkpoint.bin";
  oc.checkpoint_at_end = true;
  const auto rcr = run(c, cdir, oc);
  REQUIRE(rcr.status == "completed");
  CHECK(rcr.steps == ra.steps);

  // The complete final states (every field the checkpoint holds, contact histories included) and the
  // run loop's state are identical byte for byte.
  const dem::Checkpoint fa = dem::read_checkpoint(a / "checkpoint.bin");
  const dem::Checkpoint fc = dem::read_checkpoint(cdir / "checkpoint.bin");
  CHECK(fa.step == fc.step);
  CHECK(fa.state.size() == fc.state.size());
  CHECK(fa.state == fc.state);
  CHECK(fa.loop == fc.loop);
  // Probes (summary) identical bit for bit.
  REQUIRE(ra.probes.size() == rcr.probes.size());
  for (const auto& [k, v] : ra.probes) {
    INFO(k);
    REQUIRE(v.has_value() == rcr.probes.at(k).has_value());
    if (v) CHECK(std::memcmp(&*v, &*rcr.probes.at(k), sizeof(double)) == 0);
  }
  CHECK(summary(a)["probes"].dump() == summary(cdir)["probes"].dump());
  CHECK(summary(a)["energies"].dump() == summary(cdir)["energies"].dump());
  CHECK(summary(cdir)["restart"]["step"] == rc.interrupt_at);
  // Series: B's rows up to N, then C's rows (C starts with the state at N) are A's rows, text for text.
  const auto ra_rows = rows(a / "series.csv"), rb_rows = rows(b / "series.csv"), rc_rows = rows(cdir / "series.csv");
  const std::size_t n_rows = static_cast<std::size_t>(rc.interrupt_at / rc.every);  // rows before step N
  REQUIRE(rb_rows.size() == n_rows + 1);
  REQUIRE(ra_rows.size() == n_rows + rc_rows.size());
  for (std::size_t k = 0; k <= n_rows; ++k) CHECK(rb_rows[k] == ra_rows[k]);
  for (std::size_t k = 0; k < rc_rows.size(); ++k) CHECK(rc_rows[k] == ra_rows[n_rows + k]);
  // The bond-break log: B's breaks up to N, then C's, are A's, row for row (the restart's log holds
  // the breaks after its checkpoint, as its series holds the rows after it).
  if (c.output.bond_breaks) {
    const auto ba = rows(a / "bond_breaks.csv"), bb = rows(b / "bond_breaks.csv"), bc = rows(cdir / "bond_breaks.csv");
    REQUIRE(!bb.empty());  // at least one break before the checkpoint (rows() skips the header)
    REQUIRE(!bc.empty());  // and at least one after it
    REQUIRE(ba.size() == bb.size() + bc.size());
    for (std::size_t k = 0; k < bb.size(); ++k) CHECK(bb[k] == ba[k]);
    for (std::size_t k = 0; k < bc.size(); ++k) CHECK(bc[k] == ba[bb.size() + k]);
  }
  // Snapshots (disks): the final snapshot is the same file.
  if (c.output.vtk) {
    const std::string last = fmt::format("vtk/snapshot_{:09d}.vtp", ra.steps);
    CHECK(slurp(a / last) == slurp(cdir / last));
  }
}

TEST_CASE("The PRE restart test breaks links on both sides of the checkpoint", "[outputs][restart]") {
  // Guards the restart test above: its checkpoint must fall between the first and the last break.
  const dem::Case c = dem::read_case(source("tests/lib/fixtures/restart_pre_break.toml"));
  const auto out = fresh_dir("pre_break_links");
  dem::RunOptions o;
  o.out_dir = out;
  const auto r = dem::run_case(c, o);
  REQUIRE(r.status == "completed");
  const auto rs = rows(out / "series.csv");
  auto links_at_row = [&](std::size_t k) {  // column 3: e1.links.e0
    std::stringstream ss(rs.at(k));
    std::string cell;
    for (int i = 0; i < 3; ++i) std::getline(ss, cell, ',');
    return std::stod(cell);
  };
  const double at_start = links_at_row(1), at_checkpoint = links_at_row(200 / 20), at_end = *r.probes.at("links_end");
  CHECK(at_start == 4.0);
  CHECK(at_checkpoint < 4.0);
  CHECK(at_checkpoint > at_end);
}

TEST_CASE("A checkpoint of another case is refused, or taken as the start of a new case on request", "[outputs][restart]") {
  const dem::Case disks = dem::read_case(source("tests/lib/fixtures/restart_disks.toml"));
  const auto b = fresh_dir("other_b");
  dem::RunOptions ob;
  ob.interrupt_at_step = 1000;
  REQUIRE(run(disks, b, ob).status == "interrupted");
  const fs::path ck = b / "checkpoint.bin";

  dem::RunOptions o;
  o.restart = ck;
  // Another case (different friction): refused, naming both hashes and --start-from.
  const dem::Case other = dem::read_case(source("tests/lib/fixtures/restart_disks.toml"), {"contact.0.friction=0.5"});
  CHECK_THROWS_WITH(run(other, fresh_dir("other_c1"), o), Contains("another case") && Contains("--start-from"));
  // The same case with other outputs and a longer duration: accepted.
  const dem::Case longer =
      dem::read_case(source("tests/lib/fixtures/restart_disks.toml"), {"numerics.duration=0.13", "output.every=100"});
  CHECK(run(longer, fresh_dir("other_c2"), o).status == "completed");
  // As the start of another case: allowed when elements, walls and dt match.
  o.restart_other_case = true;
  const auto c3 = fresh_dir("other_c3");
  const auto r3 = run(other, c3, o);
  CHECK(r3.status == "completed");
  CHECK(summary(c3)["restart"]["other_case"] == true);
  CHECK(std::stod(rows(c3 / "series.csv").front()) == Approx(0.01).margin(1e-12));  // starts at the checkpoint's time
  // ... and refused when they do not.
  const dem::Case belt = dem::read_case(source("tests/lib/fixtures/restart_belt.toml"));
  CHECK_THROWS_WITH(run(belt, fresh_dir("other_c4"), o), Contains("elements"));
  // A damaged checkpoint is refused (checksum).
  std::string bytes = slurp(ck);
  bytes[bytes.size() / 2] ^= 1;
  const auto damaged = fresh_dir("other_damaged");
  fs::create_directories(damaged);
  std::ofstream(damaged / "ck.bin", std::ios::binary) << bytes;
  CHECK_THROWS_WITH(dem::read_checkpoint(damaged / "ck.bin"), Contains("checksum"));
}

TEST_CASE("SIGTERM stops a run at the next step and everything is written with status interrupted", "[outputs]") {
  const dem::Case c = dem::read_case(source("cases/impact/disk_wall.toml"));
  const auto out = fresh_dir("sigterm");
  dem::set_interrupt_signal(SIGTERM);  // as the handler does
  dem::RunOptions o;
  o.out_dir = out;
  const auto r = dem::run_case(c, o);
  dem::set_interrupt_signal(0);
  CHECK(r.status == "interrupted");
  CHECK(r.steps == 1);
  CHECK_THAT(r.message, Contains("SIGTERM"));
  const auto s = summary(out);
  CHECK(s["status"] == "interrupted");
  CHECK(s["steps"] == 1);
  CHECK(fs::exists(out / "series.csv"));
  CHECK_FALSE(fs::exists(out / "series.csv.partial"));
  CHECK(rows(out / "series.csv").size() == 2);  // t = 0 and the step where it stopped
  CHECK(fs::exists(out / "checkpoint.bin"));
  CHECK(fs::exists(out / "snapshots.pvd"));
}

TEST_CASE("An output folder never mixes two runs", "[outputs]") {
  const dem::Case c = dem::read_case(source("cases/impact/disk_wall.toml"));
  const auto out = fresh_dir("mixing");
  fs::create_directories(out / "vtk");
  std::ofstream(out / "vtk" / "snapshot_999999999.vtp") << "old";
  std::ofstream(out / "summary.json") << "{\"status\": \"completed\", \"steps\": 12345}";
  std::ofstream(out / "series.csv.partial") << "1,2,";
  std::ofstream(out / "checkpoint.bin") << "old";
  std::ofstream(out / "summary.json.4242-7.tmp") << "{";  // a temporary left by a killed write_file_atomic
  std::ofstream(out / "wall_contacts.csv") << "old";  // an earlier run's wall profile (silo_arrangements reruns)
  REQUIRE(run(c, out).status == "completed");
  CHECK_FALSE(fs::exists(out / "wall_contacts.csv"));
  CHECK_FALSE(fs::exists(out / "summary.json.4242-7.tmp"));
  CHECK_FALSE(fs::exists(out / "vtk" / "snapshot_999999999.vtp"));
  CHECK_FALSE(fs::exists(out / "series.csv.partial"));
  CHECK_FALSE(fs::exists(out / "checkpoint.bin"));
  CHECK(summary(out)["steps"] == 2000);
  // A folder holding anything dem2d run does not write is refused, and left as it was.
  std::ofstream(out / "thesis.tex") << "precious";
  CHECK_THROWS_AS(run(c, out), dem::OutputError);
  CHECK_THROWS_WITH(run(c, out), Contains("thesis.tex"));
  CHECK(slurp(out / "thesis.tex") == "precious");
  CHECK(fs::exists(out / "summary.json"));
}

TEST_CASE("Several threads finishing the same file at once all succeed and leave one whole file", "[outputs]") {
  // A study's duplicate runs (e.g. repeated rows of a Sobol' design) share one cache entry and may
  // finish together: each write needs a temporary of its own, or one renames the other's away.
  const auto dir = fresh_dir("atomic_same_file");
  fs::create_directories(dir);
  const fs::path file = dir / "entry.json";
  std::atomic<int> failures{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < 8; ++t)
    pool.emplace_back([&, t] {
      for (int k = 0; k < 300; ++k) {
        try {
          dem::write_file_atomic(file, fmt::format("{{\"writer\": {}, \"k\": {}}}\n", t, k), false);
        } catch (const dem::OutputError&) {
          ++failures;
        }
      }
    });
  for (auto& th : pool) th.join();
  CHECK(failures == 0);
  CHECK(nlohmann::json::parse(slurp(file)).contains("writer"));  // whole, parseable
  int left = 0;
  for (const auto& e : fs::directory_iterator(dir)) left += e.path() != file;
  CHECK(left == 0);  // no temporary left behind
}

TEST_CASE("A full disk or an unwritable folder is an error, never an empty result", "[outputs]") {
  const dem::Case c = dem::read_case(source("cases/impact/disk_wall.toml"));
  // Unwritable: the output folder would lie below a file.
  const auto base = fresh_dir("unwritable");
  fs::create_directories(base);
  std::ofstream(base / "file") << "x";
  CHECK_THROWS_AS(run(c, base / "file" / "out"), dem::OutputError);
  // Full disk: a file size limit of 8 kB (SIGXFSZ ignored, so writes fail with EFBIG like ENOSPC).
  const auto full = fresh_dir("full");
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit old{};
  getrlimit(RLIMIT_FSIZE, &old);
  rlimit small = old;
  small.rlim_cur = 8 * 1024;  // the series is 13 kB, the summary 2.5 kB
  setrlimit(RLIMIT_FSIZE, &small);
  std::string what;
  try {
    run(c, full);
  } catch (const dem::OutputError& e) {
    what = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  CHECK_THAT(what, Contains("write failed") && Contains("File too large"));
  CHECK_FALSE(fs::exists(full / "series.csv"));  // never a complete-looking, cut series
  // write_file_atomic on a full device: /dev/full accepts opening but every write fails (ENOSPC).
  // (Its .tmp sibling cannot be created in /dev without root; the error is reported either way.)
  CHECK_THROWS_AS(dem::write_file_atomic("/dev/full/x", "data"), dem::OutputError);
}

TEST_CASE("A restart at or past the end of the run is refused and not completed twice", "[outputs][restart]") {
  const dem::Case disks = dem::read_case(source("tests/lib/fixtures/restart_disks.toml"));
  const auto a = fresh_dir("past_end_a");
  dem::RunOptions oa;
  oa.checkpoint_at_end = true;
  REQUIRE(run(disks, a, oa).status == "completed");
  dem::RunOptions o;
  o.restart = a / "checkpoint.bin";
  const auto b = fresh_dir("past_end_b");
  CHECK_THROWS_WITH(run(disks, b, o), Contains("at or past the end of the run") && Contains("give a longer numerics.duration"));
  CHECK_FALSE(fs::exists(b / "series.csv"));
  // one step more: accepted, and the restarted series starts at the checkpoint's row
  const double dt = disks.model.numerics.dt;
  const dem::Case longer = dem::read_case(source("tests/lib/fixtures/restart_disks.toml"),
                                          {fmt::format("numerics.duration={:.17g}", disks.model.numerics.duration + dt)});
  CHECK(run(longer, fresh_dir("past_end_c"), o).status == "completed");
}
