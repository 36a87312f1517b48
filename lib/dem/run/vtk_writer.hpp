#pragma once
// Snapshots ParaView opens: one VTK XML PolyData file (.vtp, binary: appended raw, UInt64 headers) per
// snapshot and a .pvd collection that lists them with their times. Each file holds
//   points: active element centres | PRE corners (4 per PRE) | wall end points | wall contact points
//   verts:  one per active element (kind 0), one per point wall (kind 1)
//   lines:  one per segment wall (kind 2), one per contact (kind 3): centre to centre, or centre to the
//           contact point r·n on the wall
//   polys:  the square of side 2r of each PRE, turned by its rotation (kind 4)
// Point data: radius (0 except at centres), disk_radius (0 for PREs: scale circle glyphs by it),
// rotation, velocity, force (the element's resultant force of the step), moment, element_id (−1: no
// element). Cell data: kind, element_id, other_element_id (contacts between elements), wall_id (walls
// and wall contacts; −1 otherwise), so that element and wall numbers never collide; normal_force,
// shear_force, force (a contact: the force of element i on j or on the wall, f_n n + f_s t; an element:
// its resultant; a wall: the force the elements exert on it), links (linked segments of a contact).
// Field data: TimeValue [s] and step.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "dem/core/simulation.hpp"

namespace dem {

void write_vtp(const std::filesystem::path& file, const Simulation& sim);
void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& snapshots);

}  // namespace dem
