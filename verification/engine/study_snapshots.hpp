#pragma once
// Snapshots: force-network pictures (lib/dem/run/picture/force_network.hpp) of runs that a study
// declares in [[snapshot]] tables, e.g. Kiyama's Fig. 6 (the settled network) or Fig. 8 (the discharge
// at five instants). After the study's runs the engine runs each listed variant once more with an output
// folder <study out>/snapshots/<id>/<variant slug>/ that holds only the pictures at the listed times
// (no VTK, a first and a last series row), or reuses that folder when the same run (code, resolved
// case, overrides) already wrote it; result.json lists them under "snapshots" (RESULT_FORMAT.md) and
// the report shows them as a captioned gallery.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "dem/cases/case_reader.hpp"

namespace ver {

struct Study;
struct StudyRun;

/// One [[snapshot]] table: the pictures of the listed variants at the listed times.
struct Snapshot {
  std::string id;                      // a plain word: the folder snapshots/<id>/
  std::string title;                   // the caption (which paper figure it answers)
  std::vector<std::string> variants;   // variant labels (empty: every variant)
  std::vector<double> times;           // [s], strictly increasing, within every listed variant's run
  bool end = false;                    // also the last step of the run ("end")
  std::optional<double> max_force;     // [N] |f_n| drawn at the widest line, one scale for all pictures;
                                       //   required when the snapshot has more than one picture
  std::int64_t width = 800;            // [px]
  std::uint32_t line = 0;              // of the [[snapshot]] table
};

/// Reads every [[snapshot]] table of a study file into s.snapshots (after its variants): an unknown
/// key, an id that is not a plain word or repeats, an unknown variant, a time without a time unit, a
/// time past the end of a variant's run (numerics.duration) are refused as file:line: key: what.
void read_snapshots(Study& s, const dem::TableReader& top, const std::string& file);

/// The run folder's name for a variant label: letters, digits, '.', '-' kept, anything else '_'.
std::string variant_slug(const std::string& label);

/// The overrides that make a run write only the pictures of `snap` (after the study's and variant's).
std::vector<std::string> snapshot_sets(const Snapshot& snap);

/// Runs (or reuses) the snapshot runs of the study and returns result.json's "snapshots" list:
/// {id, title, variant, at, time, step, file, max_force} per picture ("file" relative to the study
/// folder; null, with a "note", when the run did not reach the time).
nlohmann::json take_snapshots(StudyRun& run);

}  // namespace ver
