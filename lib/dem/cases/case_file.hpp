#pragma once
// Case files: one TOML file describes a run (cases/README.md documents every key). Values are SI
// numbers or strings with units ("25 mm", "12 kN/mm"). Every key can be overridden from the command
// line (`--set numerics.dt=1e-7`, `--set "contact.0.kn=12 kN/mm"`). Every error is reported before
// anything runs, as `file:line: key: what was expected`.
#include <filesystem>
#include <optional>
#include <string_view>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dem/core/model.hpp"
#include "dem/core/stability.hpp"

namespace dem {

class CaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ProbeKind { value, max, min, mean, time_of_max, time_of_min, crossing, slope, restitution, contact_duration, ratio };

/// A quantity of interest computed during a run (written to summary.json under "probes").
struct ProbeSpec {
  std::string name;
  std::string location;          // "file:line" of the probe (or its quantity), for errors
  ProbeKind kind = ProbeKind::value;
  std::string quantity;          // value/max/min/mean/time_of_*/crossing/slope: a series quantity name
  std::optional<double> at;      // value: time [s] (linear interpolation); none: end of run
  double from = 0.0, to = 0.0;   // slope: least-squares slope dq/dt over from ≤ t ≤ to [s]; max, min,
                                 // mean, time_of_*, crossing: the window (to = +inf: to the end)
  double level = 0.0;            // crossing: the level [SI units of the quantity]
  int direction = 0;             // crossing: +1 upwards, −1 downwards, 0 either
  std::string against;           // slope: dq/dx against this quantity instead of t (e.g. a stiffness)
  std::string of, over;          // ratio: probe `of` / probe `over` (two probes declared before it), e.g. a
                                 // dynamic wall force over the static one (a silo's overpressure)
  std::uint32_t element = 0;     // restitution / contact_duration: element i
  std::uint32_t other = 0;       //   and element j or wall j
  bool other_is_wall = false;
};

struct OutputSpec {
  std::int64_t every = 0;              // write a series row every this many steps (0: only first/last)
  std::vector<std::string> series;     // quantity names (quantities.hpp lists them)
  std::vector<std::string> series_locations;  // "file:line" of each name, for errors
  std::int64_t vtk_every = 0;          // snapshot every this many steps (0: first and last only)
  bool vtk = true;
  // Contact-force network pictures (PNG, run/picture/force_network.hpp) in pictures/: at the first and
  // the last step if `pictures`, every `picture_every` [s] and at each of `picture_times` [s] (the first
  // step at or after the time).
  bool pictures = false;
  double picture_every = 0.0;           // [s], 0: none
  std::vector<double> picture_times;    // [s], increasing
  std::int64_t picture_width = 800;     // [px]
  std::optional<double> picture_max_force;  // [N] drawn at the largest line width; none: each picture's largest
  bool any_pictures() const { return pictures || picture_every > 0.0 || !picture_times.empty(); }
  // wall_contacts.csv at the end of the run: every contact of these walls, one row each (a silo's
  // wall-force profile per contact, run/wall_contacts_csv.hpp); indices into Model::walls
  std::vector<std::string> wall_contacts;
  std::vector<std::uint32_t> wall_contact_walls;
  // bond_breaks.csv: every bonded PRE link that breaks in tension (M8), when, where (core/bond_breaks.cpp, run/run_outputs.cpp);
  // the pictures mark them
  bool bond_breaks = false;
  // dump.lammpstrj: the elements in LAMMPS' `dump custom` format at each series row (run/lammps_dump.hpp)
  bool lammps_dump = false;
  // contacts.csv: every contact (ids, point, normal, fn, fs, PRE segment links) at the first and the last
  // step and every `contacts_every` steps (0: first and last only) (run/contacts_csv.hpp)
  bool contacts = false;
  std::int64_t contacts_every = 0;
};

/// When a run counts as settled (run.cpp): every criterion given must hold at every step of a window
/// of `settle_window` consecutive steps (not before `settle_min_time`).
struct StopSpec {
  std::optional<double> settled_increment;         // mean |Δu|, |Δv| per step below this [m]
  std::optional<double> settled_increment_factor;  // Kiyama: mean |Δu|, |Δv| below factor·Δt²·|g|
  std::optional<double> settled_force_ratio;       // mean |resultant| / mean |contact force| below this
  std::int64_t settle_window = 1000;               // steps
  double settle_min_time = 0.0;                    // not before this time [s]
  bool any() const { return settled_increment || settled_increment_factor || settled_force_ratio; }
  // after_peak: stop once |q| has fallen below (1 − drop) × its largest |q| so far (a load past its
  // peak, e.g. the platen force of a bending test).
  std::string after_peak_quantity;                 // empty: no such criterion
  std::string after_peak_location;                 // "file:line" (or "--set …") of its quantity
  double after_peak_drop = 0.5;                    // fraction of the peak lost, in (0, 1)
  double after_peak_from = 0.0;                    // track the peak only from this time (skip start-up) [s]
};

/// The table of a case file that made a run of elements (check_case's errors name it).
struct ElementSource {
  std::size_t first = 0;  // its first element; it made every element up to the next source's first
  std::string location;   // "file:line" of the table
  std::string key;        // "element.3", "arrangement.0", …
};

struct Case {
  std::filesystem::path path;
  std::string title, source;
  Model model;
  OutputSpec output;
  StopSpec stop;
  std::vector<ProbeSpec> probes;
  std::vector<std::string> overrides;
  nlohmann::json resolved;  // the case after overrides, as read (for provenance)
  std::string dt_location;  // "file:line" (or "--set …") of numerics.dt, for the time-step error
  std::vector<ElementSource> element_sources;  // in element order
};

/// The table that made `element` ({0, the case file, ""} when none is known).
ElementSource element_source(const Case& c, std::size_t element);

/// Reads a case file and applies `key=value` overrides. Throws CaseError with file:line: key: ...
Case read_case(const std::filesystem::path& path, const std::vector<std::string>& overrides = {});

/// read_case of `text` as if it were the file `path` (the same errors, every location names `path`);
/// nothing is read from the file system (the fuzz targets).
Case read_case_text(std::string_view text, const std::filesystem::path& path,
                    const std::vector<std::string>& overrides = {});

/// Checks what can only be checked on the assembled model: initial overlaps, the time-step limit over
/// every contact the case can form. Throws CaseError. Returns the stability limit [s]; `bound`, if
/// given, receives what sets it and what it assumes.
double check_case(const Case& c, StabilityBound* bound = nullptr);

}  // namespace dem
