#pragma once
// Housner's (1963) rigid rectangular block rocking on a rigid base without sliding (refs §2.4): a block of
// width 2b and height 2h, R = √(b² + h²), slenderness α = atan(b/h), I_o = (4/3) m R² about a base corner,
// p² = m g R / I_o = 3g/(4R). Released from rest on one corner at tilt θ₀ (0 < θ₀ < α), it turns back about
// that corner, I_o θ̈ = −m g R sin(α − θ), until its other corner strikes the base at θ = 0; the impact
// (instantaneous, inelastic, no bounce, no slip: angular momentum about the striking corner conserved) leaves
// ω₂ = r ω₁ with r = 1 − (2 m R²/I_o) sin²α = 1 − (3/2) sin²α, and the block rises on the new corner to the tilt
// θ₂ with cos(α − θ₂) = cos α + r² (cos(α − θ₀) − cos α). Lengths in m, angles in rad, g in m/s².

namespace ref {

// The time from release to the first impact, t₁ = ∫₀^θ₀ dθ/ω(θ), ω(θ)² = 2p² (cos(α − θ₀) − cos(α − θ)), by GSL's
// QAWS with the weight (θ₀ − θ)^(−1/2) (the integrable end-point singularity at release). Accuracy: 1e-12 relative.
double rocking_impact_time(double b, double h, double theta0, double g);

// Housner's linearised time to impact (small α): t₁ = acosh(1/(1 − θ₀/α))/p. For comparison only.
double rocking_impact_time_linear(double b, double h, double theta0, double g);

// |ω₁| at the impact: √(2p² (cos(α − θ₀) − cos α)) [rad/s]. Exact.
double rocking_impact_speed(double b, double h, double theta0, double g);

// Housner's coefficient of restitution of the angular velocity, r = 1 − (3/2) sin²α. Exact.
double rocking_restitution(double b, double h);

// The tilt θ₂ reached on the other corner after the first impact (≥ 0) [rad]. Exact.
double rocking_rebound_tilt(double b, double h, double theta0);

}  // namespace ref
