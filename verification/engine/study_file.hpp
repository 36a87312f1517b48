#pragma once
// A study file (verification/<name>/study.toml, documented in verification/README.md) as the study
// engine uses it: the base case, the variants, the refinement levels, bisection bounds or mode map, the
// checks with their references and tolerances, the figures and tables. read_study() reads it strictly,
// through the same table reader as a case (dem::TableReader): an unknown key, a wrong type or unit, a
// word that is not one of the allowed ones, a check that matches no variant, a tolerance that cannot
// fail or cannot pass, an unknown reference solver or a missing reference argument are refused as
// `file:line: key: what was expected` before anything runs.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "dem/cases/case_reader.hpp"
#include "engine/refinement_levels.hpp"
#include "engine/study_ensemble.hpp"
#include "engine/study_snapshots.hpp"

namespace ver {

enum class Kind { refinement, single, stability, mode_map };
enum class Expect { within, above, below };
enum class Trend { none, decreasing, increasing, toward_reference };

struct Variant {
  std::string label;
  std::vector<std::string> set;
  std::map<std::string, double> args;
};

struct Check {
  std::string probe, label, solver;
  std::optional<double> value;          // fixed reference value
  double offset = 0.0, scale = 1.0;     // reference = offset + scale × solver (e.g. a position from a displacement)
  std::map<std::string, double> args;
  double tolerance = 0.0;
  bool relative = false;
  std::string reason;
  std::optional<double> expected_order;
  double order_band = 0.0;
  std::vector<std::size_t> fit_levels;
  std::vector<std::string> only;
  Expect expect = Expect::within;
  bool compare_richardson = false;  // refinement: analyse without the reference, then compare the
                                    // Richardson extrapolation (not the finest level) with it
  Trend trend = Trend::none;        // a trend across the listed variants (in their order), no pinned value
  bool compare_each = false;        // refinement: every level against its own reference (level args), no order
  std::optional<double> assumed_order;  // refinement: Richardson/GCI with this order, not the observed one
  std::uint32_t line = 0;           // of the [[check]] in the study file
  // kind = single: the reference is this other variant's value of the same probe (a comparison of two
  // model choices, e.g. a slower loading; not an independent reference, so the reason must say why).
  std::string against_variant;
};

/// A figure from the time series of runs (the finest level of each listed variant), with an
/// optional reference curve evaluated at the same x values.
struct Figure {
  std::string id, title, xlabel, ylabel, x, y, solver, x_arg;
  double x_scale = 1.0, y_scale = 1.0, ref_scale = 1.0;
  bool y_from_start = false;  // plot y − y(0)
  std::int64_t every = 1;     // output.every of the runs that feed it
  std::vector<std::string> variants;
  std::map<std::string, double> args;
  bool logx = false, logy = false;
  double y_offset = 0.0;            // plot (y − y_offset) × y_scale
  bool y_minus_reference = false;   // plot y − reference at the same x (needs reference)
  std::vector<double> x_range, y_range;  // [lo, hi] in plotted units; empty: automatic
  // A figure of probe values across variants: x = the variant argument x_arg, y = the probe, one
  // curve per distinct value of group_arg (or one curve), plus the reference solver if given.
  std::string probe, group_arg, group_label;
  std::string y_relative_to;  // probe figure: each y over this variant's value of the probe (Fig. 10(c)'s cost ratio)
  std::int64_t reference_points = 0;   // > 1: the reference on a uniform grid of x_arg over the span
  bool reference_per_variant = false;  // series figure: one reference curve per variant (its own args)
  std::map<std::string, std::string> curve_labels;  // legend words per series quantity / solver
  std::vector<std::string> solvers;  // time-series figure: every reference solver (solver = the first)
  // A wall-contact profile (study_wall_profile.hpp): every contact of these walls at the end of each
  // variant's run against its depth; component "fn", "fs" or "mobilisation" (|fs| / (mu_w fn)).
  std::vector<std::string> walls;
  std::string component;
};

/// A table of probe values across variants: rows = variants (columns = the probes), or a pivot with
/// rows = distinct values of row_arg and columns = distinct values of column_arg (one probe).
struct TableDecl {
  std::string title, row_arg, column_arg, row_label, column_label;
  std::vector<std::string> probes, variants;
  double scale = 1.0;
};

struct Study {
  std::filesystem::path file;
  std::filesystem::path case_file;  // the base case, resolved relative to the study file's folder
  std::string name, title, requirement, reference_text, case_path, parameter, parameter_label;
  Kind kind = Kind::single;
  std::vector<std::string> set;
  std::vector<Variant> variants;
  Refinement refinement;            // kind = refinement: the levels, coarse → fine (refinement_levels.hpp)
  std::optional<Ensemble> ensemble; // kind = single: every variant as an ensemble of members (study_ensemble.hpp)
  double low = 0.0, high = 0.0, rel_tol = 1e-4;  // stability bisection
  std::vector<Check> checks;
  std::vector<Figure> figures;
  std::vector<TableDecl> tables;
  std::vector<Snapshot> snapshots;  // force-network pictures of runs (study_snapshots.hpp)
  nlohmann::json setup = nlohmann::json::object();
  // mode_map: block shapes (columns, rows) × friction angles × slope angles
  std::vector<std::pair<int, int>> blocks;
  std::vector<double> phis, alphas;  // [rad]
  double radius = 0.0, margin = 0.0, rotation_threshold = 0.0, slide_threshold = 0.0;
  int wall_contact = 1;
  // block = "lattice" (columns × rows bonded PREs), "polygon" (one polygon, element 0, of 2r·columns × 2r·rows)
  // or "rolling_disk" (one disk, element 0, with rolling resistance μ_r = columns/rows on contact `wall_contact`:
  // the disk that stays, in the rigid limit, exactly where the block stays; refs §7.4)
  enum class ModeBlock { lattice, polygon, rolling_disk } mode_block = ModeBlock::lattice;
};

/// The `setup` table of a study or sensitivity file (numbers and strings, shown in the report).
nlohmann::json read_setup(const dem::TableReader& r);

/// Reads and checks a study file; throws dem::CaseError "file:line: key: what was expected".
Study read_study(const std::filesystem::path& file);

/// Does check `c` apply to variant `v` (no `variants` list: every variant)?
bool applies(const Check& c, const Variant& v);

/// The words of a study kind in the file and in result.json.
const char* kind_word(Kind k);

/// The overrides of one mode-map grid point (study_mode_map.cpp): the study's `set`, then the block's
/// lattice (`blocks[block]`; with block = "polygon" the size and position of polygon element 0, its base on
/// the slope from x = 0 to x = b; with block = "rolling_disk" the rolling friction b/h), the slope angle α as the gravity direction, the friction angle φ of contact
/// `wall_contact`, the pivot probes; read_study reads the case with them for every block before anything runs.
std::vector<std::string> mode_map_sets(const Study& s, std::size_t block, double phi, double alpha);

}  // namespace ver
