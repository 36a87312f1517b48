// Sample and analyse apart: `dem2d sweep --design-only` and `dem2d analyse` give the indices of a
// normal sweep (verification/engine/sensitivity_design_io.cpp).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "quiet_options.hpp"
#include "dem/cases/case_file.hpp"
#include "engine/sensitivity.hpp"
#include "engine/sensitivity_functions.hpp"

#include "../lib/test_support.hpp"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') out.emplace_back();
    else out.back().push_back(c);
  }
  return out;
}

ver::StudyOptions options(const fs::path& out) { return test::quiet_options(out); }

}  // namespace

TEST_CASE("Sample and analyse apart: design.csv evaluated elsewhere gives the indices of a normal sweep", "[sensitivity]") {
  const fs::path root = test::fresh_dir("dem2d_unit_sweep", "design_io");
  fs::create_directories(root);
  const fs::path f = root / "sensitivity.toml";
  std::ofstream(f) << "[sensitivity]\ntitle = \"round trip\"\nfunction = \"ishigami\"\ncoefficients = [7.0, 0.1]\n"
                      "methods = [\"oat\", \"morris\", \"sobol\"]\n"
                      "[[parameter]]\nlabel = \"θ\"\nlow = -3.141592653589793\nhigh = 3.141592653589793\n"
                      "[[parameter]]\nlabel = \"x2\"\nlow = -3.141592653589793\nhigh = 3.141592653589793\n"
                      "[[parameter]]\nlabel = \"Δt\"\nlow = -3.141592653589793\nhigh = 3.141592653589793\n"
                      "[morris]\ntrajectories = 6\nbootstrap = 50\n[sobol]\nsamples = 64\nbootstrap = 50\nsecond_order = true\n";
  const auto swept = ver::run_sensitivity(f, options(root / "sweep"));
  ver::write_sensitivity_design(f, options(root / "design"));
  // "Another code": the Ishigami function of each design row (blank = the base value, the range's middle, 0).
  std::ifstream design(root / "design" / "design.csv");
  std::string line;
  std::getline(design, line);
  CHECK(line == "run,method,theta [1],x2 [1],dt [1]");  // ASCII names and units
  std::ofstream outputs(root / "outputs.csv");
  outputs << "f,ignored,run\n";  // any column order; other columns ignored
  while (std::getline(design, line)) {
    const auto c = split(line);
    REQUIRE(c.size() == 5);
    std::vector<double> x;
    for (std::size_t i = 2; i < 5; ++i) x.push_back(c[i].empty() ? 0.0 : std::stod(c[i]));
    outputs << fmt::format("{:.17g}", ver::sens::evaluate({"ishigami", {7.0, 0.1}}, x)) << ",zz," << c[0] << "\n";
  }
  outputs.close();
  const auto analysed = ver::analyse_sensitivity(f, root / "outputs.csv", options(root / "analysed"));
  const std::string a = slurp(root / "sweep" / "indices.csv"), b = slurp(root / "analysed" / "indices.csv");
  CHECK(a.size() > 1000);
  CHECK(a == b);  // the same indices, to the last digit
  CHECK(a.rfind("method,output,parameter,name,index,estimate,low,high,exact\n", 0) == 0);
  CHECK(a.find(",\"Δt\",dt,") != std::string::npos);
  CHECK(a.find(",\"θ:Δt\",theta:dt,S2,") != std::string::npos);
  CHECK(swept.passed == analysed.passed);
  // the second-order table states its run count, N (2d + 2) = 64 × 8 (a generated mutant, issue 40, wrote N / 8)
  CHECK(slurp(root / "sweep" / "result.json").find("BA_i, N = 64, 512 runs;") != std::string::npos);
  // A run missing from the outputs is a failed run; a bad number is an error at its line.
  std::ofstream(root / "bad.csv") << "run,f\n0,1.5\n1,abc\n";
  CHECK_THROWS_WITH(ver::analyse_sensitivity(f, root / "bad.csv", options(root / "bad")), Catch::Contains("bad.csv:3: f: expected a number"));
  std::ofstream(root / "norun.csv") << "f\n1.5\n";
  CHECK_THROWS_WITH(ver::analyse_sensitivity(f, root / "norun.csv", options(root / "bad")), Catch::Contains("no column \"run\""));
}
