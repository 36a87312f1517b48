// Refinement levels declared as [[level]] tables (verification/engine/refinement_levels.hpp): parsing with
// located errors, the convergence series over the levels on synthetic data, and the study engine running
// a [[level]] study exactly as the equivalent one-parameter study.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "engine/refinement_levels.hpp"
#include "engine/study.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

ver::Refinement parse(const std::string& text) {
  const toml::table root = toml::parse(std::string_view{text}, std::string_view{"study.toml"});
  return ver::read_refinement(root, "study.toml");
}

const std::string good = R"([study]
kind = "refinement"
[refinement]
label = "r [m]"
[[level]]
label = "1x3"
h = "12.5 mm"
set = ["lattice.0.radius=12.5 mm", "lattice.0.columns=1"]
args = { n_w = 1, n_h = 3 }
[[level]]
label = "2x6"
h = 6.25e-3
set = ["lattice.0.radius=6.25 mm", "lattice.0.columns=2"]
args = { n_w = 2, n_h = "6" }
[[level]]
label = "3x9"
h = "4.16667 mm"
)";

/// `good` with the first occurrence of `what` replaced by `with`.
std::string edit(const std::string& what, const std::string& with) {
  std::string t = good;
  const auto at = t.find(what);
  REQUIRE(at != std::string::npos);
  return t.replace(at, what.size(), with);
}

}  // namespace

TEST_CASE("Refinement levels: [[level]] tables give h, overrides and reference arguments per level", "[levels]") {
  const ver::Refinement r = parse(good);
  REQUIRE(r.declared_levels);
  REQUIRE(r.levels.size() == 3);
  CHECK(r.label == "r [m]");
  CHECK(r.parameter.empty());
  CHECK_FALSE(r.inverse);
  CHECK(r.levels[0].label == "1x3");
  CHECK(r.levels[0].h == Approx(0.0125).epsilon(1e-15));
  CHECK(r.levels[1].h == Approx(0.00625).epsilon(1e-15));
  CHECK(r.levels[2].h == Approx(0.00416667).epsilon(1e-12));
  CHECK(r.levels[0].set == std::vector<std::string>{"lattice.0.radius=12.5 mm", "lattice.0.columns=1"});
  CHECK(r.levels[1].args.at("n_h") == 6.0);
  CHECK(r.levels[2].set.empty());
  CHECK(r.levels[2].args.empty());

  // n = count: h = 1/n
  const ver::Refinement c = parse("[[level]]\nn = 1\nset = [\"a=1\"]\n[[level]]\nn = 4\n");
  CHECK(c.inverse);
  CHECK(c.levels[1].h == 0.25);
  CHECK(c.levels[1].value == 4.0);
  CHECK(c.levels[0].label == "level 0");
  CHECK(c.label == "h");

  // The values form is unchanged: the same overrides as the engine always wrote.
  const ver::Refinement v = parse("[refinement]\nparameter = \"numerics.dt\"\nvalues = [4e-4, 2e-4]\n");
  CHECK_FALSE(v.declared_levels);
  CHECK(v.levels[0].set == std::vector<std::string>{"numerics.dt=0.00040000000000000002"});
  const ver::Refinement n = parse("[refinement]\nparameter = \"contact.0.segments\"\nvalues = [1, 2]\nh = \"inverse\"\n");
  CHECK(n.levels[1].set == std::vector<std::string>{"contact.0.segments=2"});
  CHECK(n.levels[1].h == 0.5);
}

TEST_CASE("Refinement levels: bad input gets file:line: key: what was expected", "[levels]") {
  // line numbers of `good`: 5 = first [[level]], 7 = its h, 12 = the second level's h
  CHECK_THROWS_WITH(parse(edit("h = 6.25e-3", "h = 6.25e-2")),
                    Contains("study.toml:12: level.h: expected the levels from coarse to fine (h strictly decreasing)"));
  CHECK_THROWS_WITH(parse(edit("h = \"12.5 mm\"\n", "")), Contains("study.toml:5: level.h: missing: the level's length h"));
  CHECK_THROWS_WITH(parse(edit("h = \"12.5 mm\"", "h = \"12.5 mm\"\nn = 1")), Contains("study.toml:8: level.n: give h (a length) or n"));
  CHECK_THROWS_WITH(parse(edit("h = 6.25e-3", "n = 2")), Contains("study.toml:12: level.n: every level gives h, or every level gives n"));
  CHECK_THROWS_WITH(parse(edit("h = \"12.5 mm\"", "h = -1.0")), Contains("study.toml:7: level.h: expected a positive number"));
  CHECK_THROWS_WITH(parse(edit("h = \"12.5 mm\"", "h = \"12.5 parsecs of\"")), Contains("study.toml:7: level.h:"));
  CHECK_THROWS_WITH(parse(edit("h = \"12.5 mm\"", "h = true")),
                    Contains("study.toml:7: level.h: expected a number or a string with a unit"));
  CHECK_THROWS_WITH(parse(edit("set = [\"lattice.0.radius=12.5 mm\", \"lattice.0.columns=1\"]", "set = \"lattice.0.columns=1\"")),
                    Contains("study.toml:8: level.set: expected an array of overrides"));
  CHECK_THROWS_WITH(parse(edit("\"lattice.0.columns=1\"", "\"lattice.0.columns\"")),
                    Contains("study.toml:8: level.set: expected an array of overrides \"path=value\""));
  CHECK_THROWS_WITH(parse(edit("args = { n_w = 1, n_h = 3 }", "args = [1, 3]")),
                    Contains("study.toml:9: level.args: expected a table of reference arguments"));
  CHECK_THROWS_WITH(parse(edit("args = { n_w = 1, n_h = 3 }", "arg = { n_w = 1 }")),
                    Contains("study.toml:9: level.arg: unknown key (expected label, h or n, set, args); did you mean 'args'?"));
  CHECK_THROWS_WITH(parse(edit("label = \"2x6\"", "label = \"1x3\"")), Contains("level.label: \"1x3\" is used by two levels"));
  CHECK_THROWS_WITH(parse(edit("label = \"r [m]\"", "parameter = \"numerics.dt\"")),
                    Contains("study.toml:4: refinement.parameter: with [[level]] tables each level gives its own h"));
  CHECK_THROWS_WITH(parse(edit("label = \"r [m]\"", "values = [1, 2]")), Contains("study.toml:4: refinement.values:"));
  CHECK_THROWS_WITH(parse("[[level]]\nh = 1.0\n"), Contains("study.toml:1: level: need at least two [[level]] tables"));
  CHECK_THROWS_WITH(parse("level = [1, 2]\n"), Contains("study.toml:1: level: expected [[level]] tables"));
  CHECK_THROWS_WITH(parse("level = 3\n"), Contains("study.toml:1: level: expected [[level]] tables"));
  CHECK_THROWS_WITH(parse("[study]\n"), Contains("study.toml: refinement: missing [refinement] table (or [[level]] tables)"));
  // [[level]] tables in a study of another kind
  const toml::table other = toml::parse(std::string_view{"[study]\nkind = \"single\"\n[[level]]\nh = 1.0\n"}, std::string_view{"study.toml"});
  CHECK_THROWS_WITH(ver::refuse_levels(other, "study.toml"), Contains("study.toml:3: level: [[level]] tables need kind = \"refinement\""));
  CHECK_NOTHROW(ver::refuse_levels(toml::parse(std::string_view{"[study]\n"}, std::string_view{"study.toml"}), "study.toml"));
}

TEST_CASE("Refinement levels: observed orders between consecutive levels and Richardson on synthetic data", "[levels]") {
  // Q(h) = Q* + C h^p with h = 1/n, n = 2, 3, 5, 8 (non-constant ratio), p = 2: every two-level order
  // against Q* is 2, the three-level order is 2, Richardson from the finest two is Q* exactly.
  const ver::Refinement r = parse("[[level]]\nlabel = \"a\"\nn = 2\n[[level]]\nlabel = \"b\"\nn = 3\n"
                                  "[[level]]\nlabel = \"c\"\nn = 5\n[[level]]\nlabel = \"d\"\nn = 8\n");
  const double q_exact = 0.7, c = 0.3, p = 2.0;
  std::vector<std::optional<double>> q;
  for (const auto& l : r.levels) q.push_back(q_exact + c * std::pow(1.0 / l.value, p));
  ver::ConvergenceOptions with_ref;
  with_ref.reference = q_exact;
  std::vector<std::string> labels;
  const ver::Series s = ver::analyse_levels(r, q, with_ref, "Q", &labels);
  CHECK(labels == std::vector<std::string>{"a", "b", "c", "d"});
  REQUIRE(s.h.size() == 4);
  CHECK(s.h[1] == Approx(1.0 / 3.0).epsilon(1e-15));
  CHECK_FALSE(s.observed_order[0].has_value());
  for (std::size_t k = 1; k < 4; ++k) CHECK(*s.observed_order[k] == Approx(p).epsilon(1e-9));
  CHECK(*s.fitted_order == Approx(p).epsilon(1e-9));
  CHECK(*s.three_level_order == Approx(p).epsilon(1e-8));
  CHECK(*s.richardson == Approx(q_exact).epsilon(1e-10));
  CHECK(s.parameter == "h");

  // Without the reference (compare = "richardson"): the three-level order and Richardson recover p, Q*.
  const ver::Series n = ver::analyse_levels(r, q, {}, "Q");
  CHECK(*n.three_level_order == Approx(p).epsilon(1e-8));
  CHECK(*n.richardson == Approx(q_exact).epsilon(1e-10));

  // An assumed order (p = 1 here, wrong on purpose) moves Richardson by exactly the formula's amount.
  ver::ConvergenceOptions assumed;
  assumed.assumed_order = 1.0;
  const ver::Series a = ver::analyse_levels(r, q, assumed, "Q");
  const double qc = *q[2], qf = *q[3], ratio = 8.0 / 5.0;
  CHECK(*a.richardson == Approx(qf + (qf - qc) / (ratio - 1.0)).epsilon(1e-14));
  CHECK(*a.richardson < q_exact);  // Q falls toward Q* as h², p = 1 extrapolates too far

  // A level without a value is left out, with its label; the ratios follow the remaining h.
  q[1].reset();
  labels.clear();
  const ver::Series m = ver::analyse_levels(r, q, with_ref, "Q", &labels);
  CHECK(labels == std::vector<std::string>{"a", "c", "d"});
  REQUIRE(m.h.size() == 3);
  CHECK(*m.observed_order[1] == Approx(p).epsilon(1e-9));  // from n = 2 to n = 5
  CHECK_THROWS_AS(ver::analyse_levels(r, {0.1, 0.2}, with_ref, "Q"), std::invalid_argument);
}

namespace {

/// Writes <tmp>/verification/<name>/study.toml on the free-fall case (y(0.5 s) exact: 1.27416875 m) and runs it.
ver::StudyResult run_free_fall(const std::string& name, const std::string& body) {
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_levels" / "verification" / name;
  fs::create_directories(dir);
  const std::string kase = std::string(DEM2D_SOURCE_DIR) + "/cases/basic/free_fall.toml";
  std::ofstream(dir / "study.toml") << "[study]\ntitle = \"" << name << "\"\nrequirement = \"engine test\"\n"
                                    << "kind = \"refinement\"\ncase = \"" << kase << "\"\n" << body;
  ver::StudyOptions opt;
  opt.out_dir = dir / "out";
  opt.print = false;
  opt.use_cache = false;
  return ver::run_study(dir / "study.toml", opt);
}

const std::string variant = "[[variant]]\nlabel = \"K18 plain\"\nset = [\"numerics.velocity_start=plain\"]\n"
                            "args = { x0 = 2.0, v0 = 1.0, g = -9.80665, t = 0.5 }\n";
const std::string check = "[[check]]\nprobe = \"y_end\"\nreference = \"free_fall.position\"\ntolerance = 1.0\n"
                          "reason = \"engine test\"\nexpected_order = 1.0\norder_band = 0.2\n";

}  // namespace

TEST_CASE("Refinement levels: a [[level]] study gives the same series and checks as the one-parameter study", "[levels][study]") {
  const auto values = run_free_fall("levels_values", "[refinement]\nparameter = \"numerics.dt\"\nlabel = \"dt [s]\"\n"
                                                     "values = [4e-4, 2e-4, 1e-4]\n" + variant + check);
  const auto levels = run_free_fall("levels_tables", "[refinement]\nlabel = \"dt [s]\"\n"
                                                     "[[level]]\nlabel = \"coarse\"\nh = 4e-4\nset = [\"numerics.dt=4e-4\"]\n"
                                                     "[[level]]\nlabel = \"medium\"\nh = \"0.2 ms\"\nset = [\"numerics.dt=2e-4\"]\n"
                                                     "[[level]]\nlabel = \"fine\"\nh = 1e-4\nset = [\"numerics.dt=1e-4\"]\n" +
                                                         variant + check);
  REQUIRE(values.json["series"].size() == 1);
  REQUIRE(levels.json["series"].size() == 1);
  const auto& a = values.json["series"][0];
  const auto& b = levels.json["series"][0];
  for (const char* key : {"h", "value", "error", "observed_order", "fitted_order", "richardson", "gci_fine", "three_level_order"})
    CHECK(a[key] == b[key]);
  CHECK(b["level_labels"] == nlohmann::json({"coarse", "medium", "fine"}));
  CHECK(a["observed_order"][2].get<double>() == Approx(1.0).margin(1e-6));  // K18 plain start: first order
  CHECK(values.json["checks"][0]["observed_order"] == levels.json["checks"][0]["observed_order"]);
  CHECK(values.passed);
  CHECK(levels.passed);
  // The order band still decides: expected 1.5 ± 0.2 must fail the same sequence.
  std::string wrong = check;
  wrong.replace(wrong.find("expected_order = 1.0"), 20, "expected_order = 1.5");
  CHECK_FALSE(run_free_fall("levels_order_fail", "[[level]]\nh = 4e-4\nset = [\"numerics.dt=4e-4\"]\n"
                                                 "[[level]]\nh = 2e-4\nset = [\"numerics.dt=2e-4\"]\n" + variant + wrong)
                  .passed);
}

TEST_CASE("Refinement levels: compare = each checks every level against its own reference, and a moving reference is refused",
          "[levels][study][must_fail]") {
  // The level's args override the variant's: v0 = 1.0 at the coarse level is the true initial
  // velocity, v0 = 1.1 at the fine level is wrong by 0.05 m at t = 0.5 s: that level (only) must fail.
  const std::string levels = "[[level]]\nlabel = \"coarse\"\nh = 4e-4\nset = [\"numerics.dt=4e-4\"]\nargs = { v0 = 1.0 }\n"
                             "[[level]]\nlabel = \"fine\"\nh = 2e-4\nset = [\"numerics.dt=2e-4\"]\nargs = { v0 = 1.1 }\n";
  const std::string each = "[[check]]\nprobe = \"y_end\"\nreference = \"free_fall.position\"\ncompare = \"each\"\n"
                           "tolerance = 0.01\nreason = \"engine test\"\n";
  const auto r = run_free_fall("levels_each", levels + variant + each);
  REQUIRE(r.json["checks"].size() == 2);
  CHECK(r.json["checks"][0]["quantity"].get<std::string>() == "y_end, K18 plain [coarse]");
  CHECK(r.json["checks"][0]["passed"].get<bool>());
  CHECK_FALSE(r.json["checks"][1]["passed"].get<bool>());
  CHECK(r.json["checks"][1]["reference"].get<double>() == Approx(1.27416875 + 0.05).epsilon(1e-12));
  CHECK_FALSE(r.passed);
  // The same references for a convergence series (compare = finest) are refused before anything runs.
  std::string finest = each;
  finest.replace(finest.find("compare = \"each\"\n"), 17, "");
  CHECK_THROWS_WITH(run_free_fall("levels_moving_reference", levels + variant + finest),
                    Contains("check.compare: check \"y_end\": the reference free_fall.position is") &&
                        Contains("a convergence series needs one reference"));
  // compare = "each" with an order, or in a single study, is a located error.
  CHECK_THROWS_WITH(run_free_fall("levels_each_order", levels + variant + each + "expected_order = 1.0\n"),
                    Contains("check.compare: compare = \"each\" checks values, not an order"));
}
