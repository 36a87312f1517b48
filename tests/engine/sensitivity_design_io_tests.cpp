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
  CHECK_THROWS_WITH(ver::analyse_sensitivity(f, root / "norun.csv", options(root / "bad")), Catch::Contains("norun.csv:1: run: no such column"));
}

TEST_CASE("dem2d analyse reads its outputs strictly: field counts, one header name each, one rule for non-finite values", "[sensitivity]") {
  // f = x1 + 2 x2, one at a time with 3 points: runs 0 … 6.
  const fs::path root = test::fresh_dir("dem2d_unit_sweep", "design_io_strict");
  fs::create_directories(root);
  const fs::path f = root / "sensitivity.toml";
  std::ofstream(f) << "[sensitivity]\ntitle = \"strict\"\nfunction = \"linear\"\ncoefficients = [1.0, 2.0]\nmethods = [\"oat\"]\n"
                      "max_failed_runs = 1\n[[parameter]]\nlabel = \"x1\"\nlow = 0.0\nhigh = 1.0\n"
                      "[[parameter]]\nlabel = \"x2\"\nlow = 0.0\nhigh = 1.0\n[oat]\npoints = 3\n";
  const auto analyse = [&](const std::string& name, const std::string& text) {
    std::ofstream(root / name) << text;
    return ver::analyse_sensitivity(f, root / name, options(root / ("out_" + name)));
  };
  const std::string good = "run,f\n0,1.5\n1,1\n2,1.5\n3,2\n4,0.5\n5,1.5\n6,2.5\n";  // the function's values
  CHECK(analyse("good.csv", good).passed);
  CHECK(analyse("bom.csv", "\xEF\xBB\xBF" + good).passed);  // a spreadsheet's byte-order mark is skipped
  // A decimal comma: each row has one field more than the header; it used to read every output as 0 and pass.
  CHECK_THROWS_WITH(analyse("comma.csv", "run,f\n0,1,5\n1,0\n"), Catch::Contains("comma.csv:2: 3 fields, the header has 2"));
  CHECK_THROWS_WITH(analyse("twice.csv", "run,f,f\n0,1,2\n"),
                    Catch::Contains("twice.csv:1: f: the header names this column twice (columns 2 and 3)"));
  CHECK_THROWS_WITH(analyse("unit.csv", "run,f [m]\n0,1\n"),
                    Catch::Contains("unit.csv:1: f: no such column") && Catch::Contains("\"f [m]\" is there"));
  CHECK_THROWS_WITH(analyse("space.csv", "run,f\n0, 1.5\n"), Catch::Contains("space.csv:2: f: expected a number, got \" 1.5\""));
  // Every non-finite value is one failed run: one is allowed (max_failed_runs = 1), two are not.
  for (const std::string v : {"", "nan", "NaN", "inf", "-inf", "Infinity", "nan(0x1)", "1e400", "-1e400"}) {
    INFO("value \"" << v << "\"");
    std::string one = good;
    one.replace(one.find("\n6,2.5\n"), 7, "\n6," + v);
    const auto r = analyse("one.csv", one);
    CHECK(r.passed);
    CHECK(slurp(root / "out_one.csv" / "runs.csv").find(",failed,") != std::string::npos);
    std::string two = one;
    two.replace(two.find("\n5,1.5\n"), 7, "\n5," + v + "\n");
    CHECK_FALSE(analyse("two.csv", two).passed);
  }
  // An underflow is a number (its value, as strtod rounds it), not a failure.
  std::string tiny = good;
  tiny.replace(tiny.find("\n6,2.5\n"), 7, "\n6,1e-400\n");
  CHECK(analyse("tiny.csv", tiny).passed);
  CHECK(slurp(root / "out_tiny.csv" / "runs.csv").find(",failed,") == std::string::npos);
}
