// What the report draws: a figure with an explicit axis range (result.json "xrange"/"yrange", reports/
// study_plots.cpp) must hold every point it draws, error bars and bar widths included; a range that cuts
// off data draws a figure that looks complete and is not. Checked on every figure of a sensitivity study
// of the Ishigami function (3 parameters) and of Sobol's g-function with 2 (Morris μ* bars and μ*–σ, Sobol'
// bars with intervals).
// Planted bug that turned this red: the bars' xrange [0.5, d − 0.5] (the last parameter's bar cut off).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "quiet_options.hpp"
#include "engine/sensitivity.hpp"

#include "../lib/test_support.hpp"

namespace fs = std::filesystem;

namespace {

/// Every finite point of every curve of `fig` inside its explicit ranges; the number of ranged figures.
void check_inside(const nlohmann::json& fig, int& ranged) {
  const bool has_x = fig.contains("xrange"), has_y = fig.contains("yrange");
  if (!has_x && !has_y) return;
  ++ranged;
  for (const auto& c : fig.at("curves")) {
    const double half = c.value("style", "") == "boxes" ? 0.5 * c.value("width", 0.0) : 0.0;
    for (std::size_t i = 0; i < c.at("x").size(); ++i) {
      if (c.at("x")[i].is_null() || c.at("y")[i].is_null()) continue;
      const double x = c.at("x")[i].get<double>();
      CAPTURE(fig.at("id").get<std::string>(), c.value("label", ""), i, x);
      if (has_x) {
        CHECK(x - half >= fig["xrange"][0].get<double>());
        CHECK(x + half <= fig["xrange"][1].get<double>());
      }
      if (!has_y) continue;
      for (const char* key : {"y", "ylow", "yhigh"})
        if (c.contains(key) && !c.at(key)[i].is_null()) {
          CHECK(c.at(key)[i].get<double>() >= fig["yrange"][0].get<double>());
          CHECK(c.at(key)[i].get<double>() <= fig["yrange"][1].get<double>());
        }
    }
  }
}

}  // namespace

TEST_CASE("Axis ranges of the sensitivity figures contain the data they draw", "[sensitivity][report]") {
  for (const int d : {3, 2}) {
    CAPTURE(d);
    const fs::path root = test::fresh_dir("dem2d_unit_sweep", "figure_ranges" + std::to_string(d));
    fs::create_directories(root);
    const fs::path f = root / "sensitivity.toml";
    std::string text = "[sensitivity]\ntitle = \"ranges\"\n";
    text += d == 3 ? "function = \"ishigami\"\ncoefficients = [7.0, 0.1]\n" : "function = \"g\"\ncoefficients = [0.0, 1.0]\n";
    text += "methods = [\"morris\", \"sobol\"]\n";
    const std::string range = d == 3 ? "low = -3.141592653589793\nhigh = 3.141592653589793\n" : "low = 0.0\nhigh = 1.0\n";
    for (int i = 0; i < d; ++i) text += "[[parameter]]\nlabel = \"x" + std::to_string(i + 1) + "\"\n" + range;
    text += "[morris]\ntrajectories = 6\nbootstrap = 50\n[sobol]\nsamples = 64\nbootstrap = 50\n";
    std::ofstream(f) << text;
    ver::run_sensitivity(f, test::quiet_options(root / "out"));
    const nlohmann::json result = nlohmann::json::parse(std::ifstream(root / "out" / "result.json"));
    int ranged = 0;
    for (const auto& fig : result.at("figures")) check_inside(fig, ranged);
    CHECK(ranged >= 2);  // the Morris and Sobol' bars at least
  }
}
