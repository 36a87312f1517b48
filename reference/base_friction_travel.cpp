// θ against plate travel δ_B for a rate law dθ/dδ_B = rate(alpha + θ) (refs §3.3), two ways.
//
// With dθ/dδ_B = |λ(psi)| (refs §3.1) and psi = alpha + θ:
//   θ(δ_B):   the ODE θ' = rate(alpha + θ), θ(0) = 0, by dopri5 with dense output; the run stops
//             when θ reaches pi/2 (long face on the slope) or the last requested travel;
//   δ_B(θ):   separating variables, δ_B = ∫₀^θ dθ'/rate(alpha + θ'), by adaptive quadrature.
// The two are inverse functions of each other, which the unit tests check.
#include "ref/base_friction_travel.hpp"

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include "ref/base_friction.hpp"
#include "ref/base_friction_m21.hpp"
#include "ref/gsl_support.hpp"
#include "ref/require.hpp"

namespace ref {

namespace {

constexpr double quarter_turn = std::numbers::pi / 2.0;
constexpr double ode_tolerance = 1e-10;         // refs §3.3
constexpr double quadrature_tolerance = 1e-10;  // relative

void require_slope(const char* where, double alpha) {
  detail::require_finite(where, "alpha", alpha);
  if (!(alpha >= 0.0 && alpha < quarter_turn))
    detail::fail(where, "alpha must lie in [0, pi/2) rad", alpha);
}

void require_block(const char* where, double width, double height) {
  detail::require_positive(where, "width", width);
  detail::require_positive(where, "height", height);
}

}  // namespace

std::vector<double> theta_at_travels(const std::vector<double>& travels, double alpha,
                                     const RotationRate& rate) {
  constexpr const char* where = "ref::theta_at_travels";
  require_slope(where, alpha);
  if (!rate) throw std::invalid_argument(std::string(where) + ": empty rate function");
  for (const double travel : travels) detail::require_non_negative(where, "travel", travel);

  std::vector<double> theta(travels.size(), 0.0);
  const double rate0 = rate(alpha);
  if (!(std::isfinite(rate0) && rate0 >= 0.0))
    detail::fail(where, "rate(alpha) must be finite and >= 0", rate0);
  if (rate0 == 0.0) return theta;  // θ' = 0 at θ = 0: the block stays on its base

  std::vector<std::size_t> order(travels.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return travels[a] < travels[b]; });

  namespace odeint = boost::numeric::odeint;
  using State = std::array<double, 1>;
  const auto system = [&](const State& x, State& dxdt, double /*travel*/) {
    // Stages of the last step may overshoot pi/2; θ beyond it is never reported.
    const double r = rate(alpha + std::clamp(x[0], 0.0, quarter_turn));
    if (!(std::isfinite(r) && r >= 0.0))
      throw std::invalid_argument(std::string(where) + ": rate must be finite and >= 0");
    dxdt[0] = r;
  };
  auto stepper = odeint::make_dense_output(ode_tolerance, ode_tolerance,
                                           odeint::runge_kutta_dopri5<State>());
  stepper.initialize(State{0.0}, 0.0, 1e-3 / rate0);  // first step: ~1e-3 rad

  std::size_t next = 0;
  while (next < order.size() && travels[order[next]] == 0.0) ++next;
  for (long step = 0; next < order.size(); ++step) {
    if (stepper.current_state()[0] >= quarter_turn) {  // landed before the remaining travels
      for (; next < order.size(); ++next) theta[order[next]] = quarter_turn;
      break;
    }
    if (step > 1000000) throw std::runtime_error(std::string(where) + ": too many steps");
    stepper.do_step(system);
    for (; next < order.size() && travels[order[next]] <= stepper.current_time(); ++next) {
      State x{};
      stepper.calc_state(travels[order[next]], x);
      theta[order[next]] = std::clamp(x[0], 0.0, quarter_turn);
    }
  }
  return theta;
}

double travel_at_theta(double theta, double alpha, const RotationRate& rate) {
  constexpr const char* where = "ref::travel_at_theta";
  require_slope(where, alpha);
  if (!rate) throw std::invalid_argument(std::string(where) + ": empty rate function");
  detail::require_finite(where, "theta", theta);
  if (!(theta >= 0.0 && theta <= quarter_turn))
    detail::fail(where, "theta must lie in [0, pi/2] rad", theta);
  if (theta == 0.0) return 0.0;
  const double rate0 = rate(alpha);
  if (!(std::isfinite(rate0) && rate0 >= 0.0))
    detail::fail(where, "rate(alpha) must be finite and >= 0", rate0);
  if (rate0 == 0.0) return std::numeric_limits<double>::infinity();  // never starts to turn
  const auto slowness = [&](double turned) { return 1.0 / rate(alpha + turned); };
  // Split at psi = 90°: there the instantaneous centre of M25 crosses the base face's normal
  // through P (w0 = 0) and the rate has a weak singularity (harmless for smooth rates).
  const double split = quarter_turn - alpha;
  if (split > 0.0 && split < theta)
    return detail::integrate_qag(where, slowness, 0.0, split, 0.0, quadrature_tolerance,
                                 GSL_INTEG_GAUSS21) +
           detail::integrate_qag(where, slowness, split, theta, 0.0, quadrature_tolerance,
                                 GSL_INTEG_GAUSS21);
  return detail::integrate_qag(where, slowness, 0.0, theta, 0.0, quadrature_tolerance,
                               GSL_INTEG_GAUSS21);
}

std::vector<double> theta_at_travels(const std::vector<double>& travels, double alpha,
                                     double width, double height, MomentEvaluation evaluation) {
  require_block("ref::theta_at_travels", width, height);
  return theta_at_travels(travels, alpha, [=](double psi) {
    return base_friction_rate(psi, width, height, evaluation);
  });
}

double theta_at_travel(double travel, double alpha, double width, double height,
                       MomentEvaluation evaluation) {
  return theta_at_travels(std::vector<double>{travel}, alpha, width, height, evaluation).front();
}

double travel_at_theta(double theta, double alpha, double width, double height,
                       MomentEvaluation evaluation) {
  require_block("ref::travel_at_theta", width, height);
  return travel_at_theta(theta, alpha, [=](double psi) {
    return base_friction_rate(psi, width, height, evaluation);
  });
}

double theta_at_travel_m21(double travel, double alpha, double width, double height, int n_w,
                           int n_h) {
  m21_moment(0.0, alpha, width, height, n_w, n_h);  // validates the block and the elements
  return theta_at_travels(
             std::vector<double>{travel}, alpha,
             [=](double psi) { return m21_rate(psi, width, height, n_w, n_h); })
      .front();
}

}  // namespace ref
