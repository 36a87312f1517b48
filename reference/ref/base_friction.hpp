#pragma once
// Base-friction model (refs §3): a rigid W x H block toppling about its down-slope base corner P on
// a plate that slides under it with velocity V_B = v ĝ (v = |v_B|, ĝ the "virtual gravity"). Bray &
// Goodman's (1981) rotation rate from the moment balance about P, written as Matsui's M25 (the first
// of the paper's two equations (25)), and the sliding relation M22.
//
// Geometry (refs §3.1). Block coordinates from the pivot P: w along the base face (up-slope, 0..W),
// h along the height (0..H). psi = alpha + theta is the tilt of the base face to the horizontal.
// For a point ρ = (w, h):
//   T = (ρ x ĝ)_z in the paper's hand  = w cos psi - h sin psi,   R² = w² + h².
// Uniform Coulomb traction τ = -μ_B p (V - V_B)/|V - V_B| with V = Ω ẑ x ρ (rotation about P; the slope
// reacts only at P). Its moment about P vanishes; with λ = θ'/v_B (v_B < 0 the signed plate
// velocity, so λ < 0 while toppling) this reads
//   F(λ; psi) = ∫₀^H ∫₀^W (T - λR²) / sqrt(1 - 2Tλ + λ²R²) dw dh = 0                          (M25)
// μ_B, v, mass and thickness drop out: the motion is pure geometry, dθ/dδ_B = -λ = |λ| with δ_B the
// plate travel, and it depends on psi only.
//
// Units: SI inside (lengths in m, λ in 1/m, F in m³, angles in rad).

namespace ref {

// Default tolerance of the nested quadrature of F (refs §3.2): epsrel = tolerance and
// epsabs = tolerance · W·H·max(W, H).
inline constexpr double base_friction_quadrature_tolerance = 1e-11;

// F(λ; psi, W, H) of (M25) by nested adaptive GSL quadrature (GAUSS61 inner over w, outer over h;
// when the instantaneous centre (w0, h0) = (cos psi, -sin psi)/λ lies inside the block it is passed
// as a break point to both levels, qagp). Any finite λ (1/m) and psi (rad); W, H > 0 (m). Result in
// m³. Accuracy: |error| ≲ tolerance · W·H·max(W, H) (checked against the closed form to ≲ 1e-12 of
// that scale). Throws std::invalid_argument for bad input, std::runtime_error if GSL fails.
double base_friction_moment(double lambda, double psi, double width, double height,
                            double tolerance = base_friction_quadrature_tolerance);

// The same F by an independent route (refs §3.2): the relative velocity is a rotation about the
// instantaneous centre ρ0, so with d = ρ - ρ0
//   F = -sgn(λ) [ ∬ |d| dA + ρ0 · ∬ d/|d| dA ],
// both by closed-form rectangle antiderivatives; fixed high-order Gauss-Legendre where |λ|·max(W,H)
// is small and the closed form would cancel. Accuracy: ≲ 1e-13 · W·H·max(W, H).
double base_friction_moment_closed_form(double lambda, double psi, double width, double height);

// How λ evaluates F: the nested quadrature (the reference route of refs §3.2) or the closed form
// (same accuracy, ~1000x faster; the unit tests check that the two give the same λ to ~1e-11).
enum class MomentEvaluation { quadrature, closed_form };

// λ(psi; W, H) (1/m, <= 0), the root of (M25). 0 when F(0) >= 0, i.e. tan psi <= W/H (the block
// rests on its base; the positive root would be a rotation into the slope). Otherwise the unique
// negative root (F is non-increasing in λ, refs §3.2), bracketed by λ_lo = -2^k/H (k = 0, 1, ...)
// and solved with GSL Brent to a relative 1e-12. psi in [0, pi] rad. Accuracy: ~1e-11 relative
// (limited by F). Cost: ~0.1-1 ms with quadrature, up to ~20 ms while ρ0 lies inside the block
// (90° < psi < 118° for W/H = 1/3); ~10 µs closed form.
double base_friction_lambda(double psi, double width, double height,
                            MomentEvaluation evaluation = MomentEvaluation::quadrature);

// dθ/dδ_B = -λ = |λ| (rad/m), the rotation per unit plate travel (refs §3.1). Same accuracy.
double base_friction_rate(double psi, double width, double height,
                          MomentEvaluation evaluation = MomentEvaluation::quadrature);

// The sliding relation (M22), derived in refs §3.5: a block lying on its long face slides without
// rotating at δ/δ_B = sin alpha - tan phi_w cos alpha, whatever μ_B and v; 0 when that is <= 0 (the
// slope friction holds it). alpha in [0, pi/2], phi_w in [0, pi/2) rad. Accuracy: a few ulp.
double slide_ratio(double alpha, double wall_friction_angle);

}  // namespace ref
