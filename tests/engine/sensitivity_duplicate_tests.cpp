// Duplicate points of a sensitivity design (`dem2d sweep`, verification/engine/sensitivity.cpp): the
// same overrides are run once and the result goes to every run that has them.
#include <catch2/catch.hpp>

#include <cmath>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/sensitivity.hpp"
#include "engine/sensitivity_sampling.hpp"

#include "../lib/test_support.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<std::vector<std::string>> csv_rows(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::vector<std::vector<std::string>> rows;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace

TEST_CASE("A Sobol design with repeated points runs each distinct point once and shares its result", "[sensitivity]") {
  // The resting disk over two parameters, Saltelli's design with N = 8: 8 × (2 + 2) = 32 runs. The mass
  // takes the integers 1 or 2 kg: wherever A and B agree in it, AB_1 repeats B and AB_2 repeats A.
  const fs::path root = test::fresh_dir("dem2d_unit_sweep", "duplicates");
  fs::create_directories(root / "verification" / "dup");
  fs::create_directories(root / "cases" / "basic");
  fs::copy_file(test::source("cases/basic/rest_on_wall.toml"), root / "cases/basic/rest_on_wall.toml");
  const fs::path f = root / "verification" / "dup" / "sensitivity.toml";
  std::ofstream(f) << "[sensitivity]\ntitle = \"duplicates\"\ncase = \"../../cases/basic/rest_on_wall.toml\"\n"
                      "outputs = [\"overlap\"]\nmethods = [\"sobol\"]\n"
                      "\n[[parameter]]\npath = \"contact.0.kn\"\nlabel = \"K\"\nlow = \"5e5 N/m\"\nhigh = \"4e6 N/m\"\n"
                      "\n[[parameter]]\npath = \"element.0.mass\"\nlabel = \"m\"\nlow = \"1 kg\"\nhigh = \"2 kg\"\ninteger = true\n"
                      "\n[sobol]\nsamples = 8\nbootstrap = 20\n";
  // The distinct points, counted from the design itself.
  const ver::sens::SaltelliDesign des = ver::sens::saltelli_design(8, 2);
  std::set<std::vector<double>> distinct;  // (u of K, the mass in kg)
  auto add = [&](const ver::sens::Matrix& m) {
    for (const auto& u : m) distinct.insert({u[0], std::min(std::floor(u[1] * 2.0), 1.0) + 1.0});
  };
  add(des.a);
  add(des.b);
  for (const auto& m : des.ab) add(m);
  REQUIRE(distinct.size() < 32);  // the test needs repeats

  ver::StudyOptions o;
  o.out_dir = root / "out";
  o.jobs = 2;
  o.print = false;
  const auto r = ver::run_sensitivity(f, o);
  CHECK(r.json["provenance"]["runs_run"].get<int>() == static_cast<int>(distinct.size()));
  CHECK(r.json["provenance"]["runs_duplicate"].get<int>() == 32 - static_cast<int>(distinct.size()));
  CHECK(r.json["setup"]["runs"].get<int>() == 32);
  // Every run has its output, and runs with equal inputs have bit-identical outputs (17 digits in runs.csv).
  const auto rows = csv_rows(o.out_dir / "runs.csv");
  REQUIRE(rows.size() == 32);
  std::map<std::pair<std::string, std::string>, std::string> output_of;
  for (const auto& row : rows) {
    REQUIRE(row.size() >= 6);
    CHECK(row[5] == "completed");
    CHECK(!row[4].empty());
    const auto [it, fresh] = output_of.emplace(std::pair{row[2], row[3]}, row[4]);
    if (!fresh) CHECK(it->second == row[4]);
  }
  CHECK(output_of.size() == distinct.size());
  // Run again from the cache: nothing runs, every distinct point is reused once per run that has it.
  const auto again = ver::run_sensitivity(f, o);
  CHECK(again.json["provenance"]["runs_run"].get<int>() == 0);
  CHECK(again.json["provenance"]["runs_reused"].get<int>() == 32);
  CHECK(again.json["tables"] == r.json["tables"]);
}
