// The silo measures of issue 33: the largest single-contact force in a wall band (<wall>.fn_max), the
// mean velocity in a box (box.vx|vy), ratio probes, and the jitter of an ordered fill (an ensemble's
// members) — each against a case whose answer is known by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "dem/cases/case_file.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

/// Two disks at rest on a floor (radii 1 cm and 2 cm, 1000 kg/m³, 1 m thick) and a third one falling
/// freely far above, away from every wall; 0.2 s, heavily damped, so the two resting disks have settled.
std::string resting_and_falling(const std::string& extra_probes) {
  return "[case]\ntitle = \"silo measures\"\n[physics]\ngravity = [0.0, -9.81]\n"
         "[[material]]\nname = \"d\"\ndensity = 1000.0\n[[material]]\nname = \"w\"\n"
         "[[contact]]\nbetween = [\"d\", \"w\"]\nkn = 1e6\ndamping_ratio = 1.0\n"
         "[[contact]]\nbetween = [\"d\", \"d\"]\nkn = 1e6\ndamping_ratio = 1.0\n"
         "[[element]]\nmaterial = \"d\"\nradius = 0.01\nposition = [0.0, 0.01]\n"
         "[[element]]\nmaterial = \"d\"\nradius = 0.02\nposition = [0.5, 0.02]\n"
         "[[element]]\nmaterial = \"d\"\nradius = 0.01\nposition = [5.0, 10.0]\n"
         "[[wall]]\nname = \"floor\"\nfrom = [-1.0, 0.0]\nto = [1.0, 0.0]\nmaterial = \"w\"\n"
         "[numerics]\ndt = 1e-5\nduration = 0.2\n[output]\nseries = [\"t\"]\nevery = 1000\nvtk_every = 0\n"
         "[[probe]]\nname = \"max_all\"\nquantity = \"floor.fn_max(0,2)\"\n"
         "[[probe]]\nname = \"max_left\"\nquantity = \"floor.fn_max(0,1.25)\"\n"
         "[[probe]]\nname = \"sum_all\"\nquantity = \"floor.fn(0,2)\"\n"
         "[[probe]]\nname = \"max_none\"\nquantity = \"floor.fn_max(1.9,2)\"\n"
         "[[probe]]\nname = \"vy_falling\"\nquantity = \"box.vy(4,6,-100,100)\"\n"
         "[[probe]]\nname = \"vy_resting\"\nquantity = \"box.vy(-1,1,-1,1)\"\n"
         "[[probe]]\nname = \"vy_empty\"\nquantity = \"box.vy(20,21,0,1)\"\n"
         "[[probe]]\nname = \"share\"\nkind = \"ratio\"\nof = \"max_left\"\nover = \"max_all\"\n" + extra_probes;
}

fs::path write_case(const std::string& name, const std::string& text) {
  const fs::path dir = test::fresh_dir("dem2d_unit_silo_measures", name);
  fs::create_directories(dir);
  std::ofstream(dir / "case.toml") << text;
  return dir / "case.toml";
}

}  // namespace

TEST_CASE("fn_max is the largest single contact in the band, box.vy the mean velocity in the box, ratio a quotient", "[run]") {
  const fs::path file = write_case("measures", resting_and_falling(""));
  dem::RunOptions o;
  const dem::RunResult r = dem::run_case(dem::read_case(file, {}), o);
  const double w1 = 1000.0 * M_PI * 0.01 * 0.01 * 9.81, w2 = 4.0 * w1;  // weights per metre [N]
  CHECK(*r.probes.at("max_all") == Approx(w2).epsilon(1e-6));    // the heavier disk, not the sum
  CHECK(*r.probes.at("sum_all") == Approx(w1 + w2).epsilon(1e-6));
  CHECK(*r.probes.at("max_left") == Approx(w1).epsilon(1e-6));   // s < 1.25 m: only the light disk (s = 1.0; the heavy one at 1.5)
  CHECK(*r.probes.at("max_none") == 0.0);                        // no contact in the band
  CHECK(*r.probes.at("share") == Approx(0.25).epsilon(1e-6));    // max_left / max_all
  // the free disk falls for the whole run: v_y = −g t at t = 0.2 s (K18 staggered: exact for constant g)
  CHECK(*r.probes.at("vy_falling") == Approx(-9.81 * 0.2).epsilon(1e-3));
  CHECK(std::abs(*r.probes.at("vy_resting")) < 1e-6);
  CHECK(*r.probes.at("vy_empty") == 0.0);
}

TEST_CASE("A ratio probe names two earlier probes that are not ratios", "[run]") {
  auto refused = [](const std::string& probes, const std::string& what) {
    const fs::path file = write_case("ratio", resting_and_falling(probes));
    REQUIRE_THROWS_WITH(dem::check_outputs(dem::read_case(file, {})), Contains(what));  // what `dem2d check` does
  };
  refused("[[probe]]\nname = \"r2\"\nkind = \"ratio\"\nof = \"nosuch\"\nover = \"max_all\"\n", "of: no probe \"nosuch\"");
  refused("[[probe]]\nname = \"r2\"\nkind = \"ratio\"\nof = \"share\"\nover = \"max_all\"\n", "is a ratio itself");
  refused("[[probe]]\nname = \"r2\"\nkind = \"ratio\"\nof = \"max_all\"\n", "over");
  refused("[[probe]]\nname = \"r2\"\nquantity = \"box.vy(1,0,0,1)\"\n", "x0 < x1");
  refused("[[probe]]\nname = \"r2\"\nquantity = \"floor.fn_max(0.5,0.5)\"\n", "s0 < s1");
}

TEST_CASE("The jitter of an ordered fill moves every centre by at most the jitter, per seed, and is bounded by the gap", "[cases]") {
  const std::string base =
      "[case]\ntitle = \"jitter\"\n[[material]]\nname = \"d\"\ndensity = 1000.0\n"
      "[[contact]]\nbetween = [\"d\", \"d\"]\nkn = 1e6\n"
      "[[arrangement]]\nkind = \"ordered\"\nmaterial = \"d\"\nradius = \"1 cm\"\ns = 4\nrows = 3\n"
      "left = \"0 cm\"\nright = \"9 cm\"\nfloor = \"0 cm\"\ngap = \"0.01 cm\"\n";
  const std::string tail = "[numerics]\ndt = 1e-5\nduration = 0.1\n";
  const dem::Case plain = dem::read_case(write_case("j0", base + tail), {});
  const dem::Case a = dem::read_case(write_case("j1", base + "jitter = \"1e-4 cm\"\nseed = 1\n" + tail), {});
  const dem::Case b = dem::read_case(write_case("j2", base + "jitter = \"1e-4 cm\"\nseed = 2\n" + tail), {});
  const dem::Case a2 = dem::read_case(write_case("j3", base + "jitter = \"1e-4 cm\"\nseed = 1\n" + tail), {});
  REQUIRE(plain.model.elements.size() == 11);
  double largest = 0.0, differ = 0.0;
  for (std::size_t i = 0; i < plain.model.elements.size(); ++i) {
    largest = std::max({largest, std::abs(a.model.elements.x[i] - plain.model.elements.x[i]),
                        std::abs(a.model.elements.y[i] - plain.model.elements.y[i])});
    differ = std::max(differ, std::abs(a.model.elements.x[i] - b.model.elements.x[i]));
    CHECK(a.model.elements.x[i] == a2.model.elements.x[i]);  // the same seed, the same fill
  }
  CHECK(largest <= 1e-6);
  CHECK(largest > 1e-7);  // it does move them
  CHECK(differ > 0.0);    // another seed, another fill
  // 2√2 jitter must stay within the smallest gap (1e-4 m): 3.6e-5 m is refused, naming the bound
  REQUIRE_THROWS_WITH(dem::read_case(write_case("j4", base + "jitter = \"3.6e-3 cm\"\n" + tail), {}),
                      Contains("jitter: at most 3.53553e-05 m"));
  REQUIRE_THROWS_WITH(dem::read_case(write_case("j5", base + "seed = 3\n" + tail), {}), Contains("no effect without a jitter"));
}
