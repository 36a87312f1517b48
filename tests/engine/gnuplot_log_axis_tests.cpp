// A log axis of the report's figures (reports/gnuplot_plot.cpp, log_axis): its range is taken from the
// data with a margin, so it must contain every drawable point; its 1-2-5 tics include a data end that is
// a tic value up to round-off (relative 1e-12: a value computed as 0.2 that prints as 0.2). Two sets: x
// over [0.2, 0.9], y over [3e-5, 5e-4]. Planted bug that turned this red (g578749-025): the lower end's
// round-off allowance halved (5e-13), which dropped the tic 0.2 of data starting at 0.2 (1 + 8e-13).
#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include "gnuplot_plot.hpp"

namespace {

/// The [lo, hi] of "set <axis>range [lo:hi]" in a gnuplot script.
std::pair<double, double> range_of(const std::string& script, const std::string& axis) {
  std::smatch m;
  const std::regex re("set " + axis + "range \\[([^:]+):([^\\]]+)\\]");
  REQUIRE(std::regex_search(script, m, re));
  return {std::stod(m[1].str()), std::stod(m[2].str())};
}

}  // namespace

TEST_CASE("Log axes contain the data and keep a tic at a data end equal to a tic up to round-off", "[report][plots]") {
  {  // x: 0.2 (1 + 8e-13) .. 0.9
    report::Plot plot;
    plot.logx = true;
    plot.curves.push_back({"data", {0.2 * (1 + 8e-13), 0.3, 0.9}, {1.0, 2.0, 3.0}});
    const std::string s = report::gnuplot_script(plot, "x.svg");
    CHECK(s.find("set xtics (0.2, 0.5)") != std::string::npos);
    const auto [lo, hi] = range_of(s, "x");
    CHECK(lo < 0.2 * (1 + 8e-13));
    CHECK(hi > 0.9);
  }
  {  // y: 3e-5 .. 5e-4 (1 − 8e-13): the tics 5e-5, 1e-4, 2e-4 and 5e-4 (the upper end up to round-off)
    report::Plot plot;
    plot.logy = true;
    plot.curves.push_back({"data", {1.0, 2.0, 3.0}, {3e-5, 1e-4, 5e-4 * (1 - 8e-13)}});
    const std::string s = report::gnuplot_script(plot, "y.svg");
    CHECK(s.find("set ytics (5e-05, 0.0001, 0.0002, 0.0005)") != std::string::npos);
    const auto [lo, hi] = range_of(s, "y");
    CHECK(lo < 3e-5);
    CHECK(hi > 5e-4 * (1 - 8e-13));
  }
}
