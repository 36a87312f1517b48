#pragma once
// Quantities of a granular fill as a whole (a silo's settled packing, refs §6.1), for series and probes:
//   active.top                          highest point of the active elements, max(y + r) [m]
//   active.area_fraction(x0,x1,y0,y1)   area of the active disks whose centre x lies in [x0, x1), cut
//                                       exactly by the lines y = y0 and y = y1 (circular segments),
//                                       over the rectangle's area (x1 − x0)(y1 − y0) [1]; a fill between
//                                       walls at x0 and x1 (no disk crosses them), every element a disk
// compile_quantity (quantities.hpp) hands these names here.
#include <optional>
#include <string>

#include "dem/core/simulation.hpp"
#include "dem/run/quantities.hpp"

namespace dem {

/// max(y + r) over the active elements; −inf when none is active.
double fill_top(const Simulation& s);

/// The area fraction of the active disks in the strip y0 ≤ y < y1 between x0 and x1 (see above).
double strip_area_fraction(const Simulation& s, double x0, double x1, double y0, double y1);

/// The area of a disk of radius r centred at height yc between the lines y = y0 and y = y1 (y0 < y1).
double disk_area_between(double yc, double r, double y0, double y1);

/// The quantity if `name` is one of the fill quantities above (nullopt otherwise); throws
/// std::invalid_argument with what is wrong for a malformed one (e.g. active.area_fraction(1,0,0,1)).
std::optional<QuantityFn> compile_fill_quantity(const std::string& name);

}  // namespace dem
