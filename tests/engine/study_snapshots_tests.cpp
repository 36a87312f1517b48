// [[snapshot]] tables of a study file (verification/engine/study_snapshots.hpp): the strict reader's
// refusals (each mistake planted into a file that reads), and a small study whose snapshot run writes
// the pictures and lists them in result.json — reused when unchanged, never beside a stale picture.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "dem/cases/case_file.hpp"
#include "engine/study.hpp"
#include "engine/study_file.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

const std::string kFreeFall = std::string(DEM2D_SOURCE_DIR) + "/cases/basic/free_fall.toml";

fs::path fresh_dir(const std::string& name) {
  static int calls = 0;
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_snapshots" / (name + std::to_string(::getpid()) + "_" + std::to_string(++calls));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// A free-fall study (duration 0.5 s) with two variants and one snapshot (lines 15-20).
std::string good_study() {
  return "[study]\n"                                          // 1
         "title = \"snapshots\"\n"                            // 2
         "case = \"" + kFreeFall + "\"\n"                     // 3
         "[[variant]]\n"                                      // 4
         "label = \"dt=1e-4\"\n"                              // 5
         "set = [\"numerics.dt=1e-4\"]\n"                     // 6
         "[[variant]]\n"                                      // 7
         "label = \"dt=5e-5\"\n"                              // 8
         "set = [\"numerics.dt=5e-5\"]\n"                     // 9
         "[[check]]\n"                                        // 10
         "probe = \"y_end\"\n"                                // 11
         "value = 2.0\n"                                      // 12
         "tolerance = 10.0\n"                                 // 13
         "reason = \"a loose check: the snapshots are the point\"\n"  // 14
         "[[snapshot]]\n"                                     // 15
         "id = \"fall\"\n"                                    // 16
         "title = \"the falling disk\"\n"                     // 17
         "variants = [\"dt=1e-4\"]\n"                         // 18
         "at = [\"0.25 s\", \"end\"]\n"                       // 19
         "max_force = \"1 N\"\n";                             // 20
}

std::string planted(const std::string& from, const std::string& to) {
  std::string s = good_study();
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

/// The refusal of `text` with the file's folder cut off ("study.toml:LINE: ...").
std::string refusal(const std::string& text) {
  const fs::path f = fresh_dir("read") / "study.toml";
  std::ofstream(f) << text;
  try {
    (void)ver::read_study(f);
  } catch (const dem::CaseError& e) {
    std::string m = e.what();
    for (auto at = m.find(f.string()); at != std::string::npos; at = m.find(f.string())) m.replace(at, f.string().size(), "study.toml");
    return m;
  }
  FAIL("the study file was accepted:\n" << text);
  return "";
}

std::string at_line(int line) { return "study.toml:" + std::to_string(line) + ": "; }

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream b;
  b << in.rdbuf();
  return nlohmann::json::parse(b.str());
}

bool is_png(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::string head(8, '\0');
  in.read(head.data(), 8);
  return in && head == std::string("\x89PNG\r\n\x1a\n", 8);
}

}  // namespace

TEST_CASE("A snapshot table reads, with its times in seconds and its end", "[study_file][snapshot]") {
  const fs::path f = fresh_dir("good") / "study.toml";
  std::ofstream(f) << good_study();
  const ver::Study s = ver::read_study(f);
  REQUIRE(s.snapshots.size() == 1);
  const ver::Snapshot& snap = s.snapshots[0];
  CHECK(snap.id == "fall");
  CHECK(snap.variants == std::vector<std::string>{"dt=1e-4"});
  CHECK(snap.times == std::vector<double>{0.25});
  CHECK(snap.end);
  CHECK(snap.max_force == 1.0);
  CHECK(snap.width == 800);
  CHECK(snap.line == 15);
}

TEST_CASE("Mistakes in a snapshot table are refused with file:line", "[study_file][snapshot]") {
  CHECK_THAT(refusal(planted("max_force = ", "max_froce = ")), StartsWith(at_line(20) + "snapshot.max_froce: unknown key; did you mean 'max_force'?"));
  CHECK_THAT(refusal(planted("[\"dt=1e-4\"]\nat", "[\"dt=1e4\"]\nat")),
             StartsWith(at_line(18) + "snapshot.variants: \"dt=1e4\" names no variant; did you mean \"dt=1e-4\"?"));
  CHECK_THAT(refusal(planted("\"0.25 s\"", "\"0.25 m\"")), StartsWith(at_line(19) + "snapshot.at:"));
  CHECK_THAT(refusal(planted("\"0.25 s\"", "0.25")), StartsWith(at_line(19) + "snapshot.at: expected a time with its unit"));
  CHECK_THAT(refusal(planted("\"0.25 s\"", "\"the end\"")), StartsWith(at_line(19) + "snapshot.at:"));
  CHECK_THAT(refusal(planted("\"0.25 s\", \"end\"", "\"0.3 s\", \"0.2 s\"")), StartsWith(at_line(19) + "snapshot.at: the times must increase strictly"));
  CHECK_THAT(refusal(planted("\"0.25 s\"", "\"0.6 s\"")),
             StartsWith(at_line(19) + "snapshot.at: 0.6 s lies past the end of the run of variant \"dt=1e-4\" (numerics.duration = 0.5 s)"));
  CHECK_THAT(refusal(planted("max_force = \"1 N\"", "")), StartsWith(at_line(15) + "snapshot.max_force: snapshot \"fall\" has 2 pictures: give max_force"));
  CHECK_THAT(refusal(planted("max_force = \"1 N\"", "max_force = \"1 m\"")), StartsWith(at_line(20) + "snapshot.max_force:"));
  CHECK_THAT(refusal(planted("id = \"fall\"", "id = \"../fall\"")), StartsWith(at_line(16) + "snapshot.id: expected a plain word"));
  CHECK_THAT(refusal(good_study() + "[[snapshot]]\nid = \"fall\"\ntitle = \"t\"\nat = [\"end\"]\nvariants = [\"dt=5e-5\"]\n"),
             StartsWith(at_line(22) + "snapshot.id: \"fall\" is the id of an earlier snapshot"));
  CHECK_THAT(refusal(planted("title = \"the falling disk\"\n", "")), Contains("snapshot.title"));
  CHECK_THAT(refusal(planted("[[snapshot]]", "[[snapshots]]")), Contains("snapshots: unknown key; did you mean 'snapshot'?"));
  // a later override of the duration counts: the variant's run is what must reach the time
  CHECK_THAT(refusal(planted("set = [\"numerics.dt=1e-4\"]", "set = [\"numerics.dt=1e-4\", \"numerics.duration=0.2\"]")),
             StartsWith(at_line(19) + "snapshot.at: 0.25 s lies past the end of the run of variant \"dt=1e-4\""));
  // one picture needs no common scale
  const fs::path f = fresh_dir("one") / "study.toml";
  std::ofstream(f) << planted("\"0.25 s\", \"end\"]\nmax_force = \"1 N\"", "\"end\"]");
  CHECK_NOTHROW(ver::read_study(f));
}

TEST_CASE("A study's snapshot run writes the pictures and result.json lists them, reused or redrawn, never stale", "[study][snapshot]") {
  const fs::path dir = fresh_dir("run");
  std::ofstream(dir / "study.toml") << good_study();
  ver::StudyOptions o;
  o.out_dir = dir / "out";
  o.print = false;
  const ver::StudyResult r = ver::run_study(dir / "study.toml", o);
  REQUIRE(r.passed);
  const nlohmann::json list = read_json(o.out_dir / "result.json").at("snapshots");
  REQUIRE(list.size() == 2);
  CHECK(list[0]["id"] == "fall");
  CHECK(list[0]["title"] == "the falling disk");
  CHECK(list[0]["variant"] == "dt=1e-4");
  CHECK(list[0]["at"] == "0.25 s");
  CHECK(list[0]["step"] == 2500);
  CHECK(list[0]["time"].get<double>() == Approx(0.25).margin(1e-12));
  CHECK(list[0]["max_force"] == 1.0);
  CHECK(list[0]["file"] == "snapshots/fall/dt_1e-4/pictures/picture_000002500.png");
  CHECK(list[1]["at"] == "end");
  CHECK(list[1]["step"] == 5000);
  for (const auto& e : list) CHECK(is_png(o.out_dir / e["file"].get<std::string>()));
  // only the asked pictures: the first step's picture that "end" (output.pictures) draws is dropped, no VTK
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& x : fs::directory_iterator(o.out_dir / "snapshots/fall/dt_1e-4/pictures")) ++n;
  CHECK(n == 2);
  CHECK_FALSE(fs::exists(o.out_dir / "snapshots/fall/dt_1e-4/vtk"));
  CHECK_FALSE(fs::exists(o.out_dir / "snapshots/fall/dt_5e-5"));  // not listed

  // unchanged: the folder is reused (2 study runs + 1 snapshot run served by the cache)
  const ver::StudyResult again = ver::run_study(dir / "study.toml", o);
  CHECK(again.json["provenance"]["runs_reused"] == 3);
  CHECK(again.json["snapshots"] == list);

  // a lost picture, or other times: rerun into a cleared folder (no earlier picture stays beside the new)
  fs::remove(o.out_dir / list[0]["file"].get<std::string>());
  const ver::StudyResult lost = ver::run_study(dir / "study.toml", o);
  CHECK(lost.json["provenance"]["runs_run"] == 1);
  CHECK(is_png(o.out_dir / list[0]["file"].get<std::string>()));
  std::ofstream(dir / "study.toml") << planted("\"0.25 s\", \"end\"", "\"0.1 s\", \"0.3 s\"");
  const ver::StudyResult moved = ver::run_study(dir / "study.toml", o);
  const nlohmann::json now = moved.json["snapshots"];
  REQUIRE(now.size() == 2);
  CHECK(now[0]["step"] == 1000);
  CHECK(now[1]["step"] == 3000);
  CHECK_FALSE(fs::exists(o.out_dir / list[0]["file"].get<std::string>()));
  CHECK_FALSE(fs::exists(o.out_dir / list[1]["file"].get<std::string>()));
}
