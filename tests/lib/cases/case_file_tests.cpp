// Case files (case_file.hpp): every error is reported before anything runs, as
// `file:line: key: what was expected`; `--set` overrides change values (with units) and name
// themselves in their errors. The error variants are tests/lib/fixtures/minimal.toml with one line
// changed; the test finds that line's number itself.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/run/run.hpp"
#include "../test_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using Catch::Matchers::WithinRel;

namespace {

std::string minimal_text() {
  std::ifstream in(test::case_dir() / "minimal.toml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Variant {
  std::string path;  // the written file
  int line = 0;      // 1-based line of the changed text
};

/// minimal.toml with the first occurrence of `from` replaced by `to` (plus `append` at the end),
/// written to a temporary file named `name`.
Variant variant(const std::string& name, const std::string& from, const std::string& to,
                const std::string& append = "") {
  std::string text = minimal_text();
  const auto pos = text.find(from);
  REQUIRE(pos != std::string::npos);
  Variant v;
  v.line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
  text.replace(pos, from.size(), to);
  v.path = test::write_temp(name, text + append).string();
  return v;
}

std::string read_error(const std::string& path, const std::vector<std::string>& overrides = {}) {
  return test::message_of<dem::CaseError>([&] { dem::read_case(path, overrides); });
}

std::string check_error(const std::string& path) {
  return test::message_of<dem::CaseError>([&] { dem::check_case(dem::read_case(path)); });
}

std::string at(const Variant& v) { return v.path + ":" + std::to_string(v.line) + ": "; }

std::string num(double x) {
  char s[40];
  std::snprintf(s, sizeof s, "%.17g", x);
  return s;
}

}  // namespace

TEST_CASE("case file: the minimal case reads, with SI values", "[case]") {
  const auto c = dem::read_case(test::case_dir() / "minimal.toml");
  CHECK(c.title == "minimal");
  REQUIRE(c.model.elements.size() == 1);
  CHECK(c.model.elements.radius[0] == 0.01);
  CHECK(c.model.elements.mass[0] == 0.5);
  CHECK_THAT(c.model.elements.inertia[0], WithinRel(0.5 * 0.5 * 0.01 * 0.01, 1e-14));  // ½ m r²
  REQUIRE(c.model.laws.size() == 1);
  CHECK(c.model.laws[0].linear.kn == 1e5);
  CHECK_THAT(c.model.laws[0].linear.ks, WithinRel(2.5e4, 1e-15));
  CHECK(c.model.laws[0].linear.mu == 0.5);
  CHECK(c.model.numerics.dt == 1e-5);
  CHECK(c.model.gravity.y == -9.81);
  CHECK_NOTHROW(dem::check_case(c));
}

TEST_CASE("case file: malformed TOML gives file:line: syntax", "[case]") {
  const auto v = variant("syntax.toml", "radius = \"1 cm\"", "radius = \"1 cm");
  const auto msg = read_error(v.path);
  CHECK_THAT(msg, StartsWith(at(v) + "syntax"));
}

TEST_CASE("case file: errors name file, line, key and what was expected", "[case]") {
  struct Bad {
    const char* name;
    const char* from;
    const char* to;
    const char* key;
    const char* expected;
  };
  const auto bad = GENERATE(
      Bad{"unknown_key.toml", "mass = \"0.5 kg\"", "colour = \"red\"", "element.0.colour", "unknown key"},
      Bad{"wrong_type.toml", "radius = \"1 cm\"", "radius = true", "element.0.radius",
          "expected length as a number (SI) or a string with a unit, got a boolean"},
      Bad{"wrong_dimension.toml", "mass = \"0.5 kg\"", "mass = \"25 mm\"", "element.0.mass", "expected a mass"},
      Bad{"negative_radius.toml", "radius = \"1 cm\"", "radius = \"-1 cm\"", "element.0.radius", "must be positive"},
      Bad{"negative_mu.toml", "friction = 0.5", "friction = -0.1", "contact.0.friction", "must not be negative"},
      Bad{"unknown_material.toml", "material = \"sand\"", "material = \"clay\"", "element.0.material",
          "unknown material \"clay\""},
      Bad{"stiffness_unit.toml", "kn = \"1e5 N/m\"", "kn = \"1e5 N\"", "contact.0.kn", "expected stiffness"},
      Bad{"bad_choice.toml", "law = \"linear\"", "law = \"hertz\"", "contact.0.law",
          "expected one of \"linear\", \"face\""});
  CAPTURE(bad.name);
  const auto v = variant(bad.name, bad.from, bad.to);
  const auto msg = read_error(v.path);
  CHECK_THAT(msg, StartsWith(at(v) + bad.key + ": "));
  CHECK_THAT(msg, Contains(bad.expected));
}

TEST_CASE("case file: a missing key names the table's line", "[case]") {
  const auto v = variant("missing_key.toml", "radius = \"1 cm\"\n", "");
  const auto msg = read_error(v.path);
  // the [[element]] header is two lines above the removed radius
  CHECK_THAT(msg, StartsWith(v.path + ":" + std::to_string(v.line - 2) + ": element.0.radius: "));
  CHECK_THAT(msg, Contains("missing"));
}

TEST_CASE("case file: a time step above the stability limit names the limit and allow_unstable", "[case]") {
  // Without shear (ks = 0) the assembly is one mass on a spring–dashpot: m = 0.5 kg, K = 1e5 N/m,
  // ζ = 0.3 → K18 limit Δt = 2(√(1 + ζ²) − ζ)/ω₀ (docs/references.md §1.5) = 1.488061/447.2136 s.
  const double limit = 2.0 * (std::sqrt(1.09) - 0.3) / std::sqrt(1e5 / 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", limit);
  const auto v = variant("unstable.toml", "ks_ratio = 0.25", "ks_ratio = 0.0");
  // inside the limit: fine; above it: refused; with allow_unstable: accepted
  auto c = dem::read_case(v.path, {"numerics.dt=" + num(0.99 * limit)});
  CHECK_THAT(dem::check_case(c), WithinRel(limit, 1e-12));
  const auto msg = test::message_of<dem::CaseError>(
      [&] { dem::check_case(dem::read_case(v.path, {"numerics.dt=" + num(1.01 * limit)})); });
  // The value came from --set, and the message says so (a value from the file names file:line).
  CHECK_THAT(msg, StartsWith("--set numerics.dt=" + num(1.01 * limit) + ": numerics.dt: "));
  CHECK_THAT(msg, Contains(std::string("stability limit ") + text + " s"));
  const auto in_file = variant("unstable_in_file.toml", "ks_ratio = 0.25", "ks_ratio = 0.0");
  const auto msg2 = test::message_of<dem::CaseError>([&] {
    auto c2 = dem::read_case(in_file.path);
    c2.model.numerics.dt = 1.01 * limit;  // as if the file had said so: the location is the file's line
    dem::check_case(c2);
  });
  CHECK_THAT(msg2, StartsWith(in_file.path + ":") && Contains(": numerics.dt: "));
  CHECK_THAT(msg, Contains("allow_unstable"));
  c = dem::read_case(v.path, {"numerics.dt=" + num(1.01 * limit), "numerics.allow_unstable=true"});
  CHECK_NOTHROW(dem::check_case(c));
}

TEST_CASE("case file: overlapping fixed geometry is refused", "[case]") {
  const std::string fixed = R"(
[[contact]]
between = ["sand", "sand"]
law = "linear"
kn = "1e5 N/m"
friction = 0.5
damping_ratio = 0.3

[[element]]
material = "sand"
radius = "1 cm"
position = ["0 m", "10 cm"]
motion = "fixed"

[[element]]
material = "sand"
radius = "1 cm"
position = ["1.5 cm", "10 cm"]
motion = "fixed"
)";
  const auto v = variant("fixed_overlap.toml", "# Unit-test case", "# Unit-test case", fixed);
  const auto msg = check_error(v.path);
  // at the line of the second element's table, naming the first one's (the minimal case's own element is element 0)
  const std::string text = test::slurp(v.path);
  const auto line_of_nth_element = [&](int nth) {
    std::size_t at = 0;
    for (int k = 0; k <= nth; ++k) at = text.find("[[element]]", k == 0 ? 0 : at + 1);
    REQUIRE(at != std::string::npos);
    return std::to_string(1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
  };
  CHECK_THAT(msg, StartsWith(v.path + ":" + line_of_nth_element(2) + ": element.2: elements 1 and 2 overlap by 0.005 m at the start "
                             "(element 1: element.1, " + v.path + ":" + line_of_nth_element(1) + ")"));
  CHECK_THAT(msg, Contains("overlapping fixed geometry"));
  // an element sunk into a wall: the line of its table
  const auto sunk = variant("sunk.toml", "position = [\"0 m\", \"1 cm\"]", "position = [\"0 m\", \"0.5 cm\"]");
  CHECK_THAT(check_error(sunk.path), StartsWith(sunk.path + ":" + std::to_string(sunk.line - 3) +
                                                ": element.0: element 0 overlaps wall \"floor\" by 0.005 m at the start"));
  // the same two elements free may touch slightly, but 0.5 cm is 50 % of a radius
  const auto v2 = variant("free_overlap.toml", "# Unit-test case", "# Unit-test case", [&] {
    std::string s = fixed;
    for (auto p = s.find("motion = \"fixed\""); p != std::string::npos; p = s.find("motion = \"fixed\""))
      s.erase(p, 16);
    return s;
  }());
  CHECK_THAT(check_error(v2.path), Contains("more than 5 % of a radius"));
}

TEST_CASE("case file: --set changes values, with units", "[case]") {
  const auto path = test::case_dir() / "minimal.toml";
  const auto c = dem::read_case(path, {"numerics.dt=2e-6", "contact.0.kn=12 kN/mm", "contact.0.friction=0.25",
                                       "element.0.radius=\"2 cm\"", "numerics.skin=1 mm"});
  CHECK(c.model.numerics.dt == 2e-6);
  CHECK_THAT(c.model.laws[0].linear.kn, WithinRel(1.2e7, 1e-15));
  CHECK_THAT(c.model.laws[0].linear.ks, WithinRel(0.25 * 1.2e7, 1e-15));  // ks_ratio applies to the new kn
  CHECK(c.model.laws[0].linear.mu == 0.25);
  CHECK(c.model.elements.radius[0] == 0.02);
  CHECK(c.model.numerics.skin == 1e-3);
  CHECK(c.overrides.size() == 5);
  CHECK(c.resolved["numerics"]["dt"] == 2e-6);
}

TEST_CASE("case file: --set with a bad path names --set", "[case]") {
  const auto path = (test::case_dir() / "minimal.toml").string();
  CHECK_THAT(read_error(path, {"contact.3.kn=1"}),
             StartsWith("--set contact.3.kn=1: contact.3: ") && Contains("index below 1"));
  CHECK_THAT(read_error(path, {"numerics.dt.x=1"}), StartsWith("--set numerics.dt.x=1: ") && Contains("numerics.dt"));
  CHECK_THAT(read_error(path, {"numerics.dt"}), StartsWith("--set numerics.dt: ") && Contains("key=value"));
}

TEST_CASE("case file: --set with a line break is refused, not cut at it", "[case]") {
  // "numerics.dt=2e-6\nx = 1" used to read as dt = 2e-6 with the rest silently dropped.
  const auto path = (test::case_dir() / "minimal.toml").string();
  CHECK_THAT(read_error(path, {"numerics.dt=2e-6\nnumerics.duration=1"}),
             StartsWith("--set numerics.dt=2e-6\\nnumerics.duration=1: ") && Contains("one line") && Contains("character 17"));
  CHECK_THAT(read_error(path, {"contact.0.kn=12 kN/mm\r"}), Contains("one line") && Contains("character 22"));
  CHECK_THAT(read_error(path, {"numerics.dt=\"2e-6\n\""}), Contains("one line"));
}

// An override's value keeps its origin ("--set key=value") for error messages: apply_override moves the
// parsed node into the tree (toml++ keeps the source of a moved node, not of a copied one).
TEST_CASE("case file: --set with a bad value names --set, the key and what was expected", "[case]") {
  const auto path = (test::case_dir() / "minimal.toml").string();
  CHECK_THAT(read_error(path, {"numerics.dt=abc"}), StartsWith("--set numerics.dt=abc: numerics.dt: "));
  CHECK_THAT(read_error(path, {"numerics.dt=-1e-6"}),
             StartsWith("--set numerics.dt=-1e-6: numerics.dt: ") && Contains("must be positive"));
  CHECK_THAT(read_error(path, {"element.0.mass=25 mm"}),
             StartsWith("--set element.0.mass=25 mm: element.0.mass: ") && Contains("expected a mass"));
  CHECK_THAT(read_error(path, {"numerics.dtt=1"}),
             StartsWith("--set numerics.dtt=1: numerics.dtt: ") && Contains("unknown key"));
}

TEST_CASE("case file: --set with a bad value is refused with the key and what was expected", "[case]") {
  // the part that holds today, whatever the location prefix
  const auto path = (test::case_dir() / "minimal.toml").string();
  CHECK_THAT(read_error(path, {"numerics.dt=-1e-6"}), Contains("numerics.dt: must be positive"));
  CHECK_THAT(read_error(path, {"element.0.mass=25 mm"}), Contains("element.0.mass: expected a mass"));
  CHECK_THAT(read_error(path, {"numerics.dtt=1"}), Contains("numerics.dtt: unknown key"));
}

TEST_CASE("case file: output intervals in steps or as a time that is a whole number of steps", "[case]") {
  const auto path = test::case_dir() / "minimal.toml";  // dt = 1e-5 s
  const auto c = dem::read_case(path, {"output.every=500", "output.vtk_every=1 ms", "output.picture_every=20"});
  CHECK(c.output.every == 500);
  CHECK(c.output.vtk_every == 100);                    // 1 ms / 1e-5 s
  CHECK_THAT(c.output.picture_every, WithinRel(2e-4, 1e-12));  // 20 steps
  CHECK(dem::read_case(path, {"output.every=\"250\""}).output.every == 250);
  CHECK_THAT(read_error(path.string(), {"output.every=0.015 ms"}),
             Contains("output.every: 1.5e-05 s is 1.5 steps of dt = 1e-05 s; give a whole number of steps"));
  CHECK_THAT(read_error(path.string(), {"output.vtk_every=2 m"}), Contains("output.vtk_every: expected a time"));
  CHECK_THAT(read_error(path.string(), {"output.every=\"2.5\""}), Contains("output.every: expected a whole number of steps, got 2.5"));
  CHECK_THAT(read_error(path.string(), {"output.every=true"}), Contains("output.every: expected a whole number of steps (500) or a time"));
}

TEST_CASE("case file: inputs that would give a silent wrong answer are refused at their line", "[case]") {
  const auto path = std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/basic/free_fall.toml";  // probe 0: y at 0.5 s
  // a value probe before the start (it would be extrapolated)
  CHECK_THAT(read_error(path.string(), {"probe.0.at=-1 ms"}), Contains("probe.0.at: expected a time ≥ 0") && Contains("-0.001 s"));
  CHECK_NOTHROW(dem::read_case(path, {"probe.0.at=0 s"}));
  // the base plate's travel without a base plate (a column of zeros)
  CHECK_THAT(test::message_of<dem::CaseError>([&] { dem::check_outputs(dem::read_case(path, {"output.series=[\"t\", \"plate_travel\"]"})); }),
             Contains("output.series: ") && Contains("plate_travel") && Contains("needs a base plate"));
  const auto silo = std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/silo/static_17_18.toml";
  // an ordered fill beyond 10^6 rows (was capped silently at ~1.15e7 disks)
  CHECK_THAT(read_error(silo.string(), {"arrangement.0.count_near=20000000"}),
             Contains("arrangement.0.count_near") && Contains("needs more than 1000000 rows"));
  CHECK(dem::read_case(silo, {"arrangement.0.count_near=350"}).model.elements.size() == 350);
}

TEST_CASE("case file: the rotated-corner lever is read for a wall law and refused where elements meet (M19.r)", "[case]") {
  const auto path = std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/base_friction/mc_topple_3pre.toml";  // contact 1: PRE–slope
  CHECK(dem::read_case(path).model.laws[1].face.lever == dem::FaceLever::wall_frame);  // the paper's rule by default
  const auto c = dem::read_case(path, {"contact.1.lever=rotated_corner"});
  CHECK(c.model.laws[1].face.lever == dem::FaceLever::rotated_corner);
  CHECK(c.model.laws[0].face.lever == dem::FaceLever::wall_frame);
  // on the PRE–PRE law the lever of one element would be wrong for the other: refused, at the key's line
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  const std::string pair = "between = [\"aluminium\", \"aluminium\"]\n";
  const auto pos = text.find(pair);
  REQUIRE(pos != std::string::npos);
  const int line = 2 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
  text.insert(pos + pair.size(), "lever = \"rotated_corner\"\n");
  const std::string file = test::write_temp("pair_lever.toml", text).string();
  CHECK_THAT(read_error(file), StartsWith(file + ":" + std::to_string(line) + ": contact.0.lever: ") &&
                                   Contains("for walls") && Contains("\"aluminium\" and \"aluminium\" can meet"));
  CHECK_THAT(read_error(path.string(), {"contact.1.lever=corner"}), Contains("contact.1.lever") && Contains("rotated_corner"));
}

TEST_CASE("case file: a radius range of exactly two values - a peak drop strictly inside (0 1) - a mass on every element", "[case]") {
  const std::string arrangement = "\n[[contact]]\nbetween = [\"sand\", \"sand\"]\nkn = \"1e5 N/m\"\n[[arrangement]]\nkind = \"random\"\nmaterial = \"sand\"\nregion = [[\"-0.5 m\", \"0.1 m\"], "
                                  "[\"0.5 m\", \"0.5 m\"]]\ncount = 3\nseed = 1\nradius_range = ";
  const auto range = [&](const std::string& value) {
    return variant("radius_range.toml", "title = \"minimal\"", "title = \"minimal\"", arrangement + value + "\n").path;
  };
  CHECK(dem::read_case(range("[\"0.4 cm\", \"0.6 cm\"]")).model.elements.size() == 4);
  CHECK_THAT(read_error(range("[\"0.4 cm\", \"0.5 cm\", \"0.6 cm\"]")), Contains("arrangement.0.radius_range: expected [min, max]"));
  CHECK_THAT(read_error(range("[\"0.4 cm\"]")), Contains("arrangement.0.radius_range: expected [min, max]"));
  CHECK_THAT(read_error(range("\"0.5 cm\"")), Contains("arrangement.0.radius_range: expected [min, max]"));
  // [stop] after_peak: the fraction of the peak lost, 0 < drop < 1 (0 would stop at the peak itself)
  const auto drop = [&](const std::string& value) {
    return variant("after_peak.toml", "title = \"minimal\"", "title = \"minimal\"",
                   "\n[stop]\nafter_peak = { quantity = \"e0.y\", drop = " + value + " }\n").path;
  };
  CHECK_NOTHROW(dem::read_case(drop("1e-9")));
  CHECK_NOTHROW(dem::read_case(drop("0.999999999")));
  for (const char* bad : {"0", "1", "-0.1"}) {
    CAPTURE(bad);
    CHECK_THAT(read_error(drop(bad)), Contains("stop.after_peak.drop: expected the fraction of the peak lost"));
  }
  // A material without density and an element of it without a mass, listed last: refused by its index.
  const std::string glass = "\n[[material]]\nname = \"glass\"\n[[contact]]\nbetween = [\"glass\", \"sand\"]\nkn = \"1e5 N/m\"\n"
                            "[[contact]]\nbetween = [\"glass\", \"steel\"]\nkn = \"1e5 N/m\"\n"
                            "[[element]]\nmaterial = \"glass\"\nradius = \"1 cm\"\nposition = [\"0.5 m\", \"1 cm\"]\n";
  CHECK_THAT(read_error(variant("massless_last.toml", "title = \"minimal\"", "title = \"minimal\"", glass).path),
             Contains("element 1 has no mass"));
  CHECK_NOTHROW(dem::read_case(variant("massive_last.toml", "title = \"minimal\"", "title = \"minimal\"", glass + "mass = \"0.1 kg\"\n").path));
}

TEST_CASE("case file: a contact's rolling table (R1–R6) is read strictly", "[case][rolling]") {
  struct Bad {
    const char* name;
    const char* rolling;
    const char* key;
    const char* expected;
  };
  const auto bad = GENERATE(
      Bad{"rolling_both.toml", "{ friction = 0.1, stiffness = \"1 N*m/rad\", stiffness_factor = 2.25 }", "contact.0.rolling",
          "give exactly one of stiffness"},
      Bad{"rolling_none.toml", "{ friction = 0.1 }", "contact.0.rolling", "give exactly one of stiffness"},
      Bad{"rolling_unit.toml", "{ friction = 0.1, stiffness = \"1 N*m\" }", "contact.0.rolling.stiffness", "expected"},
      Bad{"rolling_negative.toml", "{ friction = -0.1, stiffness = \"1 N*m/rad\" }", "contact.0.rolling.friction",
          "must not be negative"},
      Bad{"rolling_zero_factor.toml", "{ friction = 0.0, stiffness_factor = 2.25 }", "contact.0.rolling.stiffness_factor",
          "friction = 0"},
      Bad{"rolling_unknown.toml", "{ friction = 0.1, stiffness = \"1 N*m/rad\", damping = 0.1 }", "contact.0.rolling.damping",
          "unknown key"},
      Bad{"rolling_missing.toml", "{ stiffness = \"1 N*m/rad\" }", "contact.0.rolling.friction", "missing"});
  CAPTURE(bad.name);
  const auto v = variant(bad.name, "friction = 0.5", std::string("friction = 0.5\nrolling = ") + bad.rolling);
  const auto msg = read_error(v.path);
  CHECK_THAT(msg, Contains(std::string(bad.key) + ": "));
  CHECK_THAT(msg, Contains(bad.expected));
}

TEST_CASE("case file: rolling resistance in SI: k_r as given or per unit thickness × l, β, ζ_r", "[case][rolling]") {
  auto law_of = [](const std::string& rolling) {
    const auto v = variant("rolling_ok.toml", "friction = 0.5", "friction = 0.5\nrolling = " + rolling);
    return dem::read_case(v.path).model.laws.at(0).rolling;
  };
  const dem::RollingLaw given = law_of("{ friction = 0.1, stiffness = \"2 N*m/rad\", damping_ratio = 0.3 }");
  CHECK(given.enabled);
  CHECK(given.mu_r == 0.1);
  CHECK(given.kr == 2.0);
  CHECK(given.damping_ratio == 0.3);
  const dem::RollingLaw factor = law_of("{ friction = 0.1, stiffness_factor = 2.25 }");
  CHECK(factor.kr == 0.0);
  CHECK(factor.stiffness_factor == 2.25);
  CHECK(factor.damping_ratio == 0.0);
  const auto thick = variant("rolling_thick.toml", "friction = 0.5",
                             "friction = 0.5\nrolling = { friction = 0.1, stiffness = \"2 N/rad\" }");
  const dem::Case c = dem::read_case(thick.path, {"physics.thickness=0.5 m"});
  CHECK(c.model.laws.at(0).rolling.kr == 1.0);  // 2 N/rad per unit thickness × 0.5 m
  CHECK_FALSE(dem::read_case(test::write_temp("no_rolling.toml", minimal_text()).string()).model.laws.at(0).rolling.enabled);
}

TEST_CASE("case file: K19 without damping is refused as having no stable time step, not 'dt <= 0 s'", "[case]") {
  // K19's Hopf bound Δt < η/K is 0 without a dashpot (refs §1.5): no Δt is stable. The message says so and
  // what to do, never "use numerics.dt <= 0 s".
  const auto v = variant("k19_undamped.toml", "damping_ratio = 0.3", "damping_ratio = 0.0");
  const auto msg = test::message_of<dem::CaseError>(
      [&] { dem::check_case(dem::read_case(v.path, {"numerics.integrator=K19"})); });
  CHECK_THAT(msg, Contains("numerics.dt: no time step is stable"));
  CHECK_THAT(msg, Contains("damping ratio") && Contains("K18") && Contains("allow_unstable"));
  CHECK_THAT(msg, !Contains("dt <= 0"));
  // with damping, K19 has a limit and the usual message
  CHECK_NOTHROW(dem::check_case(dem::read_case(v.path, {"numerics.integrator=K19", "contact.0.damping_ratio=0.3"})));
}
