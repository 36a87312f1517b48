// A driven element (Motion::driven, a velocity history) follows its prescribed motion exactly under both
// integrators: its increment is v(t + Δt/2) Δt in every step (the history at the middle of the step, K18's
// rule also under K19: a prescribed motion is not averaged), so a linear velocity ramp v = a t gives
// y(t_n) = a t_n² / 2 to rounding (the midpoint rule is exact for a linear velocity). A free element in the
// same model keeps the general (scalar) integration path in use.
#include <catch2/catch.hpp>

#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

using Catch::Matchers::WithinAbs;

namespace {

constexpr double kDt = 1e-4, kA = 2.0;  // time step [s], the ramp's acceleration [m/s²]

dem::Model ramp_model(dem::Integrator integrator) {
  auto m = test::make_model({{"disk", 2650.0}}, kDt);
  m.numerics.integrator = integrator;
  m.gravity = {0.0, -9.81};
  dem::VelocityHistory ramp;
  ramp.t = {0.0, 1.0};
  ramp.v = {{0.0, 0.0}, {0.0, kA}};
  m.drives.push_back(ramp);
  const std::size_t d = dem::add_element(m, dem::Shape::disk, 0, 0.01, {0.0, 0.0});
  m.elements.motion[d] = dem::Motion::driven;
  m.elements.drive[d] = 0;
  dem::add_element(m, dem::Shape::disk, 0, 0.01, {5.0, 0.0}, {0.1, 0.0});  // free, far away, falling
  return m;
}

}  // namespace

TEST_CASE("driven element: a velocity ramp is followed exactly by K18 and K19", "[integration][drive]") {
  for (const auto integrator : {dem::Integrator::k18, dem::Integrator::k19}) {
    INFO((integrator == dem::Integrator::k18 ? "K18" : "K19"));
    dem::Simulation sim(ramp_model(integrator));
    const int n = 1000;
    for (int s = 0; s < n; ++s) sim.step();
    const double t = n * kDt;
    const auto& e = sim.model().elements;
    CHECK_THAT(e.y[0], WithinAbs(0.5 * kA * t * t, 1e-14));     // 0.01 m: the prescribed path
    CHECK(e.x[0] == 0.0);
    CHECK(e.phi[0] == 0.0);
    CHECK_THAT(e.vy[0], WithinAbs(kA * (t - 0.5 * kDt), 1e-14)); // the velocity of the last step's middle
    CHECK_THAT(e.dy[0], WithinAbs(kA * (t - 0.5 * kDt) * kDt, 1e-17));  // increment v Δt, not averaged
    // the free element beside it still falls freely (the driven one does not disturb the general path)
    CHECK(e.vy[1] < 0.0);
    CHECK_THAT(e.x[1], WithinAbs(5.0 + 0.1 * t, 1e-12));
  }
}
