#pragma once
// wall_contacts.csv, written at the end of a run whose [output] names `wall_contacts` (cases/README.md):
// every contact of those walls, one row each, for a silo's wall-force profile per contact (refs §6.1):
//   wall,s [m],x [m],y [m],depth [m],fn [N],fs [N]
// s: distance of the contact point from the wall's `from` end along from→to; x, y: the contact point;
// depth: active.top − y (below the highest point of the fill, y up); fn: normal force, compression
// positive; fs: the force on the wall along from→to (a side wall from the floor up: the weight of the
// fill pulling it down gives fs < 0). Rows by wall in the order named, then by s.
#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"

namespace dem {

/// The file's text (header line and one row per contact).
std::string wall_contacts_csv(const Simulation& sim, const OutputSpec& o);

}  // namespace dem
