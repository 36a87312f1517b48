// The study engine's own pass/fail logic: studies that MUST fail (and, beside each, the same study
// with a correct expectation, which must pass, so that a failure is for the stated reason).
// Every study runs the free-fall case (K18 staggered, exact parabola: y(0.5 s) = 1.27416875 m).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/study.hpp"

namespace fs = std::filesystem;

namespace {

constexpr double y_exact = 2.0 + 1.0 * 0.5 - 0.5 * 9.80665 * 0.25;  // 1.27416875 m

/// Writes <tmp>/verification/<name>/study.toml (the engine takes the root two folders up) and runs it.
ver::StudyResult run(const std::string& name, const std::string& body) {
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_engine" / "verification" / name;
  fs::create_directories(dir);
  const std::string kase = std::string(DEM2D_SOURCE_DIR) + "/cases/basic/free_fall.toml";
  std::ofstream(dir / "study.toml") << "[study]\ntitle = \"" << name << "\"\nrequirement = \"engine test\"\n"
                                    << "case = \"" << kase << "\"\n" << body;
  ver::StudyOptions opt;
  opt.out_dir = dir / "out";
  opt.print = false;
  return ver::run_study(dir / "study.toml", opt);
}

/// Full precision, so that the margins below are what the study file says.
std::string num(double x) {
  std::ostringstream o;
  o.precision(17);
  o << x;
  return o.str();
}

std::string single(double value, const std::string& expect, double tolerance, const std::string& extra = "") {
  return "kind = \"single\"\n" + extra + "\n[[check]]\nprobe = \"y_end\"\nvalue = " + num(value) +
         "\nexpect = \"" + expect + "\"\ntolerance = " + num(tolerance) + "\nreason = \"engine test\"\n";
}

bool check_passed(const ver::StudyResult& r) {
  REQUIRE(r.json["checks"].size() == 1);
  return r.json["checks"][0]["passed"].get<bool>();
}

}  // namespace

TEST_CASE("engine: expect = above fails when the DEM value is not above the reference by the tolerance",
          "[study][must_fail]") {
  CHECK(run("above_ok", single(y_exact - 0.01, "above", 0.001)).passed);
  const auto below = run("above_fail", single(y_exact + 0.01, "above", 0.001));
  CHECK_FALSE(below.passed);
  CHECK_FALSE(check_passed(below));
  CHECK_FALSE(run("above_fail_margin", single(y_exact - 0.0005, "above", 0.001)).passed);  // above, not by 1 mm
}

TEST_CASE("engine: expect = below fails when the DEM value is not below the reference by the tolerance",
          "[study][must_fail]") {
  CHECK(run("below_ok", single(y_exact + 0.01, "below", 0.001)).passed);
  CHECK_FALSE(run("below_fail", single(y_exact - 0.01, "below", 0.001)).passed);
  CHECK_FALSE(run("below_fail_margin", single(y_exact + 0.0005, "below", 0.001)).passed);
}

TEST_CASE("engine: expect = within fails outside the tolerance, absolute and relative", "[study][must_fail]") {
  CHECK(run("within_ok", single(y_exact + 1e-3, "within", 2e-3)).passed);
  CHECK_FALSE(run("within_fail", single(y_exact + 1e-3, "within", 5e-4)).passed);
  CHECK_FALSE(run("within_fail_low", single(y_exact - 1e-3, "within", 5e-4)).passed);
  // relative: |error|/|ref| = 1e-3/1.27 = 7.8e-4
  const std::string rel = "\nerror = \"rel\"\n";
  CHECK(run("rel_ok", single(y_exact + 1e-3, "within", 1e-3) + rel).passed);
  CHECK_FALSE(run("rel_fail", single(y_exact + 1e-3, "within", 7e-4) + rel).passed);
}

TEST_CASE("engine: a missing DEM value fails the check, whatever the tolerance", "[study][must_fail]") {
  // The run ends at 0.2 s; the probe asks for 0.5 s: no DEM value.
  const std::string shorter = "[[variant]]\nlabel = \"short\"\nset = [\"numerics.duration=0.2\"]\n";
  const auto r = run("missing_value", single(y_exact, "within", 1e9, shorter));
  CHECK_FALSE(r.passed);
  CHECK(r.json["checks"][0]["dem"].is_null());
  CHECK(run("missing_value_control", single(y_exact, "within", 1e-9)).passed);
}

TEST_CASE("engine: an observed order outside the expected band fails the check", "[study][must_fail]") {
  // K18 plain start: error −g t Δt/2 exactly, observed order 1.
  auto refinement = [](double order) {
    return std::string("kind = \"refinement\"\n[refinement]\nparameter = \"numerics.dt\"\nlabel = \"dt\"\n"
                       "values = [4e-4, 2e-4, 1e-4]\n[[variant]]\nlabel = \"K18 plain\"\n"
                       "set = [\"numerics.velocity_start=plain\"]\n[[check]]\nprobe = \"y_end\"\n"
                       "reference = \"free_fall.position\"\nargs = { x0 = 2.0, v0 = 1.0, g = -9.80665, t = 0.5 }\n"
                       "tolerance = 1.0\nreason = \"engine test\"\nexpected_order = ") +
           num(order) + "\norder_band = 0.2\n";
  };
  const auto ok = run("order_ok", refinement(1.0));
  CHECK(ok.passed);
  CHECK(ok.json["checks"][0]["observed_order"].get<double>() == Approx(1.0).margin(1e-6));
  CHECK_FALSE(run("order_fail_high", refinement(1.5)).passed);
  CHECK_FALSE(run("order_fail_low", refinement(0.7)).passed);
}
