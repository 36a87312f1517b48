#pragma once
// The time-step guard of a bonded structure from the largest eigenvalue of its assembled stiffness
// and damping (docs/model.md §1 "Time step of a bonded structure", G1–G7); the Gershgorin guard of
// stability.hpp stays the bound for everything that is not bonded at the start (a silo's disks).
#include <cstdint>
#include <vector>

#include "dem/core/model.hpp"
#include "dem/core/stability.hpp"

namespace dem {

/// One spring of the start network, mass-normalised: its extension is bᵀx over the (up to two)
/// bodies' (x, y, φ) scaled by √m, √I; k its stiffness [N/m], eta its dashpot [N·s/m].
struct NetworkSpring {
  int dof_a = -1, dof_b = -1;  // first DOF of each body (3 per body), −1: ground (a wall, a fixed element)
  double ba[3] = {0, 0, 0}, bb[3] = {0, 0, 0};
  double k = 0.0, eta = 0.0;
  bool coulomb_shear = false;  // the shear spring of a linear (Coulomb) contact: only when sticking
};

/// The contacts present at the start as springs (G1), and which free elements are bonded.
struct StartNetwork {
  int dofs = 0;
  std::vector<NetworkSpring> springs;
  std::vector<std::uint8_t> bonded;  // per element: has a bonded face contact at the start
  bool any_bond = false;
  double hopf = 0.0;                 // smallest η/K over the springs (K19's Hopf branch), sliding
  double hopf_stick = 0.0;           // the same with the Coulomb shear springs
  std::vector<int> dof;              // per element: its first DOF, −1 if it has none (ground)
  // (G5) per DOF, a mass-normalised diagonal term added to the springs' matrix (the contacts a bonded
  // element can still form, bounded by their row share): stiffness [1/s²] and damping [1/s], without and
  // with the Coulomb shear springs; empty: none
  std::vector<double> diag_k, diag_c, diag_k_stick, diag_c_stick;
};
/// `only` (optional, per element): the free elements that keep their degrees of freedom; the others
/// are ground, their springs acting on their partners alone (the bonded block of (G5)).
StartNetwork start_network(const Model& m, const std::vector<std::uint8_t>* only = nullptr);

/// (G6) Per element: whether a contact with a new partner can form beside what keeps its place (its bonded
/// partners, the fixed elements and static walls it touches), i.e. whether some angular gap between those
/// holds the new one's direction with each of them turned by up to `kStartTurn` towards it. New partners:
/// elements of radius `new_radius` (the smallest that can come; +inf: none), and the walls within reach
/// (G7: a static wall within r + R, a moving one within r + R + its drive's fastest speed × the duration;
/// every wall without numerics.guard_reach), a segment's face as a wall and its ends and point walls as
/// points (radius 0). Separations as the row-sum bound has them (overlaps ≤ 1 % of a radius): two elements
/// of radii ρ_a, ρ_b around one of radius r at least acos(((r+ρ_a)² + (r+ρ_b)² − ((1−ε)(ρ_a+ρ_b))²) /
/// (2(r+ρ_a)(r+ρ_b))) apart, an element and a segment wall acos((r − (1−ε)ρ)/(r+ρ)), two walls 0.
std::vector<std::uint8_t> angular_room(const Model& m, double new_radius);
inline constexpr double kStartTurn = 0.0174532925199432958;  // 1° [rad]
inline constexpr double kGuardOverlap = 0.01;                 // ε: the largest overlap the guard assumes, × a radius

/// λ_max of Σ (Δt² k + 2Δt η) b bᵀ (G2) over the springs (Coulomb shear springs only if `sticking`),
/// by Lanczos with full reorthogonalisation, plus its residual bound (an upper estimate).
double network_rate(const StartNetwork& net, double dt, bool sticking);
/// λ_max of Σ w b bᵀ with w = k (`damping` false) or η: the mass-normalised stiffness [1/s²] or damping [1/s].
double network_eigenvalue(const StartNetwork& net, bool damping, bool sticking);

/// The largest Δt with λ_max(Δt²A + 2ΔtC) + Δt²λ_new + 2Δt c_new < κ (κ = 4 for K18, 12 for K19)
/// and, for K19, Δt < the smallest η/K (G3, G4), by bisection to a relative 1e-4 (the stable end); `lambda_new`,
/// `c_new`, `hopf_new`: the rates of the contacts that can still form. `solves` (optional): adds the number
/// of Lanczos solves made (two for the bracket, one per regula falsi step).
double eigen_limit(const StartNetwork& net, Integrator integrator, bool sticking, double lambda_new, double c_new,
                   double hopf_new, int* solves = nullptr);

}  // namespace dem
