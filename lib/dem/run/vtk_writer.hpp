#pragma once
// Snapshots ParaView opens: one VTK XML PolyData file (.vtp) per snapshot with the elements as points
// (radius, velocity, rotation as point data; use a "Glyph" filter with scale by radius) and the
// contacts as lines between centres (or centre to wall point) with the normal and shear force as
// cell data, plus a .pvd collection that lists the snapshots with their times.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "dem/core/simulation.hpp"

namespace dem {

void write_vtp(const std::filesystem::path& file, const Simulation& sim);
void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& snapshots);

}  // namespace dem
