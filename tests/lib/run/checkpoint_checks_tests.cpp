// Crafted checkpoints (lib/dem/run/checkpoint_checks.hpp): a file with a valid checksum but an index out of
// its table, a flag byte of 2, a NaN count, position or clock, a law of the wrong kind, is refused with the
// checkpoint file and the field named, before the Simulation reads any of it (it crashed, overflowed a heap
// buffer or ran silently before). A checkpoint of another case whose counts, Δt or laws do not match names
// the file too.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>

#include "dem/run/checkpoint.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::uint64_t u64_at(const std::string& s, std::size_t at) {
  std::uint64_t v;
  std::memcpy(&v, s.data() + at, 8);
  return v;
}

/// Where each section of a checkpoint's state starts (checkpoint.cpp, write_state), found by walking it.
struct StateLayout {
  std::uint64_t n = 0, walls = 0, candidates = 0, linear_pairs = 0, linear_walls = 0, face_pairs = 0, face_walls = 0;
  std::size_t x = 0, active = 0, wall0 = 0, candidate0 = 0, linear_pair0 = 0, linear_wall0 = 0, face_pair0 = 0,
              face_wall0 = 0, x_ref = 0, clock = 0;
  static constexpr std::size_t kLinearPair = 77 + 40, kLinearWall = 78 + 40, kFace = 331;  // + the rolling state (R1–R6)

  explicit StateLayout(const std::string& s) {
    std::size_t at = 0;
    n = u64_at(s, at), at += 8;
    at += 8 + 4 * n;  // ids
    x = at + 8;
    at += 12 * (8 + 8 * n);
    active = at + 8, at += 8 + n;
    walls = u64_at(s, at), at += 8, wall0 = at, at += 64 * walls;
    candidates = u64_at(s, at), at += 8, candidate0 = at, at += 8 * candidates;
    linear_pairs = u64_at(s, at), at += 8, linear_pair0 = at, at += kLinearPair * linear_pairs;
    linear_walls = u64_at(s, at), at += 8, linear_wall0 = at, at += kLinearWall * linear_walls;
    face_pairs = u64_at(s, at), at += 8, face_pair0 = at, at += kFace * face_pairs;
    face_walls = u64_at(s, at), at += 8, face_wall0 = at, at += kFace * face_walls;
    x_ref = at + 8;
    at += 2 * (8 + 8 * n) + 8 + 16 * walls;
    clock = at;  // skin, time, step, rebuilds, preloading, then the plate's displacement and travel
    REQUIRE(at + 8 * 4 + 1 + 3 * 8 == s.size());
  }
};

/// A checkpoint file and its bytes, with the places of the header's numbers, the state and the run loop.
struct CheckpointBytes {
  std::string bytes;
  std::size_t state = 0, loop = 0;  // offsets of the state's first byte and of the loop's first number
  explicit CheckpointBytes(const fs::path& file) : bytes(test::slurp(file)) {
    const dem::Checkpoint ck = dem::read_checkpoint(file);
    state = bytes.find(ck.state);
    REQUIRE(state != std::string::npos);
    loop = state + ck.state.size() + 8;
  }
  std::size_t step() const { return state - 8 - 3 * 8; }
  std::size_t time() const { return state - 8 - 2 * 8; }
  /// A copy with `value` written at `at` and the checksum made valid again.
  template <class T>
  std::string with(std::size_t at, T value) const {
    std::string b = bytes;
    std::memcpy(b.data() + at, &value, sizeof value);
    const std::uint64_t sum = dem::checkpoint_checksum(std::string_view(b).substr(0, b.size() - 8));
    std::memcpy(b.data() + b.size() - 8, &sum, 8);
    return b;
  }
};

fs::path write(const fs::path& dir, const std::string& name, const std::string& bytes) {
  const fs::path f = dir / name;
  std::ofstream(f, std::ios::binary) << bytes;
  return f;
}

/// The case restarted from `file`: the message of what it throws ("" if it runs).
std::string restart_error(const dem::Case& c, const fs::path& file, const fs::path& out, bool other_case = false) {
  dem::RunOptions o;
  o.out_dir = out;
  o.restart = file;
  o.restart_other_case = other_case;
  try {
    dem::run_case(c, o);
  } catch (const std::exception& x) {
    return x.what();
  }
  return "";
}

/// A checkpoint of the disks case at the first of some steps where two disks are candidates (the disks
/// bounce: at a given step they may all be apart).
fs::path disks_checkpoint(const dem::Case& disks, const fs::path& dir) {
  for (const std::int64_t step : {2000, 4000, 6000, 7000, 9000, 10000, 11000}) {
    dem::RunOptions o;
    o.out_dir = dir / "a";
    o.interrupt_at_step = step;
    REQUIRE(dem::run_case(disks, o).status == "interrupted");
    if (StateLayout(dem::read_checkpoint(dir / "a" / "checkpoint.bin").state).linear_pairs > 0) return dir / "a" / "checkpoint.bin";
    fs::remove_all(dir / "a");
  }
  FAIL("no checkpoint with a linear pair slot");
  return {};
}

}  // namespace

TEST_CASE("A crafted checkpoint of disks is refused with the file and the field named", "[outputs][restart][checkpoint]") {
  const dem::Case disks = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"));
  const fs::path dir = test::fresh_dir("dem2d_unit_checkpoint_checks", "disks");
  const fs::path file = disks_checkpoint(disks, dir);
  const CheckpointBytes ck(file);
  const StateLayout s(dem::read_checkpoint(file).state);
  REQUIRE(s.n == 6);
  REQUIRE(s.walls == 2);
  REQUIRE(s.linear_pairs > 0);
  REQUIRE(s.linear_walls > 0);
  const std::size_t at = ck.state;
  struct Crafted {
    const char* name;
    std::string bytes;
    const char* field;
  };
  const Crafted crafted[] = {
      {"pair_i", ck.with<std::uint32_t>(at + s.linear_pair0, 99), "linear pair slot 0"},
      {"pair_j", ck.with<std::uint32_t>(at + s.linear_pair0 + 4, 0), "linear pair slot 0"},
      {"pair_law", ck.with<std::int32_t>(at + s.linear_pair0 + 8, 7), "law index 7"},
      {"pair_touching", ck.with<std::uint8_t>(at + s.linear_pair0 + 12, 2), "linear pair slot 0 touching"},
      {"pair_force", ck.with<double>(at + s.linear_pair0 + 13 + 4 * 8, kNaN), "linear pair slot 0"},
      {"wall_slot_j", ck.with<std::uint32_t>(at + s.linear_wall0 + 4, 9), "wall index 9"},
      {"wall_slot_j_just_out", ck.with<std::uint32_t>(at + s.linear_wall0 + 4, 2), "wall index 2 of 2 walls"},  // one past the last
      {"wall_slot_eta_s", ck.with<double>(at + s.linear_wall0 + 13 + 8, kNaN), "linear wall slot 0"},
      {"wall_slot_opened", ck.with<std::uint8_t>(at + s.linear_wall0 + 13 + 6 * 8, 2), "linear wall slot opened"},
      {"wall_slot_rolling_kr", ck.with<double>(at + s.linear_wall0 + 78 + 8, -1.0), "linear wall slot 0 rolling"},
      {"wall_slot_rolling_mk", ck.with<double>(at + s.linear_wall0 + 78, kNaN), "linear wall slot 0 rolling"},
      {"x_nan", ck.with<double>(at + s.x + 8, kNaN), "element x[1]"},
      {"active_7", ck.with<std::uint8_t>(at + s.active + 2, 7), "element active[2]"},
      {"wall_nan", ck.with<double>(at + s.wall0 + 16, kNaN), "wall 0 (floor)"},
      {"x_ref_nan", ck.with<double>(at + s.x_ref, kNaN), "reference x[0]"},
      // the last wall's reference y: after x_ref's n values, y_ref's count and n values, wall_ref's count
      {"wall_ref_y", ck.with<double>(at + s.x_ref + 16 * s.n + 16 + 16 * (s.walls - 1) + 8, kNaN), "wall reference 1"},
      {"preloading_2", ck.with<std::uint8_t>(at + s.clock + 4 * 8, 2), "preloading"},
      {"plate_travel", ck.with<double>(at + s.clock + 4 * 8 + 1 + 16, -1.0), "plate travel"},  // the state's last 8 bytes
      {"state_clock", ck.with<double>(at + s.clock + 8, kNaN), "clock"},
      {"header_time", ck.with<double>(ck.time(), kNaN), "time"},
      {"header_step", ck.with<std::int64_t>(ck.step(), -5), "step"},
      {"keystone_count", ck.with<double>(ck.loop + 9 * 8, kNaN), "run state"},
      {"quiet_steps", ck.with<double>(ck.loop + 6 * 8, -1.5), "run state quiet steps"},
  };
  int k = 0;
  for (const Crafted& c : crafted) {
    INFO(c.name);
    // a file name that holds no field name (the message must name the field itself)
    const fs::path f = write(dir, "crafted" + std::to_string(k++) + ".bin", c.bytes);
    const std::string error = restart_error(disks, f, dir / c.name);
    CHECK_THAT(error, Contains(f.string()) && Contains(c.field));
  }
  // The untouched file restarts (the crafting itself breaks nothing).
  CHECK(restart_error(disks, write(dir, "same.bin", ck.with<std::uint8_t>(ck.state + s.active, 1)), dir / "same") == "");
}

TEST_CASE("A crafted checkpoint of bonded PREs is refused with the file and the field named", "[outputs][restart][checkpoint]") {
  const dem::Case pre = dem::read_case(test::source("tests/lib/fixtures/restart_pre_break.toml"));
  const fs::path dir = test::fresh_dir("dem2d_unit_checkpoint_checks", "pre");
  dem::RunOptions o;
  o.out_dir = dir / "a";
  o.interrupt_at_step = 200;
  REQUIRE(dem::run_case(pre, o).status == "interrupted");
  const CheckpointBytes ck(dir / "a" / "checkpoint.bin");
  const StateLayout s(dem::read_checkpoint(dir / "a" / "checkpoint.bin").state);
  REQUIRE(s.face_pairs == 1);
  const std::size_t slot = ck.state + s.face_pair0;
  const std::size_t seg0 = 12 + 1 + 48 + 16 + 1;  // i, j, law, touching; constants; θ1, θ2; geometric_start
  const std::size_t links = seg0 + 8 * 26 + 24;
  const std::pair<std::string, const char*> crafted[] = {
      {ck.with<std::uint32_t>(slot + 4, 5), "face pair slot 0"},
      {ck.with<std::int32_t>(slot + 8, -3), "law index -3"},
      {ck.with<std::uint8_t>(slot + seg0 + 24, 2), "segment linked"},
      {ck.with<std::int32_t>(slot + links, 99), "99 links"},
      {ck.with<std::uint8_t>(slot + links + 4, 2), "face slot any_tensile"},
      {ck.with<double>(slot + 13, kNaN), "face pair slot 0"},
      {ck.with<double>(slot + seg0 + 8, kNaN), "face pair slot 0 segment"},  // segment 0's p_e
  };
  int k = 0;
  for (const auto& [bytes, field] : crafted) {
    INFO(field);
    const fs::path f = write(dir, "crafted" + std::to_string(k) + ".bin", bytes);
    CHECK_THAT(restart_error(pre, f, dir / ("c" + std::to_string(k))), Contains(f.string()) && Contains(field));
    ++k;
  }
}

TEST_CASE("A checkpoint that does not fit another case names the checkpoint file and the case file", "[outputs][restart][checkpoint]") {
  const dem::Case disks = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"));
  const fs::path dir = test::fresh_dir("dem2d_unit_checkpoint_checks", "other");
  const fs::path ck = disks_checkpoint(disks, dir);
  // counts: the checkpoint and the case file, each with its number
  const std::string belt_file = test::source("tests/lib/fixtures/restart_belt.toml").string();
  const dem::Case belt = dem::read_case(belt_file);
  CHECK_THAT(restart_error(belt, ck, dir / "b", true),
             StartsWith(ck.string() + ": restart: the checkpoint has ") && Contains("elements, the case " + belt_file + " has 1"));
  // dt: the line of numerics.dt in the case file (line 53 of a copy of restart_disks.toml), or the --set
  std::string text = test::slurp(test::source("tests/lib/fixtures/restart_disks.toml"));
  REQUIRE(text.find("dt = 1e-5\n") != std::string::npos);
  const fs::path finer_file = write(dir, "finer.toml", text.replace(text.find("dt = 1e-5\n"), 10, "dt = 5e-6\n"));
  const std::string finer_error = restart_error(dem::read_case(finer_file), ck, dir / "c", true);
  CHECK_THAT(finer_error, StartsWith(ck.string() + ": restart: the checkpoint was written with dt = 1.0000000000000001e-05 s"));
  CHECK_THAT(finer_error, Contains("the case " + finer_file.string() + " has dt = 5.0000000000000004e-06 s (" +
                                   finer_file.string() + ":53: numerics.dt)"));
  const dem::Case finer_set = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"), {"numerics.dt=5e-6"});
  CHECK_THAT(restart_error(finer_set, ck, dir / "d", true), Contains("(--set numerics.dt=5e-6: numerics.dt)"));
  // laws: the case file and the two materials
  const dem::Case faces = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"), {"contact.0.law=\"face\""});
  CHECK_THAT(restart_error(faces, ck, dir / "e", true),
             StartsWith(ck.string() + ": restart: element ") &&
                 Contains("the case " + faces.path.string() + " has no linear contact law between \"") );
}

TEST_CASE("A corrupt checkpoint state names the checkpoint file and never the case it was written for", "[outputs][restart][checkpoint]") {
  const dem::Case disks = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"));
  const fs::path dir = test::fresh_dir("dem2d_unit_checkpoint_checks", "corrupt_names");
  const fs::path ck = disks_checkpoint(disks, dir);
  const CheckpointBytes cb(ck);
  const StateLayout layout(dem::read_checkpoint(ck).state);
  // the restart is made from a copy in another folder: the case path stored inside (the fixture) is not it
  const fs::path crafted = write(dir, "crafted.bin", cb.with(cb.state + layout.x, kNaN));
  const std::string msg = restart_error(disks, crafted, dir / "r");
  CHECK_THAT(msg, StartsWith(crafted.string() + ": "));
  CHECK_THAT(msg, !Contains(dem::read_checkpoint(ck).case_path));
}

TEST_CASE("A checkpoint of another format version is refused with both versions named", "[outputs][restart][checkpoint]") {
  const dem::Case disks = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"));
  const fs::path dir = test::fresh_dir("dem2d_unit_checkpoint_checks", "version");
  const fs::path ck = disks_checkpoint(disks, dir);
  const CheckpointBytes cb(ck);
  const std::size_t version_at = std::string_view("DEM2D-CHECKPOINT\n").size();
  REQUIRE(u64_at(cb.bytes, version_at) % (1ull << 32) == dem::kCheckpointVersion);
  const fs::path older = write(dir, "older.bin", cb.with<std::uint32_t>(version_at, dem::kCheckpointVersion - 1));
  CHECK_THAT(restart_error(disks, older, dir / "r"),
             StartsWith(older.string() + ": checkpoint format version " + std::to_string(dem::kCheckpointVersion - 1) +
                        ", this dem2d reads version " + std::to_string(dem::kCheckpointVersion)));
}

TEST_CASE("A checkpoint another code version wrote is refused unless --restart-any-version, which is recorded",
          "[outputs][restart][checkpoint]") {
  const dem::Case disks = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"));
  const fs::path dir = test::fresh_dir("dem2d_unit_checkpoint_checks", "version");
  dem::RunOptions o;
  o.out_dir = dir / "a";
  o.interrupt_at_step = 2000;
  REQUIRE(dem::run_case(disks, o).status == "interrupted");
  const CheckpointBytes ck(dir / "a" / "checkpoint.bin");
  const std::string version = dem::read_checkpoint(dir / "a" / "checkpoint.bin").meta["provenance"]["code_version"];
  REQUIRE(!version.empty());
  // the same file with the recorded version changed in its first letter (the checksum made valid again)
  const std::size_t at = ck.bytes.find("\"code_version\":\"" + version + "\"");
  REQUIRE(at != std::string::npos);
  const std::size_t first = at + std::strlen("\"code_version\":\"");
  const char other = version[0] == 'X' ? 'Y' : 'X';
  const fs::path f = write(dir, "other_version.bin", ck.with<char>(first, other));
  const std::string written = std::string(1, other) + version.substr(1);
  const std::string error = restart_error(disks, f, dir / "refused");
  CHECK_THAT(error, Contains(f.string()) && Contains("written by dem2d " + written) && Contains("--restart-any-version"));
  // accepted when the user says so, and recorded
  dem::RunOptions any;
  any.out_dir = dir / "accepted";
  any.restart = f;
  any.restart_any_version = true;
  REQUIRE(dem::run_case(disks, any).status == "completed");
  const auto summary = nlohmann::json::parse(test::slurp(dir / "accepted" / "summary.json"));
  CHECK(summary["restart"]["code_version_differs"] == true);
  CHECK(summary["restart"]["checkpoint_written_by"]["provenance"]["code_version"] == written);
  // the unchanged file restarts without the flag, and says the versions agree
  dem::RunOptions same;
  same.out_dir = dir / "same";
  same.restart = dir / "a" / "checkpoint.bin";
  REQUIRE(dem::run_case(disks, same).status == "completed");
  CHECK(nlohmann::json::parse(test::slurp(dir / "same" / "summary.json"))["restart"]["code_version_differs"] == false);
}
