#pragma once
// Stability limits of the two explicit schemes (docs/references.md §1.5) and the time-step guard for a
// whole assembly (docs/model.md §1 "Time step", §2 (M26); docs/references.md §4.6).
#include <cstdint>
#include <string>
#include <vector>

#include "dem/core/model.hpp"

namespace dem {

/// Exact limit on W = ω₀Δt of one mass on a spring–dashpot with damping ratio ζ.
/// K18: W < 2(√(1+ζ²) − ζ); at ζ = 0 this is Cundall's rule (K21) read as Δt < 2√(m/K).
/// K19: W < min(2ζ, 2(√(ζ²+3) − ζ)) — zero without damping; for ζ ≤ 1 it is Kiyama's Δt < η/K (K26).
double stable_w(Integrator integrator, double zeta);

/// Δt limit of one mass m on a spring K with dashpot η [s].
double stable_dt(Integrator integrator, double mass, double stiffness, double eta);

/// Δt limit of an assembly from per-element Gershgorin bounds (stability.cpp says how):
/// `stiffness_row` λ_i ≥ largest eigenvalue share of element i in M^{-1/2} K M^{-1/2}, `damping_row`
/// the same for the dashpots. Returns +inf when λ_i = 0.
double stable_dt_gershgorin(Integrator integrator, double stiffness_row, double damping_row);

/// Δt limit of the modes of an assembly whose mass-normalised stiffness is at most λ [1/s²] and
/// damping at most c [1/s], every mode having c_mode/λ_mode ≥ `hopf_ratio` [s] (the smallest η/K of
/// its springs). K18: Δt < 4/(√(c² + 4λ) + c) (= 2(√(1+ζ²) − ζ)/ω, decreasing in λ and c);
/// K19: Δt < min(hopf_ratio, 12/(√(c² + 12λ) + c)) (the Hopf branch W < 2ζ, Δt < η/K, and the flip
/// branch W < 2(√(ζ²+3) − ζ)); refs §1.5. +inf when λ = c = 0.
double stable_dt_rates(Integrator integrator, double lambda, double c, double hopf_ratio);

/// Hook for physics beyond the contacts (base friction, a body force with an effective damping rate,
/// …): each term adds, per element, a mass-normalised stiffness rate [1/s²] and a damping rate [1/s]
/// to the element's translational degrees of freedom. Register new terms in
/// `registered_stability_terms` (stability.cpp); the guard adds them to every element's bound.
struct StabilityTerm {
  std::string source;             // what adds it, printed by `dem2d check` when it sets the limit
  std::vector<double> stiffness;  // per element [1/s²] (empty: none)
  std::vector<double> damping;    // per element [1/s] (empty: none)
  double hopf_ratio = 0.0;        // its c/λ [s] if it has stiffness (0: no stiffness)
};

/// Every extra term the model's physics registers: base friction's dashpot rates (base_friction.hpp).
std::vector<StabilityTerm> registered_stability_terms(const Model& m);

/// The time-step guard's answer: the limit, what sets it, and what it assumed.
struct StabilityBound {
  double limit = 0.0;           // [s] (+inf if no contact can form)
  double limit_sticking = 0.0;  // [s] also counting the shear springs of Coulomb (linear) contacts
  std::int64_t element = -1;    // the element that sets the limit
  std::string law;              // "contact 0 (sand–sand)" and walls: the laws in its worst arrangement
  int element_contacts = 0;     // contacts with elements assumed in that arrangement (its coordination)
  int wall_contacts = 0;        // contacts with walls assumed
  double stiffness_rate = 0.0;  // λ of the setting element [1/s²]
  double damping_rate = 0.0;    // c of the setting element [1/s]
  std::string assumptions;      // one paragraph, printed by `dem2d check`
  // Bonded structures (stability_eigen.hpp, docs/model.md (G1)–(G5)): `limit` is then the largest of
  // the row-sum limit, the eigenvalue bound of the start network plus the Gershgorin rates of the
  // unbonded free elements' classes (G4) and the block bound (G5); the row-sum (Gershgorin) limit alone
  // is kept here. Without bonds both equal `limit`.
  double limit_gershgorin = 0.0;           // [s]
  double limit_gershgorin_sticking = 0.0;  // [s]
  bool eigen = false;                      // `limit` is the eigenvalue bound
  double lambda_max = 0.0, c_max = 0.0;    // λ_max of the start network's mass-normalised K [1/s²], C [1/s]
  double limit_start = 0.0;                // [s] the start network alone, without the contacts that can form (G3)
  double limit_block = 0.0;                // [s] the block bound (G5); 0 when it does not apply
};

/// The Δt limit of every contact the case CAN form (stability.cpp states the bound and its
/// assumptions). `extra`: terms from other physics (registered_stability_terms).
StabilityBound assembly_stability_bound(const Model& m, const std::vector<StabilityTerm>& extra);

/// The same for a model with polygon elements (polygon_stability.cpp, docs/model.md (P9)); the assembly bound
/// hands such a model to it.
StabilityBound polygon_stability_bound(const Model& m, const std::vector<StabilityTerm>& extra);

}  // namespace dem
