#pragma once
// Stability limits of the two explicit schemes (references.md §1.5) and the time-step guard for a
// whole assembly (model.md §1 "Time step", §2 (M26); references.md §4.6).
#include "dem/core/model.hpp"

namespace dem {

/// Exact limit on W = ω₀Δt of one mass on a spring–dashpot with damping ratio ζ.
/// K18: W < 2(√(1+ζ²) − ζ). K19: W < min(2ζ, 2(√(ζ²+3) − ζ)) — zero without damping.
double stable_w(Integrator integrator, double zeta);

/// Δt limit of one mass m on a spring K with dashpot η [s].
double stable_dt(Integrator integrator, double mass, double stiffness, double eta);

/// Δt limit of an assembly from per-element Gershgorin bounds (stability.cpp says how):
/// `stiffness_row` λ_i ≥ largest eigenvalue share of element i in M^{-1/2} K M^{-1/2}, `damping_row`
/// the same for the dashpots. Returns +inf when λ_i = 0.
double stable_dt_gershgorin(Integrator integrator, double stiffness_row, double damping_row);

}  // namespace dem
