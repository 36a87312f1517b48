// A stability study (engine/study_stability.cpp, kind = "stability"): the bisected limit of each variant is
// its probe "limit" in the figures and tables, the last variant's too. Planted bug that turns this red:
// the limits handed on for all variants but the last.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/study.hpp"

namespace fs = std::filesystem;

TEST_CASE("A stability study hands every variant's bisected limit to its table", "[stability_study]") {
  // the bonded face oscillator (ω₀ = 1000 rad/s) over 2 periods; K18 undamped and with ζ = 0.3: limits
  // 2 ms and 2(√1.09 − 0.3) ms = 1.488 ms (refs §1.5), bisected to 1 %
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_engine" / "verification" / "stability_table";
  fs::create_directories(dir);
  const std::string kase = std::string(DEM2D_SOURCE_DIR) + "/cases/oscillator/bonded_face.toml";
  std::ofstream(dir / "study.toml")
      << "[study]\ntitle = \"t\"\nrequirement = \"engine test\"\nkind = \"stability\"\ncase = \"" << kase << "\"\n"
      << "set = [\"numerics.duration=0.0126\", \"numerics.max_step_fraction=1e6\", \"numerics.integrator=K18\"]\n"
      << "[stability]\nparameter = \"numerics.dt\"\nlabel = \"dt [s]\"\nlow = 1e-4\nhigh = 1e-2\nrel_tol = 1e-2\n"
      << "[[variant]]\nlabel = \"undamped\"\nset = [\"contact.0.damping_ratio=0\"]\n"
      << "[[variant]]\nlabel = \"damped\"\nset = [\"contact.0.damping_ratio=0.3\"]\n"
      << "[[check]]\nlabel = \"largest stable dt\"\nvalue = 2e-3\nvariants = [\"undamped\"]\ntolerance = 0.5\nerror = \"rel\"\n"
      << "reason = \"a coarse bisection over 2 periods\"\n"
      << "[[table]]\ntitle = \"limits\"\nprobe = \"limit\"\n";
  ver::StudyOptions opt;
  opt.out_dir = dir / "out";
  opt.print = false;
  const ver::StudyResult r = ver::run_study(dir / "study.toml", opt);
  const nlohmann::json* table = nullptr;
  for (const auto& t : r.json.at("tables"))
    if (t.value("title", "") == "limits") table = &t;
  REQUIRE(table);
  const auto& rows = table->at("rows");
  REQUIRE(rows.size() == 2);
  CHECK(rows[0][0] == "undamped");
  CHECK(rows[1][0] == "damped");
  for (const auto& row : rows) {
    CAPTURE(row.dump());
    const double limit = std::stod(row[1].get<std::string>());
    CHECK(limit > 1e-3);
    CHECK(limit < 3e-3);
  }
}
