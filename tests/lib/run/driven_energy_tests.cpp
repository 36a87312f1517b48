// The energy bound counts what the drives put in (lib/dem/run/loop_state.cpp, energy_scale): a case whose
// only moving element is driven with a rising velocity has a kinetic energy the free elements' mass does not
// bound (it has none); it must run to its end as correct physics, not stop as a blow-up. Both integrators
// (K18 and K19), with and without gravity (a driven element lifted against it).
#include <catch2/catch.hpp>

#include <string>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/run/run.hpp"
#include "../test_support.hpp"

namespace {

/// One 1 kg disk driven from rest to `v_end` (along +y) over 1 s, a fixed disk far away; nothing else moves.
std::string ramp_case(double v_end, double g) {
  return fmt::format(R"([case]
title = "a ramp-driven disk"
[physics]
gravity = [0.0, {g}]
[[material]]
name = "d"
density = 2650.0
[[contact]]
between = ["d", "d"]
kn = 1e5
[[drive]]
name = "ramp"
times = [0.0, 1.0]
velocities = [[0.0, 0.0], [0.0, {v}]]
[[element]]
material = "d"
radius = 0.01
mass = 1.0
position = [0.0, 0.0]
motion = "driven"
drive = "ramp"
[[element]]
material = "d"
radius = 0.01
position = [5.0, 0.0]
motion = "fixed"
[numerics]
dt = 1e-4
duration = 1.0
[output]
vtk = false
)",
                     fmt::arg("g", g), fmt::arg("v", v_end));
}

}  // namespace

TEST_CASE("blow-up: a ramp-driven element with no free element runs to the end (K18 and K19)", "[trust][run]") {
  for (const char* integrator : {"K18", "K19"})
    for (const double g : {0.0, -9.81}) {
      INFO(integrator << " g = " << g);
      const auto file = test::write_temp(fmt::format("ramp_{}_{}.toml", integrator, g < 0 ? "g" : "0"), ramp_case(2.0, g));
      const auto r = dem::run_case(dem::read_case(file, {fmt::format("numerics.integrator=\"{}\"", integrator)}), {});
      CHECK(r.status == "completed");
      CHECK(r.message == "");
    }
}
