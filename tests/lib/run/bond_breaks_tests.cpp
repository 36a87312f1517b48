// The bond-break log (output.bond_breaks, lib/dem/core/bond_breaks.cpp, run_outputs.cpp): every bonded
// PRE link that breaks in tension (M8) is listed once, when and where it broke, and the pictures mark it.
// The pair of restart_pre_break.toml: the left PRE fixed, the right one thrown off to the right with a
// counter-clockwise spin, so the face opens from below: its four links break bottom first.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;

namespace {

struct BreakRow {
  double t = 0.0;
  long step = 0;
  std::string element, other;
  int segment = 0;
  double xi = 0.0, x = 0.0, y = 0.0;
  std::string mode;
};

std::vector<BreakRow> read_breaks(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "t [s],step,element,other,segment,xi,x [m],y [m],mode");
  std::vector<BreakRow> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    BreakRow r;
    std::getline(ss, cell, ','), r.t = std::stod(cell);
    std::getline(ss, cell, ','), r.step = std::stol(cell);
    std::getline(ss, r.element, ',');
    std::getline(ss, r.other, ',');
    std::getline(ss, cell, ','), r.segment = std::stoi(cell);
    std::getline(ss, cell, ','), r.xi = std::stod(cell);
    std::getline(ss, cell, ','), r.x = std::stod(cell);
    std::getline(ss, cell, ','), r.y = std::stod(cell);
    std::getline(ss, r.mode);
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("bond-break log: each bonded link once - when and where it broke - bottom first as the face opens from below") {
  const auto out = test::fresh_dir("dem2d_unit_bond_breaks", "pair");
  dem::RunOptions o;
  o.out_dir = out;
  const dem::Case c = dem::read_case(test::source("tests/lib/fixtures/restart_pre_break.toml"),
                                     {"output.bond_breaks=true", "output.picture_times=[\"0.0015 s\"]"});
  const auto r = dem::run_case(c, o);
  REQUIRE(r.status == "completed");
  const auto rows = read_breaks(out / "bond_breaks.csv");
  REQUIRE(rows.size() == 4);  // four segments, every one bonded at the start, every one broken by the end
  std::vector<int> segments;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const BreakRow& b = rows[k];
    CHECK(b.mode == "tension (M8)");
    CHECK(b.element + "-" + b.other == "0-1");
    segments.push_back(b.segment);
    // on the face between the centres (x = r = 12.5 mm at the start; the right element has moved
    // by under 0.02 m/s × 2 ms) and within its half-length (a = r)
    CHECK(b.x > 0.0125);
    CHECK(b.x < 0.0125 + 0.0001);
    CHECK(std::abs(b.y) < 0.0125);
    if (k > 0) {
      CHECK(b.step > rows[k - 1].step);  // one at a time
      CHECK(b.t > rows[k - 1].t);
      CHECK(b.y > rows[k - 1].y);  // the face opens from below: the lowest link first
    }
  }
  std::sort(segments.begin(), segments.end());
  CHECK(segments == std::vector<int>{0, 1, 2, 3});
  // the series agrees: no link left at the end
  CHECK(*r.probes.at("links_end") == 0.0);
  // a picture after the first breaks was drawn with their marks (its file exists; the marks are drawn
  // by force_network.cpp, whose pixels picture_tests checks)
  CHECK(fs::exists(out / "pictures"));
}

TEST_CASE("bond-break log: off by default - no file") {
  const auto out = test::fresh_dir("dem2d_unit_bond_breaks", "off");
  dem::RunOptions o;
  o.out_dir = out;
  const auto r = dem::run_case(dem::read_case(test::source("tests/lib/fixtures/restart_pre_break.toml")), o);
  REQUIRE(r.status == "completed");
  CHECK_FALSE(fs::exists(out / "bond_breaks.csv"));
}
