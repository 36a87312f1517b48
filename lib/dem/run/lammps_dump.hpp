#pragma once
// dump.lammpstrj: the elements in LAMMPS' `dump custom` text format, one frame per series row when the case
// asks for it ([output] lammps_dump = true; cases/README.md). OVITO and LAMMPS' own tools read it. A frame:
//   ITEM: TIMESTEP
//   <step>
//   ITEM: NUMBER OF ATOMS
//   <active elements>
//   ITEM: BOX BOUNDS ff ff pp
//   <xlo> <xhi>          the elements' bounding box (centre ± radius) in this frame [m]
//   <ylo> <yhi>
//   <zlo> <zhi>          ± half the model's thickness l [m] (2D: one layer)
//   ITEM: ATOMS id type x y vx vy omegaz radius fx fy
//   one line per active element, by id
// id = the element's dem2d id + 1 (LAMMPS numbers atoms from 1); type = its material's index + 1; x, y [m];
// vx, vy [m/s] and omegaz [rad/s] as the VTK snapshots write them (the velocity of the previous step,
// elements.hpp); radius [m] (a PRE: its core radius, half its side); fx, fy [N]: the force of the current
// step. LAMMPS names a 2D rotation rate `omegaz` (there is no `omega` attribute). SI units (LAMMPS `units si`).
#include <string>

#include "dem/core/simulation.hpp"

namespace dem {

/// One frame of the dump (the text above), for the state of `sim`.
std::string lammps_dump_frame(const Simulation& sim);

}  // namespace dem
