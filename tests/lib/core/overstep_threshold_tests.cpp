// The kinematic blow-up guard (Simulation::overstep, numerics.max_step_fraction) has an exact threshold and
// names the element that crossed it: an element whose step |Δx| is just below f·r is not reported, one just
// above is, and of two elements the one that moved more than f times *its own* radius is named, on the
// vectorised all-free path and on the general path (a fixed element present).
#include <catch2/catch.hpp>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinRel;

namespace {

constexpr double kDt = 1e-3, kF = 0.25;

/// Disk 0 (r = 2 cm) at a quarter of the threshold, disk 1 (r = 1 cm) moving `ratio` × f·r per step (K18,
/// no forces), optionally a fixed disk far away.
dem::Model two_disks(double ratio, bool with_fixed) {
  auto m = test::make_model({{"disk", 2650.0}}, kDt);
  m.numerics.integrator = dem::Integrator::k18;
  m.numerics.max_step_fraction = kF;
  m.gravity = {0.0, 0.0};
  dem::add_element(m, dem::Shape::disk, 0, 0.02, {0.0, 0.0}, {0.25 * kF * 0.02 / kDt, 0.0});
  dem::add_element(m, dem::Shape::disk, 0, 0.01, {1.0, 0.0}, {0.0, -ratio * kF * 0.01 / kDt});
  if (with_fixed) {
    const std::size_t k = dem::add_element(m, dem::Shape::disk, 0, 0.01, {-9.0, 9.0});
    m.elements.motion[k] = dem::Motion::fixed;
  }
  return m;
}

}  // namespace

TEST_CASE("blow-up guard: the step fraction threshold is exact and names the element that crossed it",
          "[integration][trust]") {
  for (const bool with_fixed : {false, true}) {
    INFO((with_fixed ? "general path" : "all-free path"));
    {
      dem::Simulation sim(two_disks(1.0 - 1e-9, with_fixed));
      sim.step();
      CHECK(sim.overstep().index == dem::Simulation::Overstep::npos);
    }
    {
      dem::Simulation sim(two_disks(1.0 + 1e-9, with_fixed));
      sim.step();
      const auto o = sim.overstep();
      CHECK(o.index == 1);
      CHECK_THAT(o.fraction2, WithinRel(kF * kF, 1e-8));
    }
  }
}
