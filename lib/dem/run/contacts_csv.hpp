#pragma once
// contacts.csv: every contact at chosen steps ([output] contacts, contacts_every; cases/README.md), one
// row each, in the order of the VTK snapshots' contact lines (vtk_writer.hpp, contacts_in_id_order):
//   step,t [s],i,j,wall,law,x [m],y [m],nx,ny,fn [N],fs [N],links,segments,mr [N*m]
// i: the element's id; j: the other element's id, or −1 for a wall contact, whose wall is then named in
// `wall` (as [[wall]] names it; empty for two elements); law: linear (disks, K-law) or face (PRE, M-law);
// x, y: the contact point — two disks: the middle of the overlap on the line of centres; two PREs: the
// face centre, dividing the line of centres as r_i : r_j; a wall: the wall's point closest to the
// element's centre. nx, ny: the unit normal n from i towards j (or the wall). fn: the normal force,
// compression positive; fs: the shear force: the force of i on j (or on the wall) is fn n + fs t, with
// t = n turned by +90° = (−ny, nx) (for a PRE face the resultants P, Q of M12). links: the face's linked
// segments (1 for a linear contact). segments: one letter per segment of a face, in the order of ξ_i
// along t (M13), empty for a linear contact:
//   B  linked, bond intact (carries tension up to σ_t A/N and cohesion, M8–M10)
//   L  linked, no bond (broken and re-formed, or never bonded: compression and friction only)
//   o  not linked, bond intact (the segment's faces are apart, it never broke)
//   x  not linked, bond broken (opened in tension, M8)
// mr: the rolling moment on i (R6; on j the opposite), 0 for a contact whose law has no rolling resistance.
#include <string>

#include "dem/core/simulation.hpp"

namespace dem {

/// The header line.
std::string contacts_csv_header();
/// The rows of the current step (contact forces must be current: Simulation::contact_forces_current).
std::string contacts_csv_rows(const Simulation& sim);
/// The letters of a face's segments (above), in the order of ξ_i from i's side; `reversed`: from j's side.
std::string segment_letters(const Simulation::FaceSegments& f, bool reversed);

}  // namespace dem
