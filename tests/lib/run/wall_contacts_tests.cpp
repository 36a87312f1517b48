// The sign of a wall's force profile (<wall>.fn/fs(s0,s1), wall_contacts.csv: lib/dem/run/
// wall_contacts_csv.hpp) on a planted case: a disk sliding down a wall pushes the wall down, so the force
// along from→to is −μ_w f_n for a wall drawn upwards and +μ_w f_n for the same wall drawn downwards; the
// fill quantities active.top and active.area_fraction (fill_quantities.hpp); the reader's refusals.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "dem/cases/case_file.hpp"
#include "dem/run/fill_quantities.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

dem::RunResult run(const fs::path& out, const std::vector<std::string>& sets = {}) {
  dem::RunOptions o;
  o.out_dir = out;
  return dem::run_case(dem::read_case(test::case_dir() / "wall_slide.toml", sets), o);
}

double probe(const dem::RunResult& r, const std::string& name) {
  REQUIRE(r.probes.count(name));
  REQUIRE(r.probes.at(name).has_value());
  return *r.probes.at(name);
}

/// The single data row of wall_contacts.csv, split.
std::vector<std::string> only_row(const fs::path& file) {
  std::istringstream in(test::slurp(file));
  std::string header, row, more;
  std::getline(in, header);
  CHECK(header == "wall,s [m],x [m],y [m],depth [m],fn [N],fs [N]");
  std::getline(in, row);
  CHECK_FALSE(std::getline(in, more));
  std::vector<std::string> cells;
  std::stringstream ss(row);
  for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
  REQUIRE(cells.size() == 7);
  return cells;
}

}  // namespace

TEST_CASE("A disk sliding down a wall drawn upwards gives fs = -mu_w fn on the wall", "[run][wall]") {
  const fs::path out = test::fresh_dir("dem2d_unit_wall", "up");
  const dem::RunResult r = run(out);
  const double fn = probe(r, "fn"), fs_up = probe(r, "fs");
  CHECK(probe(r, "vy") < -0.1);                           // it slides down
  CHECK_THAT(fn, WithinRel(0.5 * 5.0, 1e-3));             // pressed by m g_x (the damped normal oscillation has died out)
  // sliding: |fs| = μ_w fn, pointing down on the wall (to 1e-6: the normal dashpot's residual force, 5e-8
  // of f_n here, is in the probe's f_n but not in the spring force the Coulomb cap scales)
  CHECK_THAT(fs_up, WithinRel(-0.1 * fn, 1e-6));
  CHECK_THAT(probe(r, "fy"), WithinRel(fs_up, 1e-12));    // the wall's y force is its force along from→to
  const auto cells = only_row(out / "wall_contacts.csv");
  CHECK(cells[0] == "up");
  CHECK(std::stod(cells[2]) == 0.0);                                    // the contact point is on the wall
  CHECK_THAT(std::stod(cells[4]), WithinAbs(probe(r, "top") - std::stod(cells[3]), 1e-15));  // depth = top − y
  CHECK_THAT(std::stod(cells[4]), WithinAbs(0.01, 1e-6));               // one disk: its top is r above its contact
  CHECK_THAT(std::stod(cells[5]), WithinRel(fn, 1e-12));
  CHECK_THAT(std::stod(cells[6]), WithinRel(fs_up, 1e-12));
  CHECK_THAT(std::stod(cells[1]), WithinAbs(std::stod(cells[3]), 1e-15));  // s along the wall from (0, 0) = y
}

TEST_CASE("The same wall drawn downwards gives fs = +mu_w fn", "[run][wall]") {
  const fs::path out = test::fresh_dir("dem2d_unit_wall", "down");
  const dem::RunResult r = run(out, {"wall.0.from=[\"0 m\", \"1 m\"]", "wall.0.to=[\"0 m\", \"0 m\"]"});
  const double fn = probe(r, "fn");
  CHECK_THAT(probe(r, "fs"), WithinRel(0.1 * fn, 1e-6));
  CHECK_THAT(probe(r, "fy"), WithinRel(-probe(r, "fs"), 1e-12));  // along from→to is −y now
  const auto cells = only_row(out / "wall_contacts.csv");
  CHECK_THAT(std::stod(cells[6]), WithinRel(0.1 * fn, 1e-6));
  CHECK_THAT(std::stod(cells[1]), WithinAbs(1.0 - std::stod(cells[3]), 1e-12));  // s from (0, 1) downwards
}

TEST_CASE("With ample friction the disk rolls down the wall: a = 2g/3 and fs = -m g/3", "[run][wall]") {
  // a disk (I = m r²/2) rolling without slip: m a = m g − F, I α = F r, a = α r → a = 2g/3, F = m g/3;
  // μ_w = 10 far exceeds the F/f_n = (g/3)/g_x = 0.65 it needs
  const dem::RunResult r = run({}, {"contact.0.friction=10", "numerics.duration=0.2 s"});
  CHECK_THAT(probe(r, "vy"), WithinRel(-2.0 / 3.0 * 9.81 * 0.2, 2e-3));  // the start-up of the contact lags a little
  CHECK_THAT(probe(r, "fs"), WithinRel(-0.5 * 9.81 / 3.0, 1e-3));
}

TEST_CASE("Fill quantities: the exact area of a disk between two lines and active.top", "[run][fill]") {
  const double r = 0.01, full = std::numbers::pi * r * r;
  CHECK_THAT(dem::disk_area_between(0.0, r, -1.0, 1.0), WithinRel(full, 1e-15));
  CHECK_THAT(dem::disk_area_between(0.0, r, 0.0, 1.0), WithinRel(full / 2, 1e-15));
  CHECK(dem::disk_area_between(0.0, r, 0.02, 1.0) == 0.0);
  // the segment below y = r/2: r² (π/3 − √3/4) above the chord cut off, the rest below
  const double cap = r * r * (std::numbers::pi / 3.0 - std::sqrt(3.0) / 4.0);
  CHECK_THAT(dem::disk_area_between(0.0, r, -1.0, r / 2), WithinRel(full - cap, 1e-13));
  CHECK_THAT(dem::disk_area_between(0.3, r, 0.3 + r / 2, 1.0), WithinRel(cap, 1e-12));
  // the one-disk case: the disk lies in [0, 2 cm] x [0.49, 0.51 m] at the start (probe "top" read as
  // the area fraction of that square)
  const dem::Case c = dem::read_case(test::case_dir() / "wall_slide.toml",
                                     {"probe.3.quantity=active.area_fraction(0,0.02,0.49,0.51)", "numerics.duration=1e-5 s"});
  dem::RunOptions o;
  const dem::RunResult res = dem::run_case(c, o);
  REQUIRE(res.probes.at("top").has_value());
  CHECK_THAT(*res.probes.at("top"), WithinRel(full / (0.02 * 0.02), 1e-6));  // the strip holds the whole disk
}

TEST_CASE("Wall contacts and fill quantities are read strictly", "[run][wall]") {
  const auto msg = [](const std::vector<std::string>& sets) {
    return test::message_of<dem::CaseError>([&] { dem::check_outputs(dem::read_case(test::case_dir() / "wall_slide.toml", sets)); });
  };
  CHECK_THAT(msg({"output.wall_contacts=[\"nope\"]"}), Contains("wall_contacts") && Contains("unknown wall \"nope\""));
  CHECK_THAT(msg({"output.wall_contacts=[\"up\", \"up\"]"}), Contains("named twice"));
  CHECK_THAT(msg({"probe.3.quantity=active.area_fraction(0,0.02,0.5)"}), Contains("active.area_fraction(x0,x1,y0,y1)"));
  CHECK_THAT(msg({"probe.3.quantity=active.area_fraction(0.02,0,0.4,0.5)"}), Contains("x0 < x1"));
  CHECK_THAT(msg({"probe.3.quantity=active.area_fraction(0,0.02,0.4,0.5x)"}), Contains("active.area_fraction"));
}
