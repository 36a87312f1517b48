// A killed sensitivity study (`dem2d sweep`, verification/engine/sensitivity.hpp) leaves no result,
// and run again it reuses every run it had finished and gives the same indices; the Δt tied to the
// time-step guard (dt_fraction) and parameters that set further paths (also) reach the runs.
#include <catch2/catch.hpp>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "quiet_options.hpp"
#include "dem/run/interrupt.hpp"
#include "engine/sensitivity.hpp"

#include "../lib/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

/// A sweep of the resting disk (cases/basic/rest_on_wall.toml) over the wall stiffness and the mass,
/// one-at-a-time with 3 points: 1 + 2 × 3 = 7 runs of 0.1 s. `extra` goes into [sensitivity].
fs::path sweep_file(const std::string& folder, const std::string& extra = {}, const std::string& kn_extra = {}) {
  const fs::path root = test::fresh_dir("dem2d_unit_sweep", folder);
  fs::create_directories(root / "verification" / folder);
  fs::create_directories(root / "cases" / "basic");
  fs::copy_file(test::source("cases/basic/rest_on_wall.toml"), root / "cases/basic/rest_on_wall.toml");
  const fs::path f = root / "verification" / folder / "sensitivity.toml";
  std::ofstream(f) << "[sensitivity]\ntitle = \"resume\"\ncase = \"../../cases/basic/rest_on_wall.toml\"\n"
                      "outputs = [\"overlap\"]\nmethods = [\"oat\"]\n" << extra
                   << "\n[[parameter]]\npath = \"contact.0.kn\"\nlabel = \"K\"\nlow = \"5e5 N/m\"\nhigh = \"4e6 N/m\"\n"
                      "distribution = \"log-uniform\"\n" << kn_extra
                   << "\n[[parameter]]\npath = \"element.0.mass\"\nlabel = \"m\"\nlow = \"0.5 kg\"\nhigh = \"2 kg\"\n"
                      "\n[oat]\npoints = 3\n";
  return f;
}

ver::StudyOptions quiet(const fs::path& out) { return test::quiet_options(out); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Column `col` of every row of a runs.csv (no quoted commas before it).
std::vector<double> csv_column(const std::string& csv, std::size_t col) {
  std::vector<double> v;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
    REQUIRE(cells.size() > col);
    v.push_back(std::stod(cells[col]));
  }
  return v;
}


}  // namespace

TEST_CASE("A killed sweep leaves no result and continues from its finished runs with the same indices", "[sensitivity]") {
  const fs::path f = sweep_file("sweep_resume");
  const fs::path out = test::fresh_dir("dem2d_unit_sweep", "sweep_resume_out");
  const auto r1 = ver::run_sensitivity(f, quiet(out));
  CHECK(r1.passed);
  CHECK(r1.json["provenance"]["runs_run"] == 7);
  CHECK(r1.json["provenance"]["runs_reused"] == 0);
  const std::string indices = slurp(out / "indices.csv"), runs = slurp(out / "runs.csv");
  // Kill it with 3 of its 7 runs lost: SIGTERM stops the first run that is not cached.
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(out / "cache")) entries.push_back(e.path());
  REQUIRE(entries.size() == 7);
  std::sort(entries.begin(), entries.end());
  for (std::size_t k = 0; k < 3; ++k) fs::remove(entries[k]);
  dem::set_interrupt_signal(SIGTERM);
  CHECK_THROWS_AS(ver::run_sensitivity(f, quiet(out)), ver::StudyInterrupted);
  dem::set_interrupt_signal(0);
  CHECK_FALSE(fs::exists(out / "result.json"));  // no stale result
  CHECK(fs::exists(out / "running.json"));
  // Run again: the 4 finished runs are reused, the 3 lost ones run, the indices are the same bit for bit.
  const auto r2 = ver::run_sensitivity(f, quiet(out));
  CHECK(r2.json["provenance"]["runs_reused"] == 4);
  CHECK(r2.json["provenance"]["runs_run"] == 3);
  CHECK(slurp(out / "indices.csv") == indices);
  CHECK(slurp(out / "runs.csv") == runs);
  CHECK_FALSE(fs::exists(out / "running.json"));
  // Once more: everything reused.
  CHECK(ver::run_sensitivity(f, quiet(out)).json["provenance"]["runs_run"] == 0);
}

TEST_CASE("dt_fraction ties each run's time step to the guard's limit, and also sets the following paths", "[sensitivity]") {
  // K from 5e5 to 4e6 N/m (x8): the guard's limit ∝ √(m/K) falls by √8, and so must Δt.
  const fs::path f = sweep_file("sweep_dt", "dt_fraction = 0.05\n");
  const fs::path out = test::fresh_dir("dem2d_unit_sweep", "sweep_dt_out");
  const auto r = ver::run_sensitivity(f, quiet(out));
  CHECK(r.passed);
  const std::string csv = slurp(out / "runs.csv");
  REQUIRE_THAT(csv, Contains(",dt,"));
  // Rows: 0 base, 1–3 K at u = 0, 0.5, 1 (m at base, 1 kg): Δt = 0.05 × the limit, ∝ K^-1/2.
  const std::vector<double> dt = csv_column(csv, 4);  // run, method, K, m, dt
  REQUIRE(dt.size() == 7);
  CHECK(dt[1] / dt[3] == Approx(std::sqrt(8.0)).epsilon(1e-9));
  CHECK(dt[4] / dt[6] == Approx(0.5).epsilon(1e-9));  // m from 0.5 to 2 kg: Δt ∝ √m
  // A parameter's followers: K also sets the stiffness again (same value) and the duration ∝ 1/K (here
  // only to see it reach the run: a refused path would throw).
  const fs::path g = sweep_file("sweep_also", {}, "also = [{ path = \"numerics.duration\", scale = 1e5, exponent = -1.0 }]\n");
  const auto r2 = ver::run_sensitivity(g, quiet(test::fresh_dir("dem2d_unit_sweep", "sweep_also_out")));
  CHECK(r2.passed);
  // Δt as a parameter together with dt_fraction is refused, with the place.
  const fs::path h = sweep_file("sweep_bad", "dt_fraction = 0.05\n");
  {
    std::ofstream(h, std::ios::app) << "\n[[parameter]]\npath = \"numerics.dt\"\nlow = 1e-6\nhigh = 2e-6\n";
  }
  CHECK_THROWS_WITH(ver::run_sensitivity(h, quiet(test::fresh_dir("dem2d_unit_sweep", "sweep_bad_out"))),
                    Contains("sensitivity.toml:") && Contains("dt_fraction"));
}

TEST_CASE("replicates: each sample is the mean of its replicates, a replicate may not override a parameter", "[sensitivity]") {
  // The resting disk's overlap m g / K is linear in g: the mean over g = 8 and 12 m/s² is the overlap at
  // g = 10 m/s², row by row (7 samples, 14 DEM runs).
  const fs::path f = sweep_file("sweep_rep", "replicates = [[\"physics.gravity=[0,-8]\"], [\"physics.gravity=[0,-12]\"]]\n");
  const fs::path out = test::fresh_dir("dem2d_unit_sweep", "sweep_rep_out");
  const auto r = ver::run_sensitivity(f, quiet(out));
  CHECK(r.passed);
  CHECK(r.json["provenance"]["runs_run"] == 14);
  const fs::path g = sweep_file("sweep_rep_ref", "set = [\"physics.gravity=[0,-10]\"]\n");
  const fs::path out_ref = test::fresh_dir("dem2d_unit_sweep", "sweep_rep_ref_out");
  const auto rr = ver::run_sensitivity(g, quiet(out_ref));
  CHECK(rr.json["provenance"]["runs_run"] == 7);
  const std::vector<double> mean = csv_column(slurp(out / "runs.csv"), 4), ref = csv_column(slurp(out_ref / "runs.csv"), 4);
  REQUIRE(mean.size() == 7);
  REQUIRE(ref.size() == 7);
  for (std::size_t k = 0; k < 7; ++k) CHECK(mean[k] == Approx(ref[k]).epsilon(1e-9));
  CHECK(std::abs(ref[1]) > 7.0 * std::abs(ref[3]));  // K × 8 over the sweep: the rows differ (not a trivial comparison)
  // A replicate that sets a parameter's path is refused, with the place.
  const fs::path h = sweep_file("sweep_rep_bad", "replicates = [[\"contact.0.kn=1e6\"], [\"contact.0.kn=2e6\"]]\n");
  CHECK_THROWS_WITH(ver::run_sensitivity(h, quiet(test::fresh_dir("dem2d_unit_sweep", "sweep_rep_bad_out"))),
                    Contains("sensitivity.toml:") && Contains("replicates") && Contains("contact.0.kn"));
  const fs::path one = sweep_file("sweep_rep_one", "replicates = [[\"physics.gravity=[0,-8]\"]]\n");
  CHECK_THROWS_WITH(ver::run_sensitivity(one, quiet(test::fresh_dir("dem2d_unit_sweep", "sweep_rep_one_out"))),
                    Contains("at least 2"));
}

TEST_CASE("a run that ends without a value of an output is a failed run, not a good run with a hole", "[sensitivity]") {
  // The resting disk with a probe at t = 0.09 s and the duration tied to K (1e5 / K): the OAT points
  // K = 5e5, 1.41e6, 4e6 N/m end at 0.2, 0.071, 0.025 s, so two of the seven runs end before the probe.
  const auto sweep = [](const std::string& folder, const std::string& at, int max_failed) {
    const fs::path f = sweep_file(folder, fmt::format("max_failed_runs = {}\n", max_failed),
                                  "also = [{ path = \"numerics.duration\", scale = 1e5, exponent = -1.0 }]\n");
    std::ofstream(f.parent_path().parent_path().parent_path() / "cases/basic/rest_on_wall.toml", std::ios::app)
        << "\n[[probe]]\nname = \"late\"\nkind = \"value\"\nquantity = \"e0.y\"\nat = \"" << at << "\"\n";
    std::string text = slurp(f);
    text.replace(text.find("outputs = [\"overlap\"]"), 21, "outputs = [\"late\"]");
    std::ofstream(f) << text;
    const fs::path out = test::fresh_dir("dem2d_unit_sweep", folder + "_out");
    const auto result = ver::run_sensitivity(f, quiet(out));
    return std::make_pair(result, slurp(out / "runs.csv"));
  };
  const auto count_no_output = [](const nlohmann::json& result) {
    for (const auto& c : result["checks"])
      if (c["quantity"].get<std::string>().rfind("failed runs", 0) == 0) return c["dem"].get<int>();
    return -1;
  };
  const auto [r, runs] = sweep("sweep_no_output", "0.09 s", 0);
  CHECK_FALSE(r.passed);
  CHECK(count_no_output(r.json) == 2);
  std::size_t rows = 0;
  for (std::size_t at = runs.find(",no-output,\"output 'late'"); at != std::string::npos;
       at = runs.find(",no-output,\"output 'late'", at + 1))
    ++rows;
  CHECK(rows == 2);
  // Allowed by max_failed_runs, the same sweep passes, still counting them.
  const auto allowed = sweep("sweep_no_output_allowed", "0.09 s", 2).first;
  CHECK(allowed.passed);
  CHECK(count_no_output(allowed.json) == 2);
  // No run reaches the probe: every run failed, the sweep fails (it used to pass with every index nan).
  const auto none = sweep("sweep_no_output_none", "5 s", 0).first;
  CHECK_FALSE(none.passed);
  CHECK(count_no_output(none.json) == 7);
}
