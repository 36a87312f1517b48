#pragma once
// Rotation θ of a toppling block against the base-plate travel δ_B (refs §3.3). The quasi-static
// rate depends on the tilt psi = alpha + θ only, dθ/dδ_B = rate(alpha + θ), from θ(0) = 0 to
// θ = pi/2, when the long face lands on the slope. Two independent routes:
//   θ(δ_B):  Boost.Odeint runge_kutta_dopri5, dense output, abs/rel tolerance 1e-10;
//   δ_B(θ) = ∫₀^θ dθ'/rate(alpha + θ')  by gsl_integration_qag (GAUSS21, rel 1e-10).
// Because the rate depends on psi only, δ_B(θ; alpha) = G(alpha + θ) - G(alpha) with
// G(psi) = ∫ dpsi/rate(psi): the curves of different alpha are shifts of one another.
// The rate is Bray & Goodman's (M25, ref/base_friction.hpp), Matsui's element law (M21,
// ref/base_friction_m21.hpp), or any non-negative function of psi. Units: m, rad.

#include <functional>
#include <vector>

#include "ref/base_friction.hpp"

namespace ref {

// dθ/dδ_B (rad/m, >= 0) as a function of psi (rad).
using RotationRate = std::function<double(double psi)>;

// θ (rad) at each plate travel (m, >= 0, any order) from one integration; pi/2 once the block has
// landed on its long face, 0 for every travel if rate(alpha) = 0 (the block does not topple).
// alpha in [0, pi/2). The rate is called for psi in [alpha, alpha + pi/2]. Accuracy: ~1e-9 rad
// (dopri5 at 1e-10, plus the accuracy of the rate).
std::vector<double> theta_at_travels(const std::vector<double>& travels, double alpha,
                                     const RotationRate& rate);

// Plate travel (m) that turns the block by theta in [0, pi/2] from tilt alpha: ∫₀^θ dθ'/rate; +inf
// for theta > 0 when rate(alpha) = 0. Accuracy: ~1e-10 relative (plus the rate's).
double travel_at_theta(double theta, double alpha, const RotationRate& rate);

// Bray & Goodman (M25) for a W x H block (m): the rate is base_friction_rate(psi, W, H,
// evaluation). Cost with quadrature (a few hundred λ): ~0.1 s for alpha = 30°, ~1-4 s when the
// rotation crosses 90° < psi < 118°; with the closed form ~10 ms.
std::vector<double> theta_at_travels(const std::vector<double>& travels, double alpha,
                                     double width, double height,
                                     MomentEvaluation evaluation = MomentEvaluation::quadrature);
double theta_at_travel(double travel, double alpha, double width, double height,
                       MomentEvaluation evaluation = MomentEvaluation::quadrature);
double travel_at_theta(double theta, double alpha, double width, double height,
                       MomentEvaluation evaluation = MomentEvaluation::quadrature);

// Matsui's element law (M21) for n_w x n_h square elements: the rate is m21_rate(psi, W, H, n_w,
// n_h).
double theta_at_travel_m21(double travel, double alpha, double width, double height, int n_w,
                           int n_h);

}  // namespace ref
