#pragma once
// The time-step guard of a bonded structure from the largest eigenvalue of its assembled stiffness
// and damping (docs/model.md §1 "Time step of a bonded structure", G1–G5); the Gershgorin guard of
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
};
/// `only` (optional, per element): the free elements that keep their degrees of freedom; the others
/// are ground, their springs acting on their partners alone (the bonded block of (G5)).
StartNetwork start_network(const Model& m, const std::vector<std::uint8_t>* only = nullptr);

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
