// The geometry of a convergence plot (reports/study_plots.hpp), not only that it renders: the error curve
// holds exactly the levels with a positive error, the dashed reference line has the expected order as its
// log-log slope (its sign included: the error grows with h), goes through the finest plotted point and
// spans the plotted h range, whatever order the levels come in; the tolerance band spans the same range at
// the tolerance. A reference line of the wrong sign or through the wrong point still renders: this catches it.
#include <catch2/catch.hpp>

#include <cmath>
#include <nlohmann/json.hpp>

#include "study_plots.hpp"

using Catch::Matchers::WithinRel;

namespace {

double loglog_slope(const report::Curve& c) {
  return (std::log(c.y.back()) - std::log(c.y.front())) / (std::log(c.x.back()) - std::log(c.x.front()));
}

}  // namespace

TEST_CASE("convergence plot: the reference line has the expected order as its slope through the finest point",
          "[report][plots]") {
  for (const double order : {1.0, 2.0, 0.5}) {
    INFO("order " << order);
    // levels in no particular order; one with a zero error (not drawable on a log axis)
    const nlohmann::json series = {{"name", "x(1 s) [m]"},   {"parameter", "dt"},
                                   {"h", {2e-3, 1e-3, 4e-3, 8e-3}}, {"error", {3e-6, 1e-6, 1.3e-5, 0.0}},
                                   {"expected_order", order},       {"reference", 0.5}};
    std::string why_not, note;
    const auto plot = report::convergence_plot(series, why_not, note, 2e-5);
    REQUIRE(plot);
    CHECK(plot->logx);
    CHECK(plot->logy);
    CHECK(plot->ylabel == "abs. error |DEM − reference| [m]");
    REQUIRE(plot->curves.size() == 3);
    const auto& err = plot->curves[0];
    CHECK(err.x == std::vector<double>{2e-3, 1e-3, 4e-3});
    CHECK(err.y == std::vector<double>{3e-6, 1e-6, 1.3e-5});
    CHECK(note == "1 level(s) with zero or missing error not drawn");
    const auto& slope = plot->curves[1];
    CHECK(slope.dashed);
    CHECK(slope.label == (order == 1.0 ? "slope 1" : order == 2.0 ? "slope 2" : "slope 0.5"));
    REQUIRE(slope.x.size() == 2);
    CHECK(slope.x.front() == 1e-3);  // the finest plotted h …
    CHECK(slope.y.front() == 1e-6);  // … and its error
    CHECK(slope.x.back() == 4e-3);   // to the coarsest plotted h
    CHECK_THAT(loglog_slope(slope), WithinRel(order, 1e-12));
    CHECK(slope.y.back() > slope.y.front());
    const auto& band = plot->curves[2];
    CHECK(band.x == std::vector<double>{1e-3, 4e-3});
    CHECK(band.y == std::vector<double>{2e-5, 2e-5});
  }
}
