#pragma once
// Names that pandas and R users can type: an ASCII identifier for each parameter label ("Δt" → "dt",
// "K_s/K_n" → "K_s_K_n", "φ_w" → "phi_w") and the ASCII form of an SI unit ("kg/s²" → "kg/s^2",
// "kg·m/s²" → "kg*m/s^2"), for the headers of design.csv, runs.csv and indices.csv's `name` column.
#include <string>

namespace ver::sens {

/// Greek letters by name (Δ, δ as "d": Δt → dt, a difference), other characters not in [A-Za-z0-9_]
/// become "_", runs of "_" collapse, none at the ends; a leading digit gets "x" in front.
std::string ascii_name(const std::string& label);

/// The SI symbol form of dem::to_string (·, superscripts) in ASCII (*, ^n).
std::string ascii_unit(const std::string& si_unit);

}  // namespace ver::sens
