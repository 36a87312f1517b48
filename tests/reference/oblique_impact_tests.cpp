// The oblique-impact reference (reference/ref/oblique_impact.hpp) against closed forms: without friction the
// tangential motion is kept; sliding throughout, the friction impulse is μ∫e_n dt = 2μ m v_n; with an
// uncapped shear spring the slip is an oscillator of mass m/3 decoupled from the normal one. The tolerance of
// 1e-4 m/s (5e-5 of the speed; 1e-2 rad/s on ω r = 1e-4 m/s) is the first-order error of the cap's switches
// (one at the first instant, where the cap is zero) at the reference's step h = T/40000.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <map>
#include <stdexcept>
#include <string>

#include "ref/oblique_impact.hpp"
#include "ref/registry.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double kPi = std::numbers::pi;

// 1 kg, r = 1 cm, K_n = 1e6 N/m (ω_n = 1000 rad/s), no damping, 2 m/s.
ref::ObliqueImpact impact(double theta_deg, double mu, double ks) {
  return {.m = 1.0, .r = 0.01, .kn = 1e6, .eta_n = 0.0, .ks = ks, .eta_s = 0.0, .mu = mu, .v = 2.0, .theta = theta_deg * kPi / 180.0};
}

}  // namespace

TEST_CASE("oblique impact: without friction the tangential motion and spin are kept", "[reference][oblique]") {
  const ref::ObliqueRebound r = ref::oblique_impact(impact(30.0, 0.0, 8e5));
  CHECK_THAT(r.vt, WithinAbs(1.0, 1e-12));
  CHECK_THAT(r.omega, WithinAbs(0.0, 1e-12));
  CHECK_THAT(r.vn, WithinRel(2.0 * std::cos(kPi / 6.0), 1e-6));     // elastic: e = 1
  CHECK_THAT(r.duration, WithinRel(kPi / 1000.0, 1e-4));           // half a normal period
}

TEST_CASE("oblique impact: sliding throughout, the friction impulse is 2 mu m v_n", "[reference][oblique]") {
  // θ = 80°, μ = 0.1: the slip rate v_t + r ω ends at v_t − 6 μ v_n > 0, so the contact slides all along
  const double vn = 2.0 * std::cos(80.0 * kPi / 180.0), vt = 2.0 * std::sin(80.0 * kPi / 180.0);
  const ref::ObliqueRebound r = ref::oblique_impact(impact(80.0, 0.1, 1e9));
  CHECK_THAT(r.vt, WithinAbs(vt - 2.0 * 0.1 * vn, 1e-4));
  CHECK_THAT(r.omega, WithinAbs(-2.0 * 0.1 * vn * 2.0 / 0.01, 1e-2));  // I Δω = −r μ ∫e_n dt, I = m r²/2
}

TEST_CASE("oblique impact: an uncapped shear spring makes the slip an oscillator of mass m/3", "[reference][oblique]") {
  const double ks = 2e5, theta = 20.0 * kPi / 180.0;
  const double s0 = 2.0 * std::sin(theta), w_t = std::sqrt(3.0 * ks / 1.0), tc = kPi / 1000.0;
  const double s_end = s0 * std::cos(w_t * tc);  // the slip rate when the contact ends
  // μ so large that the cap μ K_n δ holds only in the last 1e-9 s, where δ < |e_s|/(μ K_n)
  const ref::ObliqueRebound r = ref::oblique_impact(impact(20.0, 1e6, ks));
  CHECK_THAT(r.vt, WithinAbs(s0 - (s0 - s_end) / 3.0, 1e-4));
  CHECK_THAT(r.omega, WithinAbs(-(2.0 / 3.0) * (s0 - s_end) / 0.01, 1e-2));
  CHECK_THAT(r.vt + 0.01 * r.omega, WithinAbs(s_end, 1e-4));
}

TEST_CASE("oblique impact: through the registry, and refusals", "[reference][oblique]") {
  const std::map<std::string, double> a{{"m", 1.0}, {"r", 0.01}, {"kn", 1e6}, {"eta_n", 0.0}, {"ks", 8e5}, {"eta_s", 0.0}, {"mu", 0.0},
                    {"v", 2.0}, {"theta", kPi / 6.0}, {"omega0", 0.0}};
  CHECK_THAT(ref::evaluate("oblique.vt_after", a), WithinAbs(1.0, 1e-12));
  CHECK_THAT(ref::evaluate("oblique.vn_after", a), WithinRel(2.0 * std::cos(kPi / 6.0), 1e-6));
  CHECK_THAT(ref::evaluate("oblique.omega_after", a), WithinAbs(0.0, 1e-12));
  ref::ObliqueImpact bad = impact(30.0, 0.1, 8e5);
  bad.theta = 0.5 * kPi;
  CHECK_THROWS_AS(ref::oblique_impact(bad), std::invalid_argument);
  bad = impact(30.0, 0.1, 8e5);
  bad.eta_n = 2000.0;  // critical: the overlap never returns to zero
  CHECK_THROWS_AS(ref::oblique_impact(bad), std::invalid_argument);
  bad = impact(30.0, -0.1, 8e5);
  CHECK_THROWS_AS(ref::oblique_impact(bad), std::invalid_argument);
}
