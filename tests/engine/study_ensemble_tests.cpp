// Ensembles of a study (engine/study_ensemble.hpp): the statistics of a probe over the members, the
// verdict on the whole confidence interval, the strict [ensemble] table, and a small ensemble run end
// to end (members that differ only by the jitter seed of an ordered fill).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "dem/cases/case_file.hpp"
#include "engine/study.hpp"
#include "engine/study_ensemble.hpp"
#include "engine/study_file.hpp"
#include "engine/study_run.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

fs::path folder(const std::string& name) {
  static int calls = 0;
  const fs::path dir = fs::temp_directory_path() / "dem2d_unit_ensemble" / (name + std::to_string(::getpid()) + "_" + std::to_string(++calls));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// Twelve disks in rows of 4 and 3 in a 9 cm box, settling for 0.05 s: a case with an ordered fill that an
/// ensemble can jitter. Probe: the x of disk 5 at the end.
std::string small_fill() {
  return "[case]\ntitle = \"ensemble test\"\n[physics]\ngravity = [\"0 m/s^2\", \"-9.80665 m/s^2\"]\n"
         "[[material]]\nname = \"sand\"\ndensity = \"2650 kg/m^3\"\n[[material]]\nname = \"wall\"\n"
         "[[contact]]\nbetween = [\"sand\", \"sand\"]\nlaw = \"linear\"\nkn = \"1e7 N/m\"\nks_ratio = 0.25\n"
         "friction_angle = \"30 deg\"\ndamping_ratio = 0.7\n"
         "[[contact]]\nbetween = [\"sand\", \"wall\"]\nlaw = \"linear\"\nkn = \"2e7 N/m\"\nks_ratio = 0.25\n"
         "friction_angle = \"10 deg\"\ndamping_ratio = 0.7\n"
         "[[arrangement]]\nkind = \"ordered\"\nmaterial = \"sand\"\nradius = \"1 cm\"\ns = 4\nrows = 3\n"
         "left = \"0 cm\"\nright = \"9 cm\"\nfloor = \"0 cm\"\ngap = \"0.01 cm\"\n"
         "[[wall]]\nname = \"left\"\nfrom = [\"0 cm\", \"0 cm\"]\nto = [\"0 cm\", \"20 cm\"]\nmaterial = \"wall\"\n"
         "[[wall]]\nname = \"right\"\nfrom = [\"9 cm\", \"0 cm\"]\nto = [\"9 cm\", \"20 cm\"]\nmaterial = \"wall\"\n"
         "[[wall]]\nname = \"bottom\"\nfrom = [\"0 cm\", \"0 cm\"]\nto = [\"9 cm\", \"0 cm\"]\nmaterial = \"wall\"\n"
         "[numerics]\nintegrator = \"K19\"\ndt = \"2e-5 s\"\nduration = \"0.05 s\"\n"
         "[output]\nseries = [\"t\"]\nevery = 100\nvtk_every = 0\n"
         "[[probe]]\nname = \"x5\"\nquantity = \"e5.x\"\n";
}

std::string ensemble_study(const fs::path& case_file, const std::string& ensemble, const std::string& check) {
  return "[study]\ntitle = \"ensemble\"\ncase = \"" + case_file.string() + "\"\nkind = \"single\"\n" + ensemble +
         "[[check]]\nprobe = \"x5\"\nlabel = \"x of disk 5\"\n" + check +
         "reason = \"test\"\n";
}

const std::string kEnsemble = "[ensemble]\nmembers = 4\nseed = \"arrangement.0.seed\"\nset = [\"arrangement.0.jitter=1e-4 cm\"]\n";

}  // namespace

TEST_CASE("ensemble statistics: mean and sample sd and the Student-t interval of the mean") {
  // values 1 … 8: mean 4.5, sd = sqrt(6) (sample), t_{0.975, 7} = 2.364624
  std::vector<std::optional<double>> v;
  for (int k = 1; k <= 8; ++k) v.push_back(double(k));
  const ver::EnsembleStat st = ver::ensemble_stat(v, 0.95);
  REQUIRE(st.n == 8);
  CHECK(*st.mean == Approx(4.5).epsilon(1e-15));
  CHECK(*st.sd == Approx(std::sqrt(6.0)).epsilon(1e-14));
  CHECK(ver::student_t_quantile(0.975, 7.0) == Approx(2.364624252).epsilon(1e-8));
  CHECK(*st.half_width == Approx(2.364624252 * std::sqrt(6.0) / std::sqrt(8.0)).epsilon(1e-8));
  // a missing member is counted, not averaged; one value: a mean without an interval
  v.push_back(std::nullopt);
  CHECK(ver::ensemble_stat(v, 0.95).members == 9);
  CHECK(ver::ensemble_stat(v, 0.95).n == 8);
  const ver::EnsembleStat one = ver::ensemble_stat({2.0, std::nullopt}, 0.95);
  CHECK(*one.mean == 2.0);
  CHECK_FALSE(one.half_width.has_value());
  CHECK_FALSE(ver::ensemble_stat({std::nullopt}, 0.95).mean.has_value());
}

TEST_CASE("ensemble verdict: the whole interval must satisfy the check") {
  ver::Check c;
  c.tolerance = 1.0;
  c.expect = ver::Expect::within;
  CHECK(ver::interval_passes(c, 10.0, 9.2, 10.8));
  CHECK_FALSE(ver::interval_passes(c, 10.0, 9.2, 11.2));  // the mean 10.2 is within, the interval is not
  c.expect = ver::Expect::above;
  CHECK(ver::interval_passes(c, 10.0, 11.01, 12.0));
  CHECK_FALSE(ver::interval_passes(c, 10.0, 10.9, 14.0));
  c.expect = ver::Expect::below;
  CHECK(ver::interval_passes(c, 10.0, 5.0, 8.99));
  CHECK_FALSE(ver::interval_passes(c, 10.0, 5.0, 9.01));
  // relative: the margin is a fraction of |reference| (below 0.7 of 10: upper end < 7)
  c.relative = true;
  c.tolerance = 0.3;
  CHECK(ver::interval_passes(c, 10.0, 5.0, 6.99));
  CHECK_FALSE(ver::interval_passes(c, 10.0, 5.0, 7.01));
}

TEST_CASE("ensemble table: refused with file:line for a study of another kind and for bad keys") {
  const fs::path dir = folder("reader");
  std::ofstream(dir / "case.toml") << small_fill();
  auto refused = [&](const std::string& ensemble, const std::string& kind, const std::string& what) {
    std::string text = ensemble_study(dir / "case.toml", ensemble, "value = 0.0\ntolerance = 1.0\n");
    if (!kind.empty()) text.replace(text.find("kind = \"single\""), 15, "kind = \"" + kind + "\"");
    std::ofstream(dir / "study.toml") << text;
    REQUIRE_THROWS_WITH(ver::read_study(dir / "study.toml"), Contains(what));
  };
  refused("[ensemble]\nmembers = 1\nseed = \"arrangement.0.seed\"\n", "", "study.toml:6: ensemble.members");
  refused("[ensemble]\nmembers = 4\nseed = \"arrangement.0.seed=3\"\n", "", "ensemble.seed");
  refused("[ensemble]\nmembers = 4\nseeds = \"arrangement.0.seed\"\n", "", "a misspelling of 'seed'");
  refused("[ensemble]\nmembers = 4\nseed = \"arrangement.0.seed\"\nconfidence = 1.5\n", "", "ensemble.confidence");
  refused(kEnsemble, "stability", "ensemble");
  // a seed without the jitter it places is refused by the case reader, at the [ensemble] line
  refused("[ensemble]\nmembers = 4\nseed = \"arrangement.0.seed\"\n", "", "study.toml:5: ensemble:");
}

TEST_CASE("ensemble run: members differ by the jitter seed, checks judge the interval, members.csv lists them") {
  const fs::path dir = folder("run");
  std::ofstream(dir / "case.toml") << small_fill();
  // disk 5 (second row, middle disk) sits near x = 4.5 cm: a tolerance of 1 mm holds, 1e-12 m cannot
  std::ofstream(dir / "study.toml") << ensemble_study(dir / "case.toml", kEnsemble,
                                                      "value = \"4.5 cm\"\nerror = \"abs\"\ntolerance = \"1 mm\"\n");
  ver::StudyOptions opt;
  opt.out_dir = dir / "out";
  opt.print = false;
  opt.jobs = 1;
  const ver::StudyResult r = ver::run_study(dir / "study.toml", opt);
  const nlohmann::json& row = r.json["checks"][0];
  CHECK(row["members"] == 4);
  REQUIRE(row["ci_low"].is_number());
  CHECK(row["ci_low"].get<double>() < row["ci_high"].get<double>());  // the members differ
  CHECK_THAT(row["note"].get<std::string>(), Contains("95 % CI"));
  CHECK(r.passed);
  CHECK(r.json["ensemble"]["members"] == 4);
  // members.csv: a header naming each probe once, then one row per member
  std::ifstream csv(dir / "out" / "members.csv");
  std::string header, line;
  std::getline(csv, header);
  CHECK(header == "variant,member,status,x5");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == 4);
}
