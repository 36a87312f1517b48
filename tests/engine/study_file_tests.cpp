// The strict readers of study and sensitivity files: every mistake a user makes in the acceptance
// machinery is refused before anything runs, as file:line: key: what was expected — planted one at a
// time into a study file that reads (and a sensitivity file whose mistakes stop it before any run).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "dem/cases/case_file.hpp"
#include "engine/sensitivity.hpp"
#include "engine/study.hpp"
#include "engine/study_file.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;

namespace {

const std::string kFreeFall = std::string(DEM2D_SOURCE_DIR) + "/cases/basic/free_fall.toml";

/// Writes `text` to a fresh folder of its own (tests run in parallel).
fs::path write(const std::string& folder, const std::string& name, const std::string& text) {
  static int calls = 0;
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_study_file" / (folder + std::to_string(::getpid()) + "_" + std::to_string(++calls));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

/// A study that reads: two variants, a check against the free-fall parabola, a figure and a table.
/// `planted` replaces `from` (the mistake), so that each test differs from a good file in one place.
std::string good_study() {
  return "[study]\n"                                         // line 1
         "title = \"strict reader\"\n"                       // 2
         "case = \"" + kFreeFall + "\"\n"                    // 3
         "kind = \"single\"\n"                               // 4
         "\n"                                                // 5
         "[[variant]]\n"                                     // 6
         "label = \"z0.3\"\n"                                // 7
         "set = [\"numerics.dt=1e-4\"]\n"                    // 8
         "args = { x0 = 2.0, v0 = 1.0, g = -9.80665, t = 0.5 }\n"  // 9
         "\n"                                                // 10
         "[[variant]]\n"                                     // 11
         "label = \"z0.5\"\n"                                // 12
         "set = [\"numerics.dt=5e-5\"]\n"                    // 13
         "args = { x0 = 2.0, v0 = 1.0, g = -9.80665, t = 0.5 }\n"  // 14
         "\n"                                                // 15
         "[[check]]\n"                                       // 16
         "probe = \"y_end\"\n"                               // 17
         "reference = \"free_fall.position\"\n"              // 18
         "variants = [\"z0.3\"]\n"                           // 19
         "tolerance = 1e-3\n"                                // 20
         "expect = \"within\"\n"                             // 21
         "error = \"abs\"\n"                                 // 22
         "reason = \"K18 staggered is exact for a parabola\"\n"  // 23
         "\n"                                                // 24
         "[[figure]]\n"                                      // 25
         "id = \"height\"\n"                                 // 26
         "y = \"e0.y\"\n"                                    // 27
         "variants = [\"z0.5\"]\n"                           // 28
         "\n"                                                // 29
         "[[table]]\n"                                       // 30
         "probe = \"y_end\"\n";                              // 31
}

std::string planted(const std::string& from, const std::string& to) {
  std::string s = good_study();
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

/// `message` with every occurrence of the path `f` replaced by the file's name.
std::string named(std::string message, const fs::path& f) {
  for (auto at = message.find(f.string()); at != std::string::npos; at = message.find(f.string()))
    message.replace(at, f.string().size(), f.filename().string());
  return message;
}

/// The message of the refusal of `text` (fails the test if it reads), the file named "study.toml".
std::string refusal(const std::string& text) {
  const fs::path f = write("study", "study.toml", text);
  try {
    (void)ver::read_study(f);
  } catch (const dem::CaseError& e) {
    return named(e.what(), f);
  }
  FAIL("the study file was accepted:\n" << text);
  return "";
}

std::string at_line(int line) { return "study.toml:" + std::to_string(line) + ": "; }

}  // namespace

TEST_CASE("A good study file reads, with every value as written", "[study_file]") {
  const fs::path f = write("study", "study.toml", good_study());
  const ver::Study s = ver::read_study(f);
  REQUIRE(s.variants.size() == 2);
  REQUIRE(s.checks.size() == 1);
  CHECK(s.checks[0].tolerance == 1e-3);
  CHECK_FALSE(s.checks[0].relative);
  CHECK(s.checks[0].expect == ver::Expect::within);
  CHECK(s.checks[0].only == std::vector<std::string>{"z0.3"});
  CHECK(s.checks[0].line == 16);
  CHECK(s.figures.size() == 1);
  CHECK(s.tables.size() == 1);
  CHECK(s.case_file == fs::path(kFreeFall).lexically_normal());
}

TEST_CASE("Misspelled words and keys of a check are refused, with the nearest right one", "[study_file]") {
  CHECK_THAT(refusal(planted("expect = \"within\"", "expect = \"abvoe\"")),
             StartsWith(at_line(21) + "check.expect: expected one of \"within\", \"above\", \"below\", got \"abvoe\"; did you mean \"above\"?"));
  CHECK_THAT(refusal(planted("error = \"abs\"", "error = \"relative\"")),
             StartsWith(at_line(22) + "check.error: expected one of \"abs\", \"rel\", got \"relative\""));
  CHECK_THAT(refusal(planted("expect = \"within\"", "expect_order = 7.0")),
             StartsWith(at_line(21) + "check.expect_order: unknown key; did you mean 'expected_order'?"));
  CHECK_THAT(refusal(planted("tolerance = 1e-3", "tolerence = 1e-3")),
             StartsWith(at_line(16) + "check.tolerance: check \"y_end\": missing tolerance (is 'tolerence', line 20, a misspelling of 'tolerance'?)"));
  CHECK_THAT(refusal(planted("[[check]]", "[[chek]]")), Contains("check: missing: at least one [[check]]") && Contains("(is 'chek', line 16, a misspelling of 'check'?)"));
  CHECK_THAT(refusal(good_study() + "\n[[figur]]\ny = \"e0.y\"\n"), Contains("figur: unknown key; did you mean 'figure'?"));
  CHECK_THAT(refusal(planted("label = \"z0.5\"", "label = \"z0.5\"\nsett = []")), Contains("variant.sett: unknown key; did you mean 'set'?"));
  CHECK_THAT(refusal(planted("kind = \"single\"", "kind = \"singel\"")), Contains("did you mean \"single\"?"));
}

TEST_CASE("A tolerance or value that can never fail or never pass is refused", "[study_file]") {
  CHECK_THAT(refusal(planted("tolerance = 1e-3", "tolerance = inf")), StartsWith(at_line(20) + "check.tolerance: expected a finite number"));
  CHECK_THAT(refusal(planted("tolerance = 1e-3", "tolerance = nan")), StartsWith(at_line(20) + "check.tolerance: expected a finite number"));
  CHECK_THAT(refusal(planted("tolerance = 1e-3", "tolerance = -1")), StartsWith(at_line(20) + "check.tolerance: expected a finite tolerance ≥ 0 for |error| ≤ tolerance"));
  // A margin below an `above` check may be negative (dem > reference − 1e-3): it can pass.
  std::string above = planted("tolerance = 1e-3", "tolerance = -1e-3");
  above.replace(above.find("expect = \"within\""), 17, "expect = \"above\"");
  CHECK_NOTHROW(ver::read_study(write("study", "study.toml", above)));
  CHECK_THAT(refusal(planted("reference = \"free_fall.position\"", "value = nan")), StartsWith(at_line(18) + "check.value: expected a finite number"));
  CHECK_THAT(refusal(planted("tolerance = 1e-3", "tolerance = \"1e-3 frobs\"")), StartsWith(at_line(20) + "check.tolerance:"));
}

TEST_CASE("A check or figure that names no variant, and twin variant labels, are refused", "[study_file]") {
  CHECK_THAT(refusal(planted("variants = [\"z0.3\"]", "variants = [\"z=0.3\"]")),
             StartsWith(at_line(16) + "check.variants: \"z=0.3\" names no variant; did you mean \"z0.3\"?"));
  CHECK_THAT(refusal(planted("variants = [\"z0.5\"]", "variants = [\"z5\"]")), StartsWith(at_line(25) + "figure.variants: \"z5\" names no variant"));
  CHECK_THAT(refusal(planted("label = \"z0.5\"", "label = \"z0.3\"")),
             StartsWith(at_line(12) + "variant.label: \"z0.3\" is the label of an earlier variant"));
  CHECK_THAT(refusal(planted("[[check]]\nprobe", "[[checks]]\nprobe")), Contains("missing: at least one [[check]]"));
}

TEST_CASE("Reference solvers, their arguments and the probes are checked before anything runs", "[study_file]") {
  CHECK_THAT(refusal(planted("\"free_fall.position\"", "\"free_fall.positon\"")),
             StartsWith(at_line(18) + "check.reference: unknown reference solver \"free_fall.positon\"; did you mean \"free_fall.position\"?"));
  CHECK_THAT(refusal(planted("args = { x0 = 2.0, v0 = 1.0, g = -9.80665, t = 0.5 }\n\n[[variant]]", "args = { x0 = 2.0, g = -9.80665, t = 0.5 }\n\n[[variant]]")),
             StartsWith(at_line(16) + "check.args: check \"y_end\" for variant \"z0.3\": the reference free_fall.position needs v0"));
  CHECK_THAT(refusal(planted("probe = \"y_end\"\nreference", "probe = \"y_ned\"\nreference")),
             StartsWith(at_line(17) + "check.probe: the case " + kFreeFall + " has no probe \"y_ned\"; did you mean \"y_end\"?"));
  CHECK_THAT(refusal(planted("reference = \"free_fall.position\"", "value = \"1.27 s\"")),
             StartsWith(at_line(18) + "check.value: the probe \"y_end\" is in m, the value is"));
  // a wrong override names its line in the study file first, then what the case reader says of it
  CHECK_THAT(refusal(planted("set = [\"numerics.dt=1e-4\"]", "set = [\"numerics.dtt=1e-4\"]")),
             StartsWith(at_line(8) + "set: variant \"z0.3\": --set numerics.dtt=1e-4: numerics.dtt: unknown key"));
  CHECK_THAT(refusal(planted("set = [\"numerics.dt=5e-5\"]", "set = [\"numerics.dt=1e-4\", \"numerics.dt=5 kg\"]")),
             StartsWith(at_line(13) + "set: variant \"z0.5\": --set numerics.dt=5 kg: numerics.dt: expected a time"));
  CHECK_THAT(refusal(planted("kind = \"single\"", "kind = \"single\"\nset = [\"numerics.skin=abc\"]")),
             StartsWith(at_line(5) + "set: variant \"z0.3\": --set numerics.skin=abc: numerics.skin:"));
}

TEST_CASE("Kind-specific tables: refinement order, mode map blocks, bisection tolerance", "[study_file]") {
  const std::string fine_to_coarse = planted("kind = \"single\"", "kind = \"refinement\"") +
                                     "\n[refinement]\nparameter = \"numerics.dt\"\nvalues = [1e-5, 2e-5, 4e-5]\n";
  CHECK_THAT(refusal(fine_to_coarse), Contains("refinement.values: expected the levels from coarse to fine"));
  CHECK_THAT(refusal(planted("kind = \"single\"", "kind = \"refinement\"")),
             StartsWith(at_line(4) + "study.kind: kind = \"refinement\" needs a [refinement] table (or [[level]] tables)"));
  CHECK_THAT(refusal(planted("kind = \"single\"", "kind = \"refinement\"") + "\n[refinement]\nparameter = \"numerics.dt\"\nvalues = [4e-5, 2e-5]\nvalue = 3\n"),
             Contains("refinement.value: unknown key; did you mean 'values'?"));
  const std::string map = "[study]\ncase = \"" + kFreeFall + "\"\nkind = \"mode_map\"\n[mode_map]\nblocks = [[\"a\", \"b\"]]\n"
                          "phis_deg = [30]\nalphas_deg = [20]\nradius = 0.01\n[[check]]\ntolerance = 0\nvalue = 0\nreason = \"r\"\n";
  CHECK_THAT(refusal(map), StartsWith(at_line(5) + "mode_map.blocks: expected [columns, rows]: two whole numbers"));
  const std::string bisect = "[study]\ncase = \"" + kFreeFall + "\"\nkind = \"stability\"\n[stability]\nlow = 1e-5\nhigh = 1e-3\n"
                             "rel_tol = 0\n[[check]]\nreference = \"free_fall.position\"\nargs = { x0 = 0, v0 = 0, g = 0, t = 0 }\n"
                             "tolerance = 0.1\nreason = \"r\"\n";
  CHECK_THAT(refusal(bisect), StartsWith(at_line(7) + "stability.rel_tol: expected a number in"));
  std::string bisect_set = bisect;
  bisect_set.replace(bisect_set.find("rel_tol = 0\n"), 12, "rel_tol = 1e-4\n[[variant]]\nlabel = \"v\"\nset = [\"numerics.dtt=1\"]\n");
  CHECK_THAT(refusal(bisect_set), StartsWith(at_line(10) + "set: variant \"v\": --set numerics.dtt=1: numerics.dtt: unknown key"));
  CHECK_THAT(refusal(good_study() + "\n[stability]\nlow = 1\nhigh = 2\n"), Contains("stability: a [stability] table needs kind = \"stability\""));
}

TEST_CASE("A mode map's overrides are read with the study file and refused at their line", "[study_file]") {
  const std::string block_mode = std::string(DEM2D_SOURCE_DIR) + "/cases/pre/block_mode.toml";
  const std::string map = "[study]\n"                                    // 1
                          "case = \"" + block_mode + "\"\n"              // 2
                          "kind = \"mode_map\"\n"                        // 3
                          "set = [\"numerics.duration=0.01\"]\n"         // 4
                          "[mode_map]\n"                                 // 5
                          "blocks = [[2, 1], [1, 3]]\n"                  // 6
                          "phis_deg = [30]\n"                            // 7
                          "alphas_deg = [20]\n"                          // 8
                          "radius = 0.0125\n"                            // 9
                          "wall_contact = 1\n"                           // 10
                          "[[check]]\nvalue = 0.0\ntolerance = 0.0\nreason = \"a mode is discrete\"\n";
  const fs::path f = write("mode_map", "study.toml", map);
  CHECK(ver::read_study(f).blocks.size() == 2);
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = map;
    REQUIRE(t.find(from) != std::string::npos);
    return t.replace(t.find(from), from.size(), to);
  };
  // the study's own override: its line in [study] set
  CHECK_THAT(refusal(with("numerics.duration=0.01", "numerics.durtion=0.01")),
             StartsWith(at_line(4) + "set: --set numerics.durtion=0.01: numerics.durtion: unknown key"));
  // the mode map's own overrides: a contact the case does not have, a lattice it cannot make
  CHECK_THAT(refusal(with("wall_contact = 1", "wall_contact = 7")),
             StartsWith(at_line(10) + "mode_map.wall_contact: the case ") && Contains("block 2x1") && Contains("contact.7"));
  CHECK_THAT(refusal(with("case = \"" + block_mode, "case = \"" + kFreeFall)),
             StartsWith(at_line(8) + "mode_map.alphas_deg: the case ") && Contains("physics.gravity.direction"));
  const std::string no_lattice = std::string(DEM2D_SOURCE_DIR) + "/cases/pre/block_on_slope.toml";  // one contact, no [[lattice]]
  CHECK_THAT(refusal(with("wall_contact = 1", "wall_contact = 0").replace(map.find(block_mode), block_mode.size(), no_lattice)),
             StartsWith(at_line(6) + "mode_map.blocks: the case ") && Contains("lattice"));
  // block = "rolling_disk": the case needs a disk element 0 and a rolling law on the wall contact
  const std::string rolling = std::string(DEM2D_SOURCE_DIR) + "/cases/basic/rolling_mode.toml";
  const std::string disk_map = with("wall_contact = 1", "wall_contact = 0\nblock = \"rolling_disk\"").replace(map.find(block_mode), block_mode.size(), rolling);
  CHECK(ver::read_study(write("mode_map_disk", "study.toml", disk_map)).mode_block == ver::Study::ModeBlock::rolling_disk);
  const std::string no_rolling = std::string(DEM2D_SOURCE_DIR) + "/cases/basic/disk_on_slope.toml";  // a disk, no rolling law
  std::string unrolled = disk_map;
  unrolled.replace(unrolled.find(rolling), rolling.size(), no_rolling);
  CHECK_THAT(refusal(unrolled), StartsWith(at_line(10) + "mode_map.wall_contact: the case ") && Contains("contact.0.rolling"));
  CHECK_THAT(refusal(with("wall_contact = 1", "wall_contact = 1\nblock = \"disk\"")),
             StartsWith(at_line(11) + "mode_map.block: expected one of"));
  // variants are not what a mode map runs
  CHECK_THAT(refusal(map + "[[variant]]\nlabel = \"v\"\nset = [\"numerics.dt=1e-6\"]\n"),
             StartsWith(at_line(15) + "variant: a mode map runs its grid"));
}

TEST_CASE("The case path is taken relative to the study file, and a missing case is named with its line", "[study_file]") {
  const fs::path root = fs::temp_directory_path() / "dem2d_unit_study_file" / "relative";
  fs::remove_all(root);
  fs::create_directories(root / "cases");
  fs::create_directories(root / "studies" / "a");
  fs::copy_file(kFreeFall, root / "cases" / "free_fall.toml");
  std::string text = good_study();
  text.replace(text.find(kFreeFall), kFreeFall.size(), "../../cases/free_fall.toml");
  std::ofstream(root / "studies" / "a" / "study.toml") << text;
  const ver::Study s = ver::read_study(root / "studies" / "a" / "study.toml");
  CHECK(s.case_file == (root / "cases" / "free_fall.toml").lexically_normal());
  text.replace(text.find("../../cases/free_fall.toml"), 26, "../cases/free_fall.toml");
  std::ofstream(root / "studies" / "a" / "study.toml") << text;
  try {
    (void)ver::read_study(root / "studies" / "a" / "study.toml");
    FAIL("a missing case was accepted");
  } catch (const dem::CaseError& e) {
    CHECK_THAT(e.what(), Equals("file not found: " + (root / "studies" / "cases" / "free_fall.toml").string() + " (from " +
                                (root / "studies" / "a" / "study.toml").string() + ":3)"));
  }
}

namespace {

std::string sens_refusal(const std::string& text) {
  const fs::path f = write("sweep", "sensitivity.toml", text);
  ver::StudyOptions o;
  o.out_dir = f.parent_path() / "out";
  o.print = false;
  try {
    (void)ver::run_sensitivity(f, o);
  } catch (const dem::CaseError& e) {
    CHECK_FALSE(fs::exists(o.out_dir / "result.json"));
    CHECK_FALSE(fs::exists(o.out_dir / "cache"));  // refused before the first run
    return named(e.what(), f);
  }
  FAIL("the sensitivity file was accepted:\n" << text);
  return "";
}

const std::string kRest = std::string(DEM2D_SOURCE_DIR) + "/cases/basic/rest_on_wall.toml";

std::string good_sweep() {
  return "[sensitivity]\ntitle = \"strict\"\ncase = \"" + kRest + "\"\noutputs = [\"overlap\"]\nmethods = [\"sobol\"]\n"  // 1-5
         "[[parameter]]\npath = \"contact.0.damping_ratio\"\nlow = 0.1\nhigh = 0.9\n"  // 6-9
         "[[parameter]]\npath = \"contact.0.kn\"\nlow = \"5e5 N/m\"\nhigh = \"4e6 N/m\"\n"  // 10-13
         "[sobol]\nsamples = 16\nbootstrap = 20\n";  // 14-16
}

std::string sweep_planted(const std::string& from, const std::string& to) {
  std::string s = good_sweep();
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

std::string sweep_line(int line) { return "sensitivity.toml:" + std::to_string(line) + ": "; }

}  // namespace

TEST_CASE("Mistakes in a sensitivity file are refused before any run", "[study_file]") {
  CHECK_THAT(sens_refusal(sweep_planted("samples = 16", "sample = 16")), StartsWith(sweep_line(15) + "sobol.sample: unknown key; did you mean 'samples'?"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1", "low = \"1 m\"")),
             StartsWith(sweep_line(9) + "parameter.high: low is"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "low = \"0.1 m\"\nhigh = \"0.9 m\"")),
             StartsWith(sweep_line(8) + "parameter.low: \"0.1 m\" cannot set contact.0.damping_ratio"));
  // Distributions (issue 36): each takes its own keys, with units that agree, read strictly.
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "distribution = \"normal\"\nmean = 0.5")),
             Contains("parameter.sd: missing: a normal distribution takes mean, sd"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "distribution = \"normal\"\nmean = 0.5\nsd = 0.1\nhigh = 0.9")),
             Contains("parameter.high: a normal distribution does not take high"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "distribution = \"triangular\"\nlow = 0.1\nmode = 0.95\nhigh = 0.9")),
             Contains("parameter.mode: expected low <= mode <= high"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "distribution = \"levels\"\nlevels = [0.5, 0.2]")),
             Contains("parameter.levels: expected increasing values"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "distribution = \"log-normal\"\nmedian = 0.5")),
             Contains("sigma_ln"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "distribution = \"levels\"\nlevels = [0.2, \"0.5 m\"]")),
             Contains("give all in one kind of unit"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "distribution = \"gauss\"\nlow = 0.1\nhigh = 0.9")),
             Contains("parameter.distribution"));
  // a key of another distribution: levels on a uniform one, low on levels (each refused by name)
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "low = 0.1\nhigh = 0.9\nlevels = [0.2, 0.5]")),
             Contains("parameter.levels: a uniform distribution does not take levels"));
  CHECK_THAT(sens_refusal(sweep_planted("low = 0.1\nhigh = 0.9", "distribution = \"levels\"\nlevels = [0.2, 0.5]\nlow = 0.1")),
             Contains("parameter.low: a levels distribution does not take low"));
  CHECK_THAT(sens_refusal(sweep_planted("samples = 16", "samples = 16\nsecond_order_tolerance = 0.05")),
             Contains("second_order_tolerance: needs second_order = true"));
  CHECK_THAT(sens_refusal(sweep_planted("methods = [\"sobol\"]", "methods = [\"sobl\"]")), Contains("did you mean \"sobol\"?"));
  CHECK_THAT(sens_refusal(sweep_planted("methods = [\"sobol\"]", "methods = [\"oat\"]")), Contains("sobol: [sobol] is given but methods does not list \"sobol\""));
  CHECK_THAT(sens_refusal(sweep_planted("samples = 16", "samples = 1099511627776")), StartsWith(sweep_line(15) + "sobol.samples: expected a whole number from 1 to 16777216"));
  CHECK_THAT(sens_refusal(sweep_planted("outputs = [\"overlap\"]", "outputs = [\"overlpa\"]")),
             StartsWith(sweep_line(4) + "sensitivity.outputs: the case has no probe \"overlpa\"; did you mean \"overlap\"?"));
  CHECK_THAT(sens_refusal(good_sweep() + "confidance = 0.9\n"), Contains("sobol.confidance: unknown key; did you mean 'confidence'?"));
  CHECK_THAT(sens_refusal(sweep_planted("path = \"contact.0.kn\"", "path = \"contact.0.kn\"\ndistribution = \"loguniform\"")),
             Contains("did you mean \"log-uniform\"?"));
}

TEST_CASE("The noise and delta keys of a sensitivity file are read strictly", "[study_file]") {
  // Issue 36: noise_sd / noise_seed and a replicate count belong to a test function; the tolerances
  // need their reason; delta_tolerance needs delta = true and the Ishigami function.
  CHECK_THAT(sens_refusal(sweep_planted("methods = [\"sobol\"]", "methods = [\"sobol\"]\nnoise_sd = 0.1")),
             StartsWith(sweep_line(6) + "sensitivity.noise_sd: only for a test function"));
  CHECK_THAT(sens_refusal(sweep_planted("samples = 16", "samples = 16\ntolerance = 0.05")),
             Contains("sobol.tolerance: only for a test function"));
  CHECK_THAT(sens_refusal(sweep_planted("samples = 16", "samples = 16\ndelta_bootstrap = 10")), Contains("sobol.delta_bootstrap: needs delta = true"));
  CHECK_THAT(sens_refusal(sweep_planted("samples = 16", "samples = 16\ndelta = true\ndelta_tolerance = 0.05\ndelta_reason = \"x\"")),
             Contains("sobol.delta_tolerance: only with delta = true for the Ishigami function"));
  CHECK_THAT(sens_refusal(sweep_planted("samples = 16", "samples = 16\ndelta_reason = \"x\"")), Contains("sobol.delta_reason: belongs to delta_tolerance"));
  const std::string fn = "[sensitivity]\nfunction = \"ishigami\"\ncoefficients = [7.0, 0.1]\nmethods = [\"sobol\"]\n"  // 1-4
                         "[[parameter]]\nlow = -3.0\nhigh = 3.0\n[[parameter]]\nlow = -3.0\nhigh = 3.0\n[[parameter]]\nlow = -3.0\nhigh = 3.0\n"
                         "[sobol]\nsamples = 16\nbootstrap = 20\n";
  auto planted = [&](const std::string& from, const std::string& to) {
    std::string s = fn;
    return s.replace(s.find(from), from.size(), to);
  };
  CHECK_THAT(sens_refusal(planted("methods", "replicates = 3\nmethods")), Contains("sensitivity.replicates: a test function has no noise unless noise_sd is given"));
  CHECK_THAT(sens_refusal(planted("methods", "replicates = 1\nnoise_sd = 1.0\nmethods")), Contains("sensitivity.replicates"));
  CHECK_THAT(sens_refusal(planted("methods", "noise_sd = -1.0\nmethods")), Contains("sensitivity.noise_sd"));
  CHECK_THAT(sens_refusal(planted("bootstrap = 20", "bootstrap = 20\ntolerance = 0.05")), Contains("sobol.tolerance_reason: missing"));
  // the convergence sample sizes are kept and checked in order
  CHECK_THAT(sens_refusal(planted("bootstrap = 20", "bootstrap = 20\nconvergence = [16, 8]")),
             Contains("sobol.convergence: expected increasing sample sizes"));
}

TEST_CASE("A refinement study reads its label and the levels a check fits, and refuses a level it lacks", "[study_file]") {
  // three levels, coarse to fine; the check fits the two finest (indices 1 and 2)
  const std::string refinement = planted("kind = \"single\"", "kind = \"refinement\"") +
                                 "\n[refinement]\nparameter = \"numerics.dt\"\nlabel = \"time step [s]\"\nvalues = [4e-5, 2e-5, 1e-5]\n";
  auto with_fit = [&](const std::string& levels) {
    std::string s = refinement;
    const std::string at = "reason = \"K18 staggered is exact for a parabola\"\n";
    return s.replace(s.find(at), at.size(), at + "fit_levels = " + levels + "\n");
  };
  const ver::Study s = ver::read_study(write("refinement", "study.toml", with_fit("[1, 2]")));
  CHECK(s.parameter == "numerics.dt");
  CHECK(s.parameter_label == "time step [s]");
  REQUIRE(s.checks.size() == 1);
  CHECK(s.checks[0].fit_levels == std::vector<std::size_t>{1, 2});
  CHECK_THAT(refusal(with_fit("[0, 3]")), Contains("check.fit_levels: expected level indices from 0 to 2"));
}
