// A study figure of wall contacts against depth (engine/study_wall_profile.hpp): the strict reader of a
// run's wall_contacts.csv, the figure's data from a known file (signs as written, the mobilisation
// |fs| / (mu_w fn), only the named walls, each listed variant from its own run), and the study-file keys
// refused where they do not belong.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "dem/cases/case_file.hpp"
#include "engine/study_file.hpp"
#include "engine/study_run.hpp"
#include "engine/study_wall_profile.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace {

fs::path write(const std::string& name, const std::string& text) {
  static int calls = 0;
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_wall_profile" / (std::to_string(::getpid()) + "_" + std::to_string(++calls));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

const std::string kHeader = "wall,s [m],x [m],y [m],depth [m],fn [N],fs [N]\n";

std::string csv_refusal(const std::string& text) {
  const fs::path f = write("wall_contacts.csv", text);
  try {
    (void)ver::read_wall_contacts_csv(f);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  FAIL("the file was accepted:\n" << text);
  return "";
}

const std::string kSilo = std::string(DEM2D_SOURCE_DIR) + "/cases/silo/static_ordered.toml";

std::string study(const std::string& figure) {
  return "[study]\ntitle = \"t\"\ncase = \"" + kSilo + "\"\nkind = \"single\"\n"
         "[[variant]]\nlabel = \"17/18\"\nset = []\n"
         "args = { s = 18, B = 0.4, r = 0.01, count = 350, rho = 2650.0, g = 9.80665, mu_w = 0.17633 }\n"
         "[[check]]\nprobe = \"walls_fx\"\nvalue = 0.0\ntolerance = 1e-9\nreason = \"r\"\n"
         "[[figure]]\nid = \"p\"\n" + figure;
}

std::string study_refusal(const std::string& figure) {
  const fs::path f = write("study.toml", study(figure));
  try {
    (void)ver::read_study(f);
  } catch (const dem::CaseError& e) {
    return e.what();
  }
  FAIL("the study was accepted:\n" << figure);
  return "";
}

}  // namespace

TEST_CASE("wall_contacts.csv is read with every value as written", "[wall_profile]") {
  const fs::path f = write("wall_contacts.csv", kHeader + "left,0.01,0,0.01,0.32,80.5,-3.25\nright,0.2,0.4,0.2,0.13,40,1.5e-1\n");
  const auto rows = ver::read_wall_contacts_csv(f);
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].wall == "left");
  CHECK(rows[0].depth == 0.32);
  CHECK(rows[0].fn == 80.5);
  CHECK(rows[0].fs == -3.25);
  CHECK(rows[1].fs == 0.15);
}

TEST_CASE("A malformed wall_contacts.csv is refused at its line", "[wall_profile]") {
  CHECK_THAT(csv_refusal(""), Contains(":0: empty file"));
  CHECK_THAT(csv_refusal("wall,s,x,y,depth,fn,fs\n"), Contains(":1: expected the header"));
  CHECK_THAT(csv_refusal(kHeader + "left,0.01,0,0.01,0.32,80.5\n"), Contains(":2: expected 7 cells"));
  CHECK_THAT(csv_refusal(kHeader + "left,0.01,0,0.01,0.32,80.5,-3\nleft,0.01,0,0.01,0.32,8x,-3\n"),
             Contains(":3: cell 6: expected a finite number, got \"8x\""));
  CHECK_THAT(csv_refusal(kHeader + "left,0.01,0,0.01,0.32,nan,-3\n"), Contains(":2: cell 6"));
  CHECK_THAT(csv_refusal(kHeader + "left,0.01,0,0.01,-0.1,80,-3\n"), Contains(":2: depth"));
  CHECK_THAT(csv_refusal(kHeader + ",0.01,0,0.01,0.1,80,-3\n"), Contains(":2: cell 1"));
}

TEST_CASE("The figure's points keep the sign of fs and give |fs| / (mu_w fn) as the mobilisation", "[wall_profile]") {
  const std::vector<ver::WallContactRow> rows = {{"left", 0.01, 0.0, 0.01, 0.30, 80.0, -4.0},
                                                 {"left", 0.05, 0.0, 0.05, 0.26, 50.0, 2.0},
                                                 {"right", 0.01, 0.4, 0.01, 0.30, 70.0, -7.0},
                                                 {"left", 0.09, 0.0, 0.09, 0.22, 0.0, 0.0}};
  ver::Figure f;
  f.walls = {"left"};
  f.x_scale = 100.0;
  f.component = "fs";
  const auto fs_curve = ver::wall_profile_points(rows, f, 0.2, "DEM");
  CHECK(fs_curve["x"] == std::vector<double>{30.0, 26.0, 22.0});
  CHECK(fs_curve["y"] == std::vector<double>{-4.0, 2.0, 0.0});  // the right wall's contact left out
  f.component = "fn";
  CHECK(ver::wall_profile_points(rows, f, 0.2, "DEM")["y"] == std::vector<double>{80.0, 50.0, 0.0});
  f.component = "mobilisation";
  const auto mob = ver::wall_profile_points(rows, f, 0.2, "DEM");
  REQUIRE(mob["y"].size() == 2);  // no normal force: no mobilisation
  CHECK_THAT(mob["y"][0].get<double>(), WithinRel(4.0 / (0.2 * 80.0), 1e-15));
  CHECK_THAT(mob["y"][1].get<double>(), WithinRel(2.0 / (0.2 * 50.0), 1e-15));
  f.walls = {"left", "right"};
  f.component = "fs";
  CHECK(ver::wall_profile_points(rows, f, 0.2, "DEM")["y"].size() == 4);
}

TEST_CASE("A figure of walls reads, and its keys are refused where they do not belong", "[wall_profile]") {
  const std::string good = "walls = [\"left\", \"right\"]\ncomponent = \"fn\"\nreference = \"silo.janssen_contact_force\"\n"
                           "x_arg = \"z\"\nreference_points = 20\n";
  const ver::Study s = ver::read_study(write("study.toml", study(good)));
  REQUIRE(s.figures.size() == 1);
  CHECK(s.figures[0].walls == std::vector<std::string>{"left", "right"});
  CHECK(s.figures[0].component == "fn");
  CHECK_THAT(study_refusal("walls = [\"left\"]\n"), Contains("component: expected \"fn\", \"fs\" or \"mobilisation\""));
  CHECK_THAT(study_refusal("walls = [\"left\"]\ncomponent = \"tau\"\n"), Contains("component"));
  CHECK_THAT(study_refusal("walls = [\"left\"]\ncomponent = \"fn\"\ny = \"t\"\n"), Contains("no y, probe or group_arg"));
  CHECK_THAT(study_refusal("walls = [\"left\"]\ncomponent = \"fn\"\nreference = \"silo.janssen_contact_force\"\n"),
             Contains("needs x_arg"));
  CHECK_THAT(study_refusal("walls = [\"left\"]\ncomponent = \"mobilisation\"\nreference = \"silo.janssen_contact_force\"\n"
                           "x_arg = \"z\"\nreference_points = 5\n"),
             Contains("the line 1"));
  CHECK_THAT(study_refusal("walls = [\"left\"]\ncomponent = \"fn\"\nreference = \"silo.janssen_wall_force\"\n"
                           "x_arg = \"z1\"\nreference_points = 5\n"),
             Contains("needs z2"));
  CHECK_THAT(study_refusal("walls = [\"left\"]\ncomponent = \"mobilisation\"\nargs = { mu_w = 0.0 }\n"), Contains("mu_w > 0"));
  CHECK_THAT(study_refusal("y = \"t\"\ncomponent = \"fn\"\n"), Contains("needs walls"));
  CHECK_THAT(study_refusal("walls = [\"left\"]\ncomponent = \"fn\"\ny_from_start = true\n"),
             Contains("y_from_start") && Contains("not for a figure of walls"));
}

TEST_CASE("A figure of walls draws each listed variant from its own run's wall contacts - the last one too", "[wall_profile]") {
  // Three variants, each run's wall_contacts.csv with its own normal force; the figure lists all three,
  // then the first and the last. Each curve is its variant's file, in the variants' order.
  const std::string text = "[study]\ntitle = \"t\"\ncase = \"" + kSilo + "\"\nkind = \"single\"\n"
                           "[[variant]]\nlabel = \"a\"\nset = []\n[[variant]]\nlabel = \"b\"\nset = []\n"
                           "[[variant]]\nlabel = \"c\"\nset = []\n"
                           "[[check]]\nprobe = \"walls_fx\"\nvalue = 0.0\ntolerance = 1e-9\nreason = \"r\"\n"
                           "[[figure]]\nid = \"p\"\nwalls = [\"left\"]\ncomponent = \"fn\"\n"
                           "[[figure]]\nid = \"q\"\nwalls = [\"left\"]\ncomponent = \"fn\"\nvariants = [\"a\", \"c\"]\n";
  const fs::path file = write("study.toml", text);
  const ver::Study s = ver::read_study(file);
  REQUIRE(s.figures.size() == 2);
  const fs::path out = file.parent_path() / "out";
  for (int k = 0; k < 3; ++k) {
    fs::create_directories(out / "runs" / ("variant" + std::to_string(k)));
    std::ofstream(out / "runs" / ("variant" + std::to_string(k)) / "wall_contacts.csv")
        << kHeader << "left,0.1,0,0.3,0.1," << 10 * (k + 1) << ",0\n";
  }
  const ver::StudyOptions opt;
  ver::StudyRun run{.s = s, .out = out, .opt = opt};
  const nlohmann::json all = ver::wall_profile_curves(run, s.figures[0]);
  REQUIRE(all.size() == 3);
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    CHECK(all[k]["y"] == std::vector<double>{10.0 * (k + 1)});
    CHECK(all[k]["label"].get<std::string>().find(std::string(1, static_cast<char>('a' + k))) != std::string::npos);
  }
  const nlohmann::json two = ver::wall_profile_curves(run, s.figures[1]);
  REQUIRE(two.size() == 2);
  CHECK(two[0]["y"] == std::vector<double>{10.0});
  CHECK(two[1]["y"] == std::vector<double>{30.0});
}
