// numerics.guard_reach (docs/model.md G7): the time-step guard counts as partners only the elements within
// reach, and the run evaluates the guard again once a free element has moved farther than the reach;
// a Δt above the new guard stops the run ("refused") before the contact it did not count can form.
// Planted bugs that turn these red: the run's re-check left out (the run reaches the contact and
// completes), the partner test with the reach doubled (refused later than it must), and the reach
// ignored by the guard (refused at the start).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/core/stability.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

using Catch::Matchers::Contains;

namespace {

/// A free 1 kg disk (radius 1 cm) at x = 0 moving at 0.2 m/s towards a fixed one at x = 10 cm (gap 8 cm,
/// touching at t = 0.4 s); K = 1e6 N/m, no damping, K18. The row sums count the fixed partner as an
/// element (w + b = K/m + K/√(m m_j) = 2e6 1/s²): the guard's limit is 2/√(2e6) s = 1.41421 ms.
std::string approach_case(const std::string& dt, const std::string& reach) {
  return fmt::format(R"([case]
title = "guard reach"
source = "tests/lib/run/guard_reach_tests.cpp"
[physics]
gravity = [0.0, 0.0]
[[material]]
name = "disk"
density = "2650 kg/m^3"
[[contact]]
between = ["disk", "disk"]
law = "linear"
kn = "1e6 N/m"
ks = 0.0
friction = 0.0
damping_ratio = 0.0
[[element]]
material = "disk"
radius = "1 cm"
mass = "1 kg"
position = ["0 m", "0 m"]
velocity = ["0.2 m/s", "0 m/s"]
[[element]]
material = "disk"
radius = "1 cm"
mass = "1 kg"
position = ["10 cm", "0 m"]
motion = "fixed"
[numerics]
integrator = "K18"
dt = "{}"
duration = "0.6 s"
{}
[output]
vtk = false
)",
                     dt, reach.empty() ? "" : fmt::format("guard_reach = \"{}\"", reach));
}

dem::RunResult run(const std::string& name, const std::string& text) {
  dem::RunOptions o;
  o.out_dir = test::fresh_dir("dem2d_unit_guard_reach", name);
  return dem::run_case(dem::read_case(test::write_temp(name + ".toml", text)), o);
}

}  // namespace

TEST_CASE("guard reach: without it a partner anywhere counts and the time step is refused at the start", "[run][stability]") {
  CHECK_THROWS_WITH(dem::check_case(dem::read_case(test::write_temp("reach_none.toml", approach_case("5 ms", "")))),
                    Contains("above the stability limit 0.00141421 s"));
}

TEST_CASE("guard reach: a partner out of reach does not count at the start", "[run][stability]") {
  const dem::Case far = dem::read_case(test::write_temp("reach_far.toml", approach_case("1 ms", "1 cm")));
  CHECK(dem::assembly_stability_bound(far.model, {}).limit == std::numeric_limits<double>::infinity());
  // the gap, 8 cm, against twice the reach: a free element moves R, a fixed one 0
  const dem::Case near = dem::read_case(test::write_temp("reach_near.toml", approach_case("1 ms", "8.0001 cm")));
  CHECK(dem::assembly_stability_bound(near.model, {}).limit == Approx(2.0 / std::sqrt(2e6)).epsilon(1e-12));
  const dem::Case short_of = dem::read_case(test::write_temp("reach_short.toml", approach_case("1 ms", "7.9999 cm")));
  CHECK(dem::assembly_stability_bound(short_of.model, {}).limit == std::numeric_limits<double>::infinity());
}

TEST_CASE("guard reach: the run stops before a contact its guard did not count", "[run][stability]") {
  CHECK_NOTHROW(dem::check_case(dem::read_case(test::write_temp("reach_start.toml", approach_case("5 ms", "1 cm")))));
  const dem::RunResult r = run("refused", approach_case("5 ms", "1 cm"));
  CHECK(r.status == "refused");
  // the re-checks come each 1 cm of travel (5 steps of 1 mm); the one at x = 7 cm (gap 1 cm, t = 0.35 s)
  // or just after it counts the fixed disk: 1.41 ms < Δt = 5 ms. Touching would be at t = 0.4 s.
  CHECK(r.time > 0.3);
  CHECK(r.time < 0.4);
  CHECK_THAT(r.message, Contains("element 0 moved more than numerics.guard_reach = 0.01 m"));
  CHECK_THAT(r.message, Contains("the guard of the current positions is 0.00141421 s (before: inf s)"));
  CHECK(r.stability_limit == Approx(2.0 / std::sqrt(2e6)).epsilon(1e-12));
}

TEST_CASE("guard reach: below the new guard the run goes on through the contact", "[run][stability]") {
  const dem::RunResult r = run("passes", approach_case("1 ms", "1 cm"));
  CHECK(r.status == "completed");
  CHECK(r.stability_limit == Approx(2.0 / std::sqrt(2e6)).epsilon(1e-12));  // the lowest guard the run saw
}
