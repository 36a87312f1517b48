// A study figure of time series (engine/study_run.hpp, draw_figures): each listed variant's curve is
// read from that variant's own run (runs/variant<k>/series.csv), the last variant included, in the
// variants' order, and only the listed ones.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>
#include <unistd.h>

#include "engine/study_file.hpp"
#include "engine/study_run.hpp"

namespace fs = std::filesystem;

TEST_CASE("A series figure draws each listed variant from its own run - the last one too", "[figures]") {
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_figure_curves" / std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string silo = std::string(DEM2D_SOURCE_DIR) + "/cases/silo/static_ordered.toml";
  std::ofstream(dir / "study.toml") << "[study]\ntitle = \"t\"\ncase = \"" << silo << "\"\nkind = \"single\"\n"
                                    << "[[variant]]\nlabel = \"a\"\nset = []\n[[variant]]\nlabel = \"b\"\nset = []\n"
                                    << "[[variant]]\nlabel = \"c\"\nset = []\n"
                                    << "[[check]]\nprobe = \"walls_fx\"\nvalue = 0.0\ntolerance = 1e-9\nreason = \"r\"\n"
                                    << "[[figure]]\nid = \"all\"\nx = \"t\"\ny = \"e0.y\"\n"
                                    << "[[figure]]\nid = \"ends\"\nx = \"t\"\ny = \"e0.y\"\nvariants = [\"a\", \"c\"]\n";
  const ver::Study s = ver::read_study(dir / "study.toml");
  REQUIRE(s.figures.size() == 2);
  const fs::path out = dir / "out";
  for (int k = 0; k < 3; ++k) {  // variant k: e0.y = k + 1 at t = 0 and k + 2 at t = 1
    const fs::path run = out / "runs" / ("variant" + std::to_string(k));
    fs::create_directories(run);
    std::ofstream(run / "series.csv") << "t [s],e0.y [m]\n0," << k + 1 << "\n1," << k + 2 << "\n";
  }
  const ver::StudyOptions opt;
  ver::StudyRun run{.s = s, .out = out, .opt = opt};
  const nlohmann::json figures = ver::draw_figures(run);
  REQUIRE(figures.size() == 2);
  const nlohmann::json& all = figures[0]["curves"];
  REQUIRE(all.size() == 3);
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    CHECK(all[k]["label"] == "DEM " + std::string(1, static_cast<char>('a' + k)));
    CHECK(all[k]["y"] == std::vector<double>{k + 1.0, k + 2.0});
  }
  const nlohmann::json& ends = figures[1]["curves"];
  REQUIRE(ends.size() == 2);
  CHECK(ends[0]["y"] == std::vector<double>{1.0, 2.0});
  CHECK(ends[1]["y"] == std::vector<double>{3.0, 4.0});
}

TEST_CASE("A series figure with a reference draws its curve once, and not where it plots DEM minus reference", "[figures]") {
  // free fall from rest, g = −9.81: the reference v(t) = g t at the run's own times (t = 0, 1)
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_figure_reference" / std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string silo = std::string(DEM2D_SOURCE_DIR) + "/cases/silo/static_ordered.toml";
  const std::string figure = "x = \"t\"\ny = \"e0.vy\"\nreference = \"free_fall.velocity\"\nx_arg = \"t\"\nargs = { v0 = 0.0, g = -9.81 }\n";
  std::ofstream(dir / "study.toml") << "[study]\ntitle = \"t\"\ncase = \"" << silo << "\"\nkind = \"single\"\n"
                                    << "[[check]]\nprobe = \"walls_fx\"\nvalue = 0.0\ntolerance = 1e-9\nreason = \"r\"\n"
                                    << "[[figure]]\nid = \"with\"\n" << figure
                                    << "[[figure]]\nid = \"minus\"\ny_minus_reference = true\n" << figure;
  const ver::Study s = ver::read_study(dir / "study.toml");
  REQUIRE(s.figures.size() == 2);
  const fs::path run = dir / "out" / "runs" / "variant0";
  fs::create_directories(run);
  std::ofstream(run / "series.csv") << "t [s],e0.vy [m/s]\n0,0\n1,-9.5\n";
  const ver::StudyOptions opt;
  ver::StudyRun study{.s = s, .out = dir / "out", .opt = opt};
  const nlohmann::json figures = ver::draw_figures(study);
  REQUIRE(figures.size() == 2);
  const nlohmann::json& with = figures[0]["curves"];
  REQUIRE(with.size() == 2);
  CHECK(with[1]["style"] == "reference");
  CHECK(with[1]["x"] == std::vector<double>{0.0, 1.0});
  CHECK(with[1]["y"] == std::vector<double>{0.0, -9.81});
  const nlohmann::json& minus = figures[1]["curves"];
  REQUIRE(minus.size() == 1);  // DEM − reference only
  CHECK(minus[0]["y"][1].get<double>() == Approx(-9.5 + 9.81));
}

TEST_CASE("A table over two variant arguments places each variant's probe at its row and column", "[figures]") {
  // four variants on a 2 × 2 grid of (a, b) and one without b (left out); the probe is 10 a + b
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_table_grid" / std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string silo = std::string(DEM2D_SOURCE_DIR) + "/cases/silo/static_ordered.toml";
  std::ofstream f(dir / "study.toml");
  f << "[study]\ntitle = \"t\"\ncase = \"" << silo << "\"\nkind = \"single\"\n";
  for (const auto& [a, b] : std::vector<std::pair<int, int>>{{1, 1}, {1, 2}, {2, 1}, {2, 2}})
    f << "[[variant]]\nlabel = \"v" << a << b << "\"\nset = []\nargs = { a = " << a << ", b = " << b << " }\n";
  f << "[[variant]]\nlabel = \"lone\"\nset = []\nargs = { a = 3 }\n"
    << "[[check]]\nprobe = \"walls_fx\"\nvalue = 0.0\ntolerance = 1e-9\nreason = \"r\"\n"
    << "[[table]]\ntitle = \"grid\"\nprobe = \"walls_fx\"\nrow_arg = \"a\"\ncolumn_arg = \"b\"\nrow_label = \"a\"\ncolumn_label = \"b\"\n";
  f.close();
  const ver::Study s = ver::read_study(dir / "study.toml");
  const ver::StudyOptions opt;
  ver::StudyRun run{.s = s, .out = dir / "out", .opt = opt};
  for (const auto& v : s.variants) {
    ver::RunOut r;
    r.probes["walls_fx"] = v.args.count("b") ? 10.0 * v.args.at("a") + v.args.at("b") : 99.0;
    run.finest_runs.push_back(r);
  }
  ver::fill_tables(run);
  REQUIRE(run.tables.size() == 1);
  const nlohmann::json& t = run.tables[0];
  CHECK(t["columns"] == std::vector<std::string>{"a \\ b", "b = 1", "b = 2"});
  REQUIRE(t["rows"].size() == 2);
  CHECK(t["rows"][0] == std::vector<std::string>{"a = 1", "11", "12"});
  CHECK(t["rows"][1] == std::vector<std::string>{"a = 2", "21", "22"});
}

TEST_CASE("The mode map's chart leaves the same margin above its last row as below its first", "[figures]") {
  ver::Study s;
  s.blocks = {{1, 3}, {2, 6}};
  s.phis = {0.5, 0.6, 0.7};  // 6 rows, ticks at 0 … 5
  const nlohmann::json chart = ver::mode_chart(s, {});
  const auto& ticks = chart.at("yticks");
  REQUIRE(ticks.size() == 6);
  const double first = ticks.front().at(0), last = ticks.back().at(0);
  const double lo = chart.at("yrange").at(0), hi = chart.at("yrange").at(1);
  CHECK(first - lo == Approx(0.7));
  CHECK(hi - last == Approx(first - lo));
}
