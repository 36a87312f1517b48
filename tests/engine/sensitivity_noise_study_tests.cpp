// The run-to-run noise of a sensitivity study and its one-at-a-time sweeps, through whole studies and the
// plan's bookkeeping (engine/sensitivity_noise.cpp, sensitivity_oat.cpp). Planted bugs that turn these red:
// the B rows' noise taken from the wrong runs, the noise checks' reason stating a 105 % interval, the
// ±tolerance check's verdict inverted, and the sweeps of the last output left out.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/sensitivity.hpp"
#include "engine/sensitivity_study.hpp"
#include "quiet_options.hpp"

#include "../lib/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

/// Runs a sensitivity study of the linear function 1·x1 + 2·x2 on [0, 1]² (Sobol' only): `sensitivity` goes
/// into [sensitivity], `sobol` is the [sobol] table's body.
ver::StudyResult linear_study(const std::string& folder, const std::string& sensitivity, const std::string& sobol,
                              const std::string& coefficients = "[1.0, 2.0]") {
  const fs::path root = test::fresh_dir("dem2d_unit_linear_study", folder);
  fs::create_directories(root);
  std::ofstream(root / "sensitivity.toml")
      << "[sensitivity]\ntitle = \"" << folder << "\"\nfunction = \"linear\"\ncoefficients = " << coefficients
      << "\nmethods = [\"sobol\"]\n"
      << sensitivity << "[[parameter]]\nlabel = \"x1\"\nlow = 0.0\nhigh = 1.0\n[[parameter]]\nlabel = \"x2\"\nlow = 0.0\nhigh = 1.0\n"
      << "[sobol]\n" << sobol;
  return ver::run_sensitivity(root / "sensitivity.toml", test::quiet_options(root / "out"));
}

}  // namespace

TEST_CASE("the noise of each Sobol' row's mean comes from its own runs", "[sensitivity][noise]") {
  // n = 2 rows, d = 1: runs A 0–1, B 2–3, AB_1 4–5 after the sobol_begin; run k has variance k + 1 over 2 replicates
  ver::sens::Plan plan;
  plan.sobol_begin = 3;
  plan.runs.resize(9);
  for (std::size_t k = 0; k < 6; ++k) {
    plan.runs[3 + k].noise_var = {static_cast<double>(k + 1)};
    plan.runs[3 + k].replicates = 2;
  }
  const auto m = ver::sens::mean_noise_of_runs(plan, 0, 2, 1);
  REQUIRE(m);
  CHECK(m->a == std::vector<double>{0.5, 1.0});
  CHECK(m->b == std::vector<double>{1.5, 2.0});
  CHECK(m->ab.at(0) == std::vector<double>{2.5, 3.0});
}

TEST_CASE("a noisy test function: the noise fraction's checks state their interval and verdict right", "[sensitivity][noise]") {
  // V_f = 5/12; noise σ = 1: φ = 1 / (1 + 5/12) = 12/17
  const ver::StudyResult r = linear_study("noise", "noise_sd = 1.0\nnoise_seed = 1\nreplicates = 4\n",
                                          "samples = 512\nbootstrap = 200\nconfidence = 0.9\nseed = 1\ntolerance = 0.1\n"
                                          "tolerance_reason = \"a unit test's margin\"\n");
  int interval = 0, within = 0;
  for (const auto& c : r.json.at("checks")) {
    const std::string q = c.at("quantity");
    if (q.rfind("noise fraction of", 0) != 0) continue;
    CHECK(c.at("reference").get<double>() == Approx(12.0 / 17.0).epsilon(1e-12));
    if (q.find("within ±") != std::string::npos) {
      ++within;
      const double err = std::abs(c.at("dem").get<double>() - c.at("reference").get<double>());
      CHECK(err < 0.05);  // 512 rows × 4 replicates: the estimate is close
      CHECK(c.at("passed").get<bool>() == (err <= 0.1));
    } else {
      ++interval;
      CHECK_THAT(c.at("tolerance_reason").get<std::string>(), Contains("the 90 % bootstrap interval"));
    }
  }
  CHECK(interval == 1);
  CHECK(within == 1);
}

TEST_CASE("one-at-a-time sweeps cover every output", "[sensitivity]") {
  // the resting disk with a second probe: 1 + 1 × 3 runs, two outputs, a figure and rows for each
  const fs::path root = test::fresh_dir("dem2d_unit_oat_outputs", "two");
  fs::create_directories(root);
  std::string text = test::slurp(test::source("cases/basic/rest_on_wall.toml"));
  text += "\n[[probe]]\nname = \"height\"\nkind = \"value\"\nquantity = \"e0.y\"\n";
  std::ofstream(root / "case.toml") << text;
  std::ofstream(root / "sensitivity.toml")
      << "[sensitivity]\ntitle = \"oat\"\ncase = \"case.toml\"\noutputs = [\"overlap\", \"height\"]\nmethods = [\"oat\"]\n"
         "[[parameter]]\npath = \"contact.0.kn\"\nlabel = \"K\"\nlow = \"5e5 N/m\"\nhigh = \"4e6 N/m\"\n[oat]\npoints = 3\n";
  const ver::StudyResult r = ver::run_sensitivity(root / "sensitivity.toml", test::quiet_options(root / "out"));
  int figures = 0;
  for (const auto& fig : r.json.at("figures"))
    if (fig.value("id", "") == "oat_0" || fig.value("id", "") == "oat_1") ++figures;
  CHECK(figures == 2);
  const std::string csv = test::slurp(root / "out" / "indices.csv");
  CHECK_THAT(csv, Contains("oat,overlap,\"K\",K,range"));
  CHECK_THAT(csv, Contains("oat,height,\"K\",K,range"));
}

TEST_CASE("a Sobol' study of a test function: its figure names the interval, and 100 resamples get the width checks", "[sensitivity][sobol_study]") {
  // without noise, confidence 0.9, exactly 100 bootstrap resamples (the least that
  // compares the intervals' widths with the CLT)
  const ver::StudyResult r =
      linear_study("sobol", "", "samples = 256\nbootstrap = 100\nconfidence = 0.9\nseed = 1\ndelta = true\ndelta_bootstrap = 20\n");
  // the tables: Sobol' over N = 256 rows and 256 (2 + 2) runs; δ over the 512 rows of A and B, the 90 %
  // intervals, one row per parameter of the study's own output
  std::string output;
  bool sobol_title = false, delta_title = false;
  int delta_rows = 0;
  for (const auto& t : r.json.at("tables")) {
    const std::string title = t.at("title");
    if (title.rfind("Sobol' indices (Saltelli sampling", 0) == 0) {
      sobol_title = title.find("N = 256, 1024 runs; 90 % bootstrap intervals") != std::string::npos;
      output = t.at("rows").at(0).at(0);
    }
    if (title.rfind("Borgonovo", 0) == 0) {
      delta_title = title.find("over the 512 rows of A and B") != std::string::npos && title.find("90 % intervals") != std::string::npos;
      for (const auto& row : t.at("rows")) delta_rows += row.at(0) == output ? 1 : 0;
    }
  }
  CHECK(sobol_title);
  CHECK(delta_title);
  CHECK(delta_rows == 2);
  bool labelled = false;
  for (const auto& fig : r.json.at("figures"))
    if (fig.value("id", "") == "sobol_0")
      for (const auto& c : fig.at("curves")) labelled |= c.value("label", "") == "S, 90 % bootstrap interval";
  CHECK(labelled);
  int widths = 0;
  for (const auto& c : r.json.at("checks")) widths += c.at("quantity").get<std::string>().rfind("width of the", 0) == 0 ? 1 : 0;
  CHECK(widths >= 4);  // S and S_T of both inputs at least (Janon's too where its σ_∞ > 0)
}

TEST_CASE("Spearman's rank correlation of two rankings", "[sensitivity]") {
  using ver::sens::spearman;
  CHECK(spearman({1, 2, 3}, {1, 2, 3}) == 1.0);
  CHECK(spearman({1, 2, 3}, {3, 2, 1}) == -1.0);           // 1 − 6·8/(3·8)
  CHECK(spearman({1, 2, 3}, {1, 3, 2}) == Approx(0.5));    // 1 − 6·2/24
  CHECK(spearman({1, 2, 3, 4}, {2, 1, 4, 3}) == Approx(0.6));  // 1 − 6·4/60
  CHECK(ver::sens::descending_ranks({0.1, 0.7, 0.3}) == std::vector<double>{3, 1, 2});
}

TEST_CASE("a sweep whose output variance overflows fails, its indices reported as not computable", "[sensitivity]") {
  // f = 1.5e308 x1 + 1e-300 x2 on [0, 1]²: every output finite, its variance not (it overflows).
  const ver::StudyResult r = linear_study("overflow", "", "samples = 64\nbootstrap = 20\nseed = 1\n", "[1.5e308, 1e-300]");
  CHECK_FALSE(r.passed);
  bool named = false;
  for (const auto& c : r.json["checks"])
    if (c["quantity"].get<std::string>().rfind("Sobol' indices of f computable", 0) == 0) {
      named = true;
      CHECK_FALSE(c["passed"].get<bool>());
      CHECK_THAT(c["note"].get<std::string>(), Contains("6 of 6 indices not computable") && Contains("variance"));
    }
  CHECK(named);
  // The same function scaled down by 1e300 has every index and passes that check (it is absent).
  const ver::StudyResult ok = linear_study("overflow_scaled", "", "samples = 64\nbootstrap = 20\nseed = 1\n", "[1.5e8, 1e-8]");
  for (const auto& c : ok.json["checks"]) CHECK(c["quantity"].get<std::string>().find("computable") == std::string::npos);
}
