#pragma once
// The case a run actually uses, in SI with every default filled in (summary.json "resolved_case",
// `dem2d check`): integrator, velocity start, per contact law the displacement increments, segment
// positions, end rule, onset, damping; the elements' count and total mass; walls, outputs with their
// units, stop rules, probes with their units.
#include <string>

#include <nlohmann/json.hpp>

#include "dem/cases/case_file.hpp"

namespace dem {

/// The resolved case in SI (units in the key names' comments of cases/README.md; every length m,
/// time s, force N, stiffness N/m, pressure Pa, damping N·s/m, angle rad).
nlohmann::json resolved_case_si(const Case& c);

/// The SI unit of a probe's value: the quantity's unit, s for time_of_* / crossing / contact_duration,
/// the quantity's unit per s (or per the `against` quantity's unit) for a slope, 1 for restitution.
std::string probe_unit(const ProbeSpec& p);

/// Total mass of the active elements [kg].
double total_mass(const Model& m);

}  // namespace dem
