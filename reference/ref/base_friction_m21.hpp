#pragma once
// The quasi-static rotation rate that Matsui's per-element base-friction law (M21) gives a rigid
// W x H block made of n_w x n_h equal square elements (refs §3.7), for comparison with the exact
// uniform-friction rate of Bray & Goodman (ref/base_friction.hpp, M25).
//
// Same geometry and signs as ref/base_friction.hpp: block coordinates (w, h) from the down-slope base
// corner P, psi the tilt of the base face, λ = θ'/v_B (< 0 while toppling), dθ/dδ_B = -λ.
// Element e: centre c_e = ((i + 1/2) s, (j + 1/2) s), side s = W/n_w = H/n_h, radius r = s/2, mass
// m_e. M21 gives it, with S_e = sqrt(|V_e - V_B|² + (rΩ)²) and V_e = Ω ẑ x c_e,
//   force  -μ_B m_e g (V_e - V_B)/S_e   (at its centre),
//   moment -(2/3) μ_B m_e g r (rΩ)/S_e  (the disk's spin torque; a square's is 0.7652, refs §3.7).
// The slope reacts only at P; the moment about P vanishes. Dividing by μ_B g v_B (m_e ∝ s²):
//   F21(λ) = Σ_e s² [T_e - λ(|c_e|² + (2/3) r²)] / sqrt(1 - 2 T_e λ + λ²(|c_e|² + r²)) = 0   (M21)
// with T_e = c_w cos psi - c_h sin psi; F21 -> F of (M25) as the elements shrink. The root is the
// M21 rate λ21. Units SI (m, 1/m, rad).

namespace ref {

// F21(λ; psi, W, H, n_w, n_h) in m³ (same normalisation as base_friction_moment). Requires
// W/n_w = H/n_h (square elements) to 1e-9 relative, n_w, n_h >= 1. Accuracy: a few ulp per term.
double m21_moment(double lambda, double psi, double width, double height, int n_w, int n_h);

// λ21(psi) (1/m, <= 0): 0 when F21(0) = W H T_cm >= 0 (no toppling, the same condition as M25),
// else the root in [λ_lo, 0), λ_lo = -2^k/H doubled until F21(λ_lo) > 0 (F21(-∞) > 0), by GSL Brent
// to a relative 1e-13. psi in [0, pi]. Accuracy: ~1e-13 relative.
double m21_lambda(double psi, double width, double height, int n_w, int n_h);

// dθ/dδ_B = -λ21 (rad/m).
double m21_rate(double psi, double width, double height, int n_w, int n_h);

}  // namespace ref
