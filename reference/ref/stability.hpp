#pragma once
// Exact stability limits of Kiyama's two explicit cycles for one damped contact (refs §1.4-1.5),
// their amplification matrices, an independent spectral-radius bisection, and the first-order
// numerical damping of the modified equation.
// W = omega0 dt is the dimensionless time step, zeta the damping ratio of the contact.

#include <Eigen/Dense>

#include "ref/oscillator.hpp"

namespace ref {

enum class Scheme {
  K18,  // Cundall: dx_{k+1} = v_k dt (symplectic Euler, dashpot on the lagged velocity)
  K19,  // Kiyama: dx_{k+1} = (dx_k + v_k dt)/2 (averaged increment)
};

// Closed-form limit W* (stable iff W < W*), zeta >= 0 (refs §1.5):
//   K18: 2(sqrt(1 + zeta^2) - zeta), evaluated as 2/(sqrt(1 + zeta^2) + zeta);
//   K19: min(2 zeta, 2(sqrt(zeta^2 + 3) - zeta)), the second as 6/(sqrt(zeta^2 + 3) + zeta).
// Accuracy: a few ulp.
double stability_limit(Scheme scheme, double damping_ratio);

// The same limit in seconds for a mass m on a spring K with a dashpot eta: W*/omega0.
// Accuracy: a few ulp.
double stability_limit_time_step(Scheme scheme, const Oscillator& contact);

// Kiyama's time-step rule dt < eta/K (K26). For zeta <= 1 it equals the K19 limit (refs §1.5).
double kiyama_time_step_limit(double stiffness, double damping);

// One step of the cycle of refs §1.4 in p = v dt, q = dx (refs §1.5):
//   K18 acts on (x_k, p_{k-1}); K19 on (x_k, p_{k-1}, q_k). Exact (entries are polynomials in W).
Eigen::Matrix2d amplification_matrix_K18(double W, double damping_ratio);
Eigen::Matrix3d amplification_matrix_K19(double W, double damping_ratio);
Eigen::MatrixXd amplification_matrix(Scheme scheme, double W, double damping_ratio);

// Largest eigenvalue modulus (Eigen::EigenSolver). Accuracy: ~eps ||A|| / (eigenvalue separation);
// poor only next to a defective eigenvalue (K19 as W -> 0, where the pair meets at 1).
double spectral_radius(const Eigen::MatrixXd& matrix);

// The limit found numerically: bisection on W in [0, 4] for the first W with spectral radius
// > 1 + 1e-12, to an interval width of `tolerance`. Independent of stability_limit().
// Accuracy: ~tolerance + 1e-11 where the crossing is transversal (every zeta > 0 for K18; zeta >~
// 0.01 for K19). For K19 at zeta = 0 (true limit 0) it returns a value below ~1e-5, the resolution
// of the spectral radius of the near-defective pair.
double stability_limit_spectral(Scheme scheme, double damping_ratio, double tolerance = 1e-12);

// Decay rate of the discrete solution in units of omega0 (modified equation, refs §1.5), first
// order in W:  K18: zeta + zeta^2 W;  K19: zeta - (1 - 6 zeta^2) W / 2.  Error O(W^2).
double numerical_damping_ratio(Scheme scheme, double damping_ratio, double W);

}  // namespace ref
