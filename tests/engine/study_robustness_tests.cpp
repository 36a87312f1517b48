// The study runner and the report facing broken inputs and killed studies (verification/engine/
// study.hpp, reports/study_result.hpp): a malformed study.toml gets a located error, a study name
// cannot leave the output folder, a killed study leaves no stale result.json and continues from its
// cache of finished runs, a broken or incomplete study is listed as such while the others are read.
#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "quiet_options.hpp"
#include "dem/run/interrupt.hpp"
#include "engine/study.hpp"
#include "study_result.hpp"

#include "../lib/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

using test::slurp;
using test::source;

fs::path fresh_dir(const std::string& name) {
  const auto d = test::fresh_dir("dem2d_unit_study", name);
  fs::create_directories(d);
  return d;
}

/// A copy of verification/rest_on_wall/study.toml (a quick two-run study) with `edit` applied, placed
/// in verification/<folder>/ of a temporary tree whose cases/ points to the real case.
/// `replace` is replaced at every occurrence; `prefix` goes before the first line (root keys).
fs::path study_copy(const std::string& folder, const std::string& replace = {}, const std::string& with = {},
                    const std::string& prefix = {}) {
  const fs::path root = fresh_dir("tree_" + folder);
  fs::create_directories(root / "verification" / folder);
  fs::create_directories(root / "cases" / "basic");
  fs::copy_file(source("cases/basic/rest_on_wall.toml"), root / "cases/basic/rest_on_wall.toml");
  std::ifstream in(source("verification/rest_on_wall/study.toml"));
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  if (!replace.empty()) {
    REQUIRE(text.find(replace) != std::string::npos);
    for (auto at = text.find(replace); at != std::string::npos; at = text.find(replace, at + with.size()))
      text.replace(at, replace.size(), with);
  }
  text = prefix + text;
  const fs::path file = root / "verification" / folder / "study.toml";
  std::ofstream(file) << text;
  return file;
}

/// The [study] header followed by a name line.
std::string fmt_name(const std::string& name) { return "[study]\nname = \"" + name + "\"\n"; }

ver::StudyOptions quiet(const fs::path& out) { return test::quiet_options(out); }

}  // namespace

TEST_CASE("A malformed study file gets a located error, not a crash", "[study]") {
  // check = [1] (an array of numbers) instead of [[check]] tables: used to dereference a null table.
  const fs::path f = study_copy("bad_check", "[[check]]", "[other_check]", "check = [1]\n");
  const fs::path out = fresh_dir("bad_check_out");
  CHECK_THROWS_WITH(ver::run_study(f, quiet(out)), Contains("study.toml:1: check: expected [[check]] tables"));
  // variant = [2]: an array that holds no table.
  const fs::path g = study_copy("bad_variant", "[[variant]]", "[[other_variant]]", "variant = [2]\n");
  CHECK_THROWS_WITH(ver::run_study(g, quiet(out)), Contains("study.toml:1: variant: expected [[variant]] tables"));
  // check = 3: not an array at all.
  const fs::path h = study_copy("bad_check3", "[[check]]", "[other_check]", "check = 3\n");
  CHECK_THROWS_WITH(ver::run_study(h, quiet(out)), Contains("study.toml:1: check: expected [[check]] tables"));
}

TEST_CASE("A study name cannot write outside the output folder", "[study]") {
  // From a scratch working directory, so that a broken guard writes only below it.
  const fs::path cwd = fs::current_path(), scratch = fresh_dir("bad_name_cwd") / "x" / "y";
  fs::create_directories(scratch);
  fs::current_path(scratch);
  for (const char* name : {"../escape", "a/b", "..", "/tmp/dem2d_unit_study/abs"}) {
    INFO(name);
    const fs::path f = study_copy("bad_name", "[study]\n", fmt_name(name));
    CHECK_THROWS_WITH(ver::run_study(f, quiet({})), Contains("study.name") && Contains("plain folder name"));
  }
  fs::current_path(cwd);
}

TEST_CASE("A killed study leaves no stale result and continues from its finished runs", "[study]") {
  const fs::path f = study_copy("resume");
  const fs::path out = fresh_dir("resume_out");
  // A first, complete run: two runs done, none reused.
  const auto r1 = ver::run_study(f, quiet(out));
  REQUIRE(fs::exists(out / "result.json"));
  CHECK_FALSE(fs::exists(out / "running.json"));
  CHECK(r1.json["provenance"]["runs_run"] == 2);
  CHECK(r1.json["provenance"]["runs_reused"] == 0);
  // Killed (SIGTERM at the first step of the first run that is not cached): no result.json is left
  // behind, running.json says why, and the report lists the study as incomplete.
  fs::remove_all(out / "cache");
  dem::set_interrupt_signal(SIGTERM);
  CHECK_THROWS_AS(ver::run_study(f, quiet(out)), ver::StudyInterrupted);
  dem::set_interrupt_signal(0);
  CHECK_FALSE(fs::exists(out / "result.json"));
  CHECK(fs::exists(out / "running.json"));
  const auto listed = report::read_study_results(out.parent_path());
  bool found = false;
  for (const auto& s : listed)
    if (s.folder == out.filename().string()) {
      found = true;
      CHECK_THAT(s.read_error, Contains("interrupted"));
    }
  CHECK(found);
  // Run again: runs finished earlier are reused (here: all, after a complete run), results identical.
  const auto r2 = ver::run_study(f, quiet(out));
  const auto r3 = ver::run_study(f, quiet(out));
  CHECK(r3.json["provenance"]["runs_reused"] == 2);
  CHECK(r3.json["provenance"]["runs_run"] == 0);
  CHECK(r3.json["checks"].dump() == r1.json["checks"].dump());
  CHECK(r2.json["checks"].dump() == r1.json["checks"].dump());
  // --fresh clears the cache: every run again.
  auto o = quiet(out);
  o.use_cache = false;
  CHECK(ver::run_study(f, o).json["provenance"]["runs_run"] == 2);
}

TEST_CASE("One broken result.json does not stop the others from being read", "[study][report]") {
  const fs::path dir = fresh_dir("broken_results");
  for (const char* d : {"a_good", "b_truncated", "c_no_order", "d_running"}) fs::create_directories(dir / d);
  std::ofstream(dir / "a_good" / "result.json") << R"({"study": "a", "passed": true, "checks": [{"passed": true}]})";
  std::ofstream(dir / "b_truncated" / "result.json") << R"({"study": "b", "checks": [)";
  std::ofstream(dir / "c_no_order" / "result.json") << R"({"study": "c", "passed": false, "checks": [{"passed": false, "observed_order": 2}]})";
  std::ofstream(dir / "d_running" / "running.json") << R"({"status": "running"})";
  const auto studies = report::read_study_results(dir);
  REQUIRE(studies.size() == 4);
  CHECK(report::study_status(studies[0]) == "PASS");
  CHECK(report::study_status(studies[1]) == "UNREADABLE");
  CHECK(report::study_status(studies[2]) == "FAIL");
  CHECK_FALSE(report::number_field(report::array_field(studies[2].result, "checks")[0], "expected_order"));
  CHECK(report::study_status(studies[3]) == "UNREADABLE");
  CHECK_THAT(studies[3].read_error, Contains("interrupted or is still running"));
}

TEST_CASE("A study that fails after it started says so in running.json, and the report shows why", "[study][report]") {
  // A case key that reads but a run the case reader refuses at run time: a variant that sets the time
  // step above the stability limit. The study stops with the guard's message; running.json records it.
  const fs::path dir = fresh_dir("failed_mark");
  const fs::path f = dir / "verification" / "fails" / "study.toml";
  fs::create_directories(f.parent_path());
  std::ofstream(f) << "[study]\ncase = \"" << test::source("cases/impact/disk_wall.toml").string()
                   << "\"\n[[variant]]\nlabel = \"too large\"\nset = [\"numerics.dt=1e-2\"]\n"
                      "[[check]]\nprobe = \"e\"\nvalue = 0.5\ntolerance = 1\nreason = \"engine test\"\n";
  const fs::path out = dir / "studies" / "fails";
  CHECK_THROWS(ver::run_study(f, quiet(out)));
  const nlohmann::json mark = nlohmann::json::parse(std::ifstream(out / "running.json"));
  CHECK(mark["status"] == "failed");
  CHECK_THAT(mark["message"].get<std::string>(), Contains("numerics.dt"));
  const auto studies = report::read_study_results(dir / "studies");
  REQUIRE(studies.size() == 1);
  CHECK_THAT(studies[0].read_error, StartsWith("no result.json: the study failed: ") && Contains("numerics.dt"));
}

namespace {

/// rest_on_wall with a trend check over its two variants (K18 → K19, equal to round-off), a table
/// of probes across variants and a probe figure (x = the variant argument n).
fs::path trend_study(const std::string& folder, const std::string& trend, const std::string& tolerance) {
  const std::string extra = "\n[[check]]\nprobe = \"overlap\"\nlabel = \"trend\"\ntrend = \"" + trend +
                            "\"\ntolerance = " + tolerance + "\nreason = \"test\"\n"
                            "\n[[table]]\ntitle = \"cost\"\nprobes = [\"element_steps_per_second\", \"overlap\"]\n"
                            "\n[[figure]]\nid = \"p\"\nprobe = \"overlap\"\nx_arg = \"n\"\n"
                            "reference = \"rest.overlap\"\nreference_scale = -1.0\nargs = { m = 1.0, g = 9.80665, K = 1e6 }\n";
  const fs::path f = study_copy(folder, "set = [\"numerics.integrator=K19\"]",
                                "set = [\"numerics.integrator=K19\"]\nargs = { n = 2 }");
  std::string text;
  {
    std::ifstream in(f);
    std::stringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  const std::string k18 = "set = [\"numerics.integrator=K18\"]";
  text.replace(text.find(k18), k18.size(), k18 + "\nargs = { n = 1 }");
  std::ofstream(f) << text + extra;
  return f;
}

const nlohmann::json* check_named(const nlohmann::json& result, const std::string& name) {
  for (const auto& c : result["checks"])
    if (c["quantity"] == name) return &c;
  return nullptr;
}

}  // namespace

TEST_CASE("A trend check passes only when every step moves the asserted way by more than the tolerance", "[study]") {
  // K18 and K19 settle to the same overlap (to round-off): no step exceeds +1e-9, every step exceeds −1e-9.
  const auto strict = ver::run_study(trend_study("trend_strict", "decreasing", "1e-9"), quiet(fresh_dir("trend_strict_out")));
  const auto* c = check_named(strict.json, "trend");
  REQUIRE(c);
  CHECK((*c)["expect"] == "decreasing");
  CHECK_FALSE((*c)["passed"].get<bool>());
  CHECK_FALSE(strict.passed);
  CHECK(std::abs((*c)["error"].get<double>()) < 1e-15);
  CHECK((*c)["note"].get<std::string>().find("K18: ") != std::string::npos);

  const auto loose = ver::run_study(trend_study("trend_loose", "increasing", "-1e-9"), quiet(fresh_dir("trend_loose_out")));
  CHECK((*check_named(loose.json, "trend"))["passed"].get<bool>());
  CHECK(loose.passed);
  // The declared table: one row per variant, the cost and the probe.
  REQUIRE(loose.json["tables"].size() == 1);
  const auto& table = loose.json["tables"][0];
  CHECK(table["columns"] == nlohmann::json({"variant", "element_steps_per_second", "overlap"}));
  REQUIRE(table["rows"].size() == 2);
  CHECK(table["rows"][1][0] == "K19");
  // The probe figure: x = n, the DEM points and the reference at each variant (−x_eq = −mg/K).
  const auto& fig = loose.json["figures"][0];
  REQUIRE(fig["curves"].size() == 2);
  CHECK(fig["curves"][0]["x"] == nlohmann::json({1.0, 2.0}));
  CHECK(fig["curves"][1]["style"] == "reference");
  CHECK(fig["curves"][1]["y"][0].get<double>() == Approx(-9.80665e-6).epsilon(1e-12));
  CHECK(fig["curves"][0]["y"][1].get<double>() == Approx(-9.80665e-6).epsilon(1e-9));
}

TEST_CASE("Bad trend and figure declarations get a located error", "[study]") {
  const fs::path out = fresh_dir("trend_bad_out");
  CHECK_THROWS_WITH(ver::run_study(trend_study("trend_bad", "sideways", "0"), quiet(out)),
                    Contains("check.trend") && Contains("\"decreasing\", \"increasing\", \"toward_reference\", got \"sideways\""));
  const fs::path g = study_copy("range_bad", {}, {}, "");
  std::ofstream(g, std::ios::app) << "\n[[figure]]\ny = \"t\"\nx_range = [1.0, 0.0]\n";
  CHECK_THROWS_WITH(ver::run_study(g, quiet(out)), Contains("figure.x_range") && Contains("lo < hi"));
}

TEST_CASE("A trend check follows the order its variants list names and a figure can show ratios to one variant", "[study]") {
  // The list names K19 before K18 (file order: K18, K19): the steps and the values shown follow the list.
  const fs::path f = trend_study("trend_order", "increasing", "-1e-9");
  std::ofstream(f, std::ios::app) << "\n[[check]]\nprobe = \"overlap\"\nlabel = \"listed order\"\ntrend = \"decreasing\"\n"
                                     "variants = [\"K19\", \"K18\"]\ntolerance = -1e-9\nreason = \"test\"\n"
                                     "\n[[figure]]\nid = \"ratio\"\nprobe = \"overlap\"\nx_arg = \"n\"\ny_relative_to = \"K19\"\n";
  const auto r = ver::run_study(f, quiet(fresh_dir("trend_order_out")));
  const auto* c = check_named(r.json, "listed order");
  REQUIRE(c);
  const std::string note = (*c)["note"].get<std::string>();
  REQUIRE(note.find("K19: ") != std::string::npos);
  CHECK(note.find("K19: ") < note.find("K18: "));
  // y over K19's value: K19's point is exactly 1, K18's equal to it up to round-off (the same overlap).
  const nlohmann::json* fig = nullptr;
  for (const auto& x : r.json["figures"])
    if (x["id"] == "ratio") fig = &x;
  REQUIRE(fig);
  const auto& y = (*fig)["curves"][0]["y"];
  REQUIRE(y.size() == 2);
  CHECK(y[1].get<double>() == 1.0);
  CHECK(y[0].get<double>() == Approx(1.0).epsilon(1e-9));
}

TEST_CASE("y_relative_to names a variant of the study and needs a probe figure", "[study]") {
  const fs::path out = fresh_dir("relative_bad_out");
  const fs::path f = trend_study("relative_bad", "increasing", "-1e-9");
  std::ofstream(f, std::ios::app) << "\n[[figure]]\nid = \"ratio\"\nprobe = \"overlap\"\nx_arg = \"n\"\ny_relative_to = \"K20\"\n";
  CHECK_THROWS_WITH(ver::run_study(f, quiet(out)), Contains("figure.y_relative_to") && Contains("no variant \"K20\""));
  const fs::path g = study_copy("relative_series", {}, {}, "");
  std::ofstream(g, std::ios::app) << "\n[[figure]]\ny = \"t\"\ny_relative_to = \"K18\"\n";
  CHECK_THROWS_WITH(ver::run_study(g, quiet(out)), Contains("figure.y_relative_to") && Contains("needs a probe figure"));
}

TEST_CASE("A check against another variant takes that variant's value of the probe as its reference", "[study]") {
  const fs::path f = trend_study("against_variant", "increasing", "-1e-9");
  std::ofstream(f, std::ios::app) << "\n[[check]]\nprobe = \"overlap\"\nlabel = \"K19 as K18\"\nagainst_variant = \"K18\"\n"
                                     "variants = [\"K19\"]\nerror = \"rel\"\ntolerance = 1e-9\nreason = \"test\"\n"
                                     "\n[[check]]\nprobe = \"overlap\"\nlabel = \"K19 above K18\"\nagainst_variant = \"K18\"\n"
                                     "variants = [\"K19\"]\nexpect = \"above\"\ntolerance = 0.0\nreason = \"test\"\n";
  const auto r = ver::run_study(f, quiet(fresh_dir("against_variant_out")));
  const nlohmann::json* same = nullptr;
  const nlohmann::json* above = nullptr;
  for (const auto& c : r.json["checks"]) {
    const std::string q = c["quantity"].get<std::string>();
    if (q.rfind("K19 as K18", 0) == 0) same = &c;
    if (q.rfind("K19 above K18", 0) == 0) above = &c;
  }
  REQUIRE(same);
  REQUIRE(above);
  // K18 and K19 settle to the same overlap (−mg/K) up to round-off: within 1e-9, and not above it.
  CHECK((*same)["passed"].get<bool>());
  CHECK((*same)["reference"].get<double>() == Approx(-9.80665e-6).epsilon(1e-9));
  CHECK_FALSE((*above)["passed"].get<bool>());
}

TEST_CASE("against_variant is refused without a known variant or when it would compare a variant with itself", "[study]") {
  const fs::path out = fresh_dir("against_bad_out");
  auto bad = [&](const std::string& folder, const std::string& body) {
    const fs::path f = trend_study(folder, "increasing", "-1e-9");
    std::ofstream(f, std::ios::app) << "\n[[check]]\nprobe = \"overlap\"\n" << body << "tolerance = 0.0\nreason = \"test\"\n";
    return f;
  };
  CHECK_THROWS_WITH(ver::run_study(bad("against_unknown", "against_variant = \"K20\"\nvariants = [\"K19\"]\n"), quiet(out)),
                    Contains("check.against_variant") && Contains("no variant \"K20\""));
  CHECK_THROWS_WITH(ver::run_study(bad("against_self", "against_variant = \"K18\"\n"), quiet(out)),
                    Contains("check.against_variant") && Contains("cannot fail"));
  CHECK_THROWS_WITH(ver::run_study(bad("against_value", "against_variant = \"K18\"\nvalue = 1.0\nvariants = [\"K19\"]\n"), quiet(out)),
                    Contains("check.against_variant") && Contains("one of them"));
}
