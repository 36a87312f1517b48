#pragma once
// A [[figure]] with `walls` (verification/README.md): the wall-contact profile of a silo at the end of each
// variant's run — every contact of the named walls, its force against its depth below the fill top
// (Kiyama's Fig. 7 per contact, refs §6.1) — read from the run's wall_contacts.csv (written by the run
// when the engine sets output.wall_contacts, lib/dem/run/wall_contacts_csv.hpp), with a reference
// solver per variant on a grid of depths.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/study_file.hpp"

namespace ver {

struct StudyRun;

/// One row of wall_contacts.csv.
struct WallContactRow {
  std::string wall;
  double s = 0.0, x = 0.0, y = 0.0, depth = 0.0, fn = 0.0, fs = 0.0;
};

/// Reads a wall_contacts.csv strictly: the header exactly as the run writes it, seven cells per row,
/// finite numbers, depth ≥ 0 up to round-off; throws std::runtime_error "file:line: what was expected".
std::vector<WallContactRow> read_wall_contacts_csv(const std::filesystem::path& file);

/// The plotted value of a contact: fn, fs (the force on the wall along from→to, as written), or the
/// friction mobilisation |fs| / (mu_w fn); nullopt for a mobilisation without normal force (fn ≤ 0).
std::optional<double> wall_profile_value(const WallContactRow& c, const std::string& component, double mu_w);

/// The DEM points of one run: x = depth × x_scale, y = value × y_scale, the contacts of f.walls only.
nlohmann::json wall_profile_points(const std::vector<WallContactRow>& rows, const Figure& f, double mu_w,
                                   const std::string& label);

/// Reads `component` of a figure that names `walls` and refuses what does not belong to it (y, probe,
/// y_from_start, y_minus_reference, group_arg, a reference without x_arg and reference_points > 1, a
/// reference or mobilisation argument missing for a selected variant): "file:line: key: what".
void read_wall_profile(Figure& f, const Study& s, const dem::TableReader& r, const toml::node& n);

/// The figure's curves: per selected variant its points and its reference curve; for the mobilisation
/// the line 1 (Janssen's full mobilisation).
nlohmann::json wall_profile_curves(const StudyRun& run, const Figure& f);

}  // namespace ver
