#pragma once
// Unilateral (no-tension) contacts in a linear rigid-spring network: the active-set solve.
//
// A unilateral contact is a normal spring that can only push (Cundall's disk contact, docs/model.md
// K8: no tension) and, optionally, a tangential spring that acts only while the normal one does. The
// static answer is the solution of the linear complementarity problem
//     f_c ≤ 0 (compression),  g_c ≥ 0 (gap: the normal extension of an open contact),  f_c g_c = 0,
// found by a primal active-set iteration: solve with every contact closed; open the closed contacts
// in tension (f > 0, the largest first); close the open ones whose extension is negative (they would
// penetrate); re-solve; stop when no closed contact pulls and no open contact penetrates. For a
// positive-definite stiffness the LCP has exactly one solution, and it satisfies these two conditions.
// Tolerances: a force is "tension" above tol·max|f| and an extension "penetration" below −tol·max|u|
// (roundoff of the direct solve, tol = 1e-12).
#include <vector>

#include "ref/lattice_beam.hpp"

namespace ref {

struct UnilateralContact {
  int normal = -1;      // spring index in the network (tension > 0, extension > 0 separates)
  int tangential = -1;  // its tangential spring, or −1
};

struct NoTensionSolution {
  std::vector<double> u;            // displacements (3 per body)
  std::vector<bool> open;           // per contact: left open (carries nothing)
  int iterations = 0;               // linear solves
};

// Solves the network with the given contacts unilateral; the other springs stay linear. Leaves every
// contact's springs active or not as in the answer. Throws if the iteration does not settle in
// 4·(contacts + 1) solves or a solve is singular (e.g. opening a contact frees a rigid mode).
NoTensionSolution solve_no_tension(RigidSpringNetwork& net, const std::vector<UnilateralContact>& contacts);

}  // namespace ref
