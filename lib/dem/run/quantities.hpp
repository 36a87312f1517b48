#pragma once
// Named quantities of a running simulation, for the time-series CSV and probes:
//   t, step, contacts, energy.kinetic, energy.potential, energy.elastic, energy.total,
//   mean_increment                     mean of |Δx| and |Δy| over active elements [m]
//   unbalanced_force_ratio             mean |resultant force| over free elements / mean |contact force|
//   e<i>.x|y|phi|vx|vy|omega|fx|fy|moment     element i (state after the step)
//   e<i>.px(a,b)  e<i>.py(a,b)        a body point at offset (a r, b r) in the element's frame [m]
//   e<i>.gap.<wall>  e<i>.gap.e<j>     surface gap (negative: overlap) [m]
//   e<i>.fn.<wall>   e<i>.fs.<wall>    contact normal / shear force with a wall (or e<j>) [N]
//   e<i>.links.<wall or e<j>>          linked segments of that contact (face law; 1 for linear)
//   <wall>.fx  <wall>.fy               force of the elements on the wall [N]
//   <wall>.x   <wall>.y                wall position (first end point) [m]
//   walls.fx  walls.fy                 force of the elements on all walls together [N]
//   discharged.count  discharged.mass  disks removed below a [discharge] outlet line, their mass [kg]
//   active.count  active.mass          elements still in the run, their mass [kg]
//   active.top                         highest point of the active elements, max(y + r) [m]
//   active.area_fraction(x0,x1,y0,y1)  area fraction of the active disks in a strip (fill_quantities.hpp)
//   <wall>.fn(s0,s1)  <wall>.fs(s0,s1) force of the contacts whose contact point lies in the band
//                                      s0 <= s < s1 along the wall (s [m] from its `from` end towards
//                                      `to`): normal part (compression positive) and tangential part
//                                      along from→to (the wall-force depth profile of a silo) [N]
//   <wall>.fn_max(s0,s1)               the largest normal force of a single contact in that band [N]
//                                      (a silo's per-contact overpressure; 0 if no contact)
//   box.vx(x0,x1,y0,y1)  box.vy(…)    mean velocity of the active free elements whose centre lies in the
//                                      box [x0,x1]×[y0,y1] [m] now, 0 if none (a silo's flow pattern) [m/s]
//   plate_travel                       base plate travel δ_B = ∫|v_B| dt (base friction, M21) [m]
//   plate_dx   plate_dy                base plate displacement since the start [m]
//   e<i>.corner_slide(α)               slide δ of element i's lower corner (−1,−1) down a slope inclined
//                                      at α degrees in the case's frame (M23, M24; 0: slope = x axis,
//                                      down-slope −x) since the start [m]
#include <functional>
#include <string>

#include "dem/core/simulation.hpp"

namespace dem {

using QuantityFn = std::function<double(const Simulation&)>;

/// Mean of |Δx| and |Δy| per step over the active free elements (Kiyama's static criterion) [m].
double mean_increment(const Simulation& s);

/// The unbalanced-force ratio as YADE's unbalancedForce() defines it: the mean over the active free
/// elements of |resultant force| (contacts and gravity, this step) divided by the mean over the
/// contacts that carry force of |contact force|. +inf when no contact carries force.
double unbalanced_force_ratio(const Simulation& s);

/// Compiles a quantity name against a model; throws std::invalid_argument naming what is wrong.
QuantityFn compile_quantity(const std::string& name, const Model& m);
/// Whether a quantity may read the contact forces of element–element contacts (Simulation::contact,
/// contact_force_sum): a run that reports it keeps them at every step (Simulation::keep_contact_forces).
bool reads_contact_forces(const std::string& name);

/// The SI unit of a quantity name (one compile_quantity accepts): "s", "m", "N", "J", "rad", "m/s",
/// "rad/s", "N*m", "1" (a count or a ratio); "unknown" for a name it does not know.
std::string quantity_unit(const std::string& name);

/// A series.csv header cell: the quantity and its unit, "e0.y [m]" (pandas reads it as one column name).
std::string series_header(const std::string& name);

/// The quantity name of a series.csv header cell: "e0.y [m]" → "e0.y" (a cell without a unit as is).
std::string series_column_name(const std::string& header_cell);

}  // namespace dem
