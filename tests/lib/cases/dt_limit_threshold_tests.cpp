// The time-step refusal (check_case, refs §1.5) sits exactly at the stability limit it states: a Δt a part
// in 10⁹ below the limit is accepted, the limit itself is accepted (the rule is Δt ≤ limit), a Δt a part
// in 10⁹ above it is refused with the limit in the message, for K18 and for K19 (whose limits differ), and
// numerics.allow_unstable lifts the refusal. A refusal at twice (or half) its stated bound fails here.
#include <catch2/catch.hpp>

#include <string>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "../test_support.hpp"

using Catch::Matchers::Contains;

namespace {

// one disk resting on a floor: a single disk–wall contact sets the limit
const char* kCase = R"([case]
title = "dt threshold"
[physics]
gravity = [0.0, -9.81]
[[material]]
name = "d"
density = 2650.0
[[material]]
name = "w"
[[contact]]
between = ["d", "w"]
kn = "1e6 N/m"
ks_ratio = 0.25
damping_ratio = 0.3
[[element]]
material = "d"
radius = "1 cm"
position = [0.0, 0.01]
[[wall]]
from = [-1.0, 0.0]
to = [1.0, 0.0]
material = "w"
[numerics]
dt = 1e-7
duration = 1e-5
[output]
vtk = false
)";

double limit_at(const std::filesystem::path& path, const std::string& integrator, double dt) {
  return dem::check_case(dem::read_case(path, {"numerics.integrator=\"" + integrator + "\"",
                                               fmt::format("numerics.dt={:.17g}", dt)}));
}

}  // namespace

TEST_CASE("dt limit: the refusal is exact at the stated stability limit (K18 and K19)", "[case][stability]") {
  const auto path = test::write_temp("dt_threshold.toml", kCase);
  double limits[2] = {0.0, 0.0};
  int k = 0;
  for (const std::string integrator : {"K18", "K19"}) {
    INFO(integrator);
    const double limit = limit_at(path, integrator, 1e-7);
    limits[k++] = limit;
    REQUIRE(limit > 1e-6);
    CHECK(limit_at(path, integrator, limit * (1.0 - 1e-9)) == limit);  // the limit does not depend on Δt
    CHECK(limit_at(path, integrator, limit) == limit);                  // Δt = limit is accepted
    const std::string msg = test::message_of<dem::CaseError>([&] { limit_at(path, integrator, limit * (1.0 + 1e-9)); });
    CHECK_THAT(msg, Contains("numerics.dt") && Contains("above the stability limit") &&
                        Contains(fmt::format("{:.6g} s", limit)) && Contains(integrator));
    const auto unstable = dem::read_case(path, {"numerics.integrator=\"" + integrator + "\"", "numerics.allow_unstable=true",
                                                fmt::format("numerics.dt={:.17g}", 2.0 * limit)});
    CHECK(dem::check_case(unstable) == limit);
  }
  CHECK(limits[0] != limits[1]);
}
