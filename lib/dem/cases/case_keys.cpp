#include "dem/cases/case_keys.hpp"

namespace dem {

namespace {

using json = nlohmann::json;
namespace d = dims;

KeySpec base(std::string key, SpecKind kind, std::string desc, json fallback = nullptr) {
  KeySpec k;
  k.key = std::move(key);
  k.kind = kind;
  k.description = std::move(desc);
  k.fallback = std::move(fallback);
  return k;
}
KeySpec q(std::string key, std::vector<Dimension> ds, std::string desc, json fallback = nullptr) {
  KeySpec k = base(std::move(key), SpecKind::quantity, std::move(desc), std::move(fallback));
  k.dims = std::move(ds);
  return k;
}
KeySpec num(std::string key, std::string desc, json fallback = nullptr) {
  return base(std::move(key), SpecKind::number, std::move(desc), std::move(fallback));
}
KeySpec whole(std::string key, std::string desc, std::int64_t lo, std::optional<std::int64_t> hi, json fallback = nullptr) {
  KeySpec k = base(std::move(key), SpecKind::integer, std::move(desc), std::move(fallback));
  k.min = lo;
  k.max = hi;
  return k;
}
KeySpec flag(std::string key, std::string desc, bool fallback) {
  return base(std::move(key), SpecKind::boolean, std::move(desc), fallback);
}
KeySpec text(std::string key, std::string desc, json fallback = nullptr) {
  return base(std::move(key), SpecKind::string, std::move(desc), std::move(fallback));
}
KeySpec words(std::string key, std::vector<std::string> allowed, std::string desc, json fallback = nullptr) {
  KeySpec k = base(std::move(key), SpecKind::choice, std::move(desc), std::move(fallback));
  k.choices = std::move(allowed);
  return k;
}
/// vector, quantities, vectors: of `dim`; `length`: exactly this many entries (0: any).
KeySpec many(std::string key, SpecKind kind, Dimension dim, std::string desc, int length = 0, json fallback = nullptr) {
  KeySpec k = base(std::move(key), kind, std::move(desc), std::move(fallback));
  k.dims = {dim};
  k.length = length;
  return k;
}
KeySpec sub(std::string key, SpecKind kind, std::string table, std::string desc, std::vector<Dimension> ds = {}) {
  KeySpec k = base(std::move(key), kind, std::move(desc));
  k.table = std::move(table);
  k.dims = std::move(ds);
  return k;
}
KeySpec need(KeySpec k) {
  k.required = true;
  return k;
}

TableSpec top_level() {
  return {"", "A dem2d case: one TOML file describes one run (cases/README.md).", {
      need(sub("case", SpecKind::table, "case", "the title and the source")),
      sub("physics", SpecKind::table, "physics", "gravity and the element depth"),
      need(sub("material", SpecKind::tables, "material", "materials, by name (at least one)")),
      sub("drive", SpecKind::tables, "drive", "velocity histories, by name, for driven elements, walls and the base plate"),
      sub("base_friction", SpecKind::table, "base_friction", "a base-friction model (M21): the plate under the model"),
      sub("contact", SpecKind::tables, "contact", "the contact law of each material pair that can meet"),
      sub("element", SpecKind::tables, "element", "one element each"),
      sub("lattice", SpecKind::tables, "lattice", "a grid of elements, bonded by default"),
      sub("row", SpecKind::tables, "row", "elements in a line"),
      sub("arrangement", SpecKind::tables, "arrangement", "generated fills: ordered (Kiyama's (s-1)/s) or random"),
      sub("wall", SpecKind::tables, "wall", "segment and point walls"),
      need(sub("numerics", SpecKind::table, "numerics", "integrator, time step, duration, blow-up bounds")),
      sub("output", SpecKind::table, "output", "series, snapshots, pictures and other output files"),
      sub("discharge", SpecKind::table, "discharge", "a silo's discharge: the slit, the outlet line, the keystone rule"),
      sub("stop", SpecKind::table, "stop", "when a run counts as settled, or past its peak"),
      sub("probe", SpecKind::tables, "probe", "quantities of interest written to summary.json"),
  }};
}

std::vector<TableSpec> small_tables() {
  return {
      {"case", "The title and where the case comes from.", {
          need(text("title", "what the case is")),
          text("source", "where it comes from (paper, section)", ""),
      }},
      {"physics", "Gravity and the element depth.", {
          q("thickness", {d::length}, "the element depth l (2D: per unit thickness times l)", "1 m"),
          sub("gravity", SpecKind::vector_or_table, "physics.gravity",
              "gravity [gx, gy], or { magnitude, direction } (direction from +x); default none", {d::acceleration}),
      }},
      {"physics.gravity", "Gravity by magnitude and direction.", {
          need(q("magnitude", {d::acceleration}, "|g|")),
          need(q("direction", {d::angle}, "the direction of g from +x, e.g. \"-90 deg\"")),
      }},
      {"material", "A material, by name.", {
          need(text("name", "the material's name (unique)")),
          q("density", {d::density}, "the density ρ (mass = ρ · area · thickness); none: each element gives its mass"),
          num("base_friction", "μ_B of the base plate (M21); > 0 needs a [base_friction] table", 0.0),
      }},
      {"drive", "A velocity history, by name: constant, or piecewise linear in time.", {
          need(text("name", "the drive's name (unique)")),
          many("velocity", SpecKind::vector, d::velocity, "a constant velocity [vx, vy]"),
          many("times", SpecKind::quantities, d::time, "times of a piecewise linear history (strictly increasing)"),
          many("velocities", SpecKind::vectors, d::velocity, "[vx, vy] at each of `times`"),
      }},
      {"base_friction", "The base plate of a base-friction model (M21).", {
          sub("plate_velocity", SpecKind::vector_or_table, "base_friction.plate_velocity",
              "the plate's constant velocity [vx, vy] or { magnitude, direction }; or plate_drive", {d::velocity}),
          text("plate_drive", "a [[drive]] name: the plate's velocity history; or plate_velocity"),
          q("normal_gravity", {d::acceleration}, "g_B, the gravity pressing the model onto the plate", "9.80665 m/s^2"),
          need(q("regularisation_speed", {d::velocity}, "v_ε > 0: M21 uses max(V, v_ε) for the relative speed V")),
      }},
      {"base_friction.plate_velocity", "The plate velocity by magnitude and direction.", {
          need(q("magnitude", {d::velocity}, "|v_B|")),
          need(q("direction", {d::angle}, "the direction of v_B from +x")),
      }},
      {"contact.rolling", "Rolling resistance of a linear contact: an elastic–plastic spring–dashpot moment (R1–R6).", {
          need(num("friction", "μ_r: the moment is capped at μ_r R_r e_n (R4)")),
          q("stiffness", {d::energy / d::angle, d::force / d::angle}, "k_r [N*m/rad, or N/rad per unit thickness]; or stiffness_factor"),
          num("stiffness_factor", "β of k_r = β k_n μ_r² R_r² (R2; Ai et al.: 2.25); or stiffness"),
          num("damping_ratio", "ζ_r of the rolling dashpot C_r = 2 ζ_r √(I_r k_r) (R5)", 0.0),
      }},
      {"contact.gap", "Gap springs of a linear contact: bonds formed at the start between disks at most `distance` apart, in parallel with the contact law (B1–B5).", {
          need(q("distance", {d::length}, "pairs whose surface gap is at most this at the start are bonded (B1); may be 0")),
          need(q("kn", {d::stiffness}, "normal spring of the bond, in tension and compression (B2)")),
          need(q("ks", {d::stiffness}, "shear spring of the bond (B2)")),
          num("damping_ratio", "ζ of the bond's dashpots η = 2ζ√(m_eff k), normal and shear (B3)", 0.0),
          q("tensile_strength", {d::force}, "the bond breaks when its tension exceeds this (B4.a); none: never in tension"),
          q("shear_strength", {d::force}, "the bond breaks when its shear force exceeds this (B4.b); none: never in shear"),
          q("break_distance", {d::length}, "the bond breaks when the surface gap exceeds this (B4.c); none: never by distance"),
      }},
      {"contact.kn_from_elastic", "Kiyama's K_n per unit thickness from 2D elastic contact (K22.b, K23), times l.", {
          need(q("E", {d::pressure}, "Young's modulus")),
          need(num("nu", "Poisson's ratio, 0 <= nu < 0.5")),
          need(q("q", {d::force_per_length}, "the line load of the formula")),
          need(q("radius", {d::length}, "the r of the formula (equal disks)")),
          num("c", "the constant c of K23 (1.5 reproduces Kiyama's Table 1; 2/3 is K22.a-consistent)", 1.5),
          num("factor", "a factor on K_n (Kiyama's walls: 2)", 1.0),
      }},
      {"element.preload", "A static rigid rotation before the first step that loads the springs.", {
          need(q("rotation", {d::angle}, "the rotation")),
          need(many("about", SpecKind::vector, d::length, "the centre of the rotation [x, y]")),
      }},
      {"stop.after_peak", "Stop once |quantity| has fallen by `drop` below its largest value since `from`.", {
          need(text("quantity", "a series quantity name, e.g. \"platen.fy\"")),
          num("drop", "the fraction of the peak lost, in (0, 1)", 0.5),
          q("from", {d::time}, "track the peak from this time on (skips a start-up transient)", "0 s"),
      }},
  };
}

TableSpec contact_table() {
  return {"contact", "The contact law of one material pair: linear (Cundall, Kiyama) or face (Matsui's PRE).", {
      need(text("between", "")),  // replaced below: an array of two names
      words("law", {"linear", "face"}, "the contact law", "linear"),
      num("friction", "μ (Coulomb; for the face law tan φ of Mohr–Coulomb); or friction_angle", 0.0),
      q("friction_angle", {d::angle}, "φ, μ = tan φ; or friction"),
      num("damping_ratio", "ζ (h_n for the face law), on the mass of mass_basis; or eta_n", 0.0),
      words("mass_basis", {"reduced", "particle"}, "the mass of ζ: the pair's reduced mass or the particle's (Kiyama)", "reduced"),
      q("eta_n", {d::damping, d::damping_per_thickness}, "normal dashpot η_n [N·s/m, or Pa·s per unit thickness]; or damping_ratio"),
      q("eta_s", {d::damping, d::damping_per_thickness}, "shear dashpot η_s (with eta_n; default η_n √(K_s/K_n), K25)"),
      words("onset", {"increment", "overlap"}, "how a contact formed during the run starts", "increment"),
      q("kn", {d::stiffness, d::pressure}, "normal stiffness K_n (linear: N/m or Pa per unit thickness; face: N/m per segment)"),
      sub("kn_from_elastic", SpecKind::table, "contact.kn_from_elastic", "linear: Kiyama's K_n from E, nu, q, radius (K23); or kn"),
      q("ks", {d::stiffness, d::pressure}, "shear stiffness K_s; or ks_ratio (default 0)"),
      num("ks_ratio", "K_s / K_n (K24); or ks"),
      sub("rolling", SpecKind::table, "contact.rolling", "linear: rolling resistance (R1–R6), off if absent"),
      sub("gap", SpecKind::table, "contact.gap", "linear: gap springs between disks bonded at the start (B1–B5), off if absent"),
      words("end_rule", {"elastic", "total"}, "linear: Kiyama's K8 (elastic) or no attractive total force", "elastic"),
      words("positions", {"centres", "ends"}, "face: segment positions, M13.1 or M13.2 (ends: 2 segments)", "centres"),
      whole("segments", "face: the segment count N (default 1; 2 with positions = \"ends\")", 1, 8),
      words("normal_increment", {"exact", "linearised"}, "face: the normal displacement increment", "linearised"),
      words("tangential_increment", {"exact", "literal", "linearised", "hisatake"}, "face: the tangential displacement increment",
            "linearised"),
      q("tensile_strength", {d::pressure}, "face: the tensile strength of a bonded link", "0 Pa"),
      q("cohesion", {d::pressure}, "face: the cohesion of Mohr–Coulomb", "0 Pa"),
      flag("healing", "face: broken links bond again on contact", false),
      words("lever", {"wall_frame", "rotated_corner"},
            "face, walls only: segment forces act at the wall frame's face points (M19) or at the element's rotated corner (M19.r)",
            "wall_frame"),
      flag("bonded", "face: faces touching at the start are bonded (also with walls)", false),
      q("kn_modulus", {d::pressure}, "face: k_n per unit area per unit strain (M6); or kn"),
      q("ks_modulus", {d::pressure}, "face: k_s per unit area per unit strain, with kn_modulus (default 0)"),
  }};
}

/// The keys every element table has ([[element]], [[lattice]], [[row]], [[arrangement]]).
std::vector<KeySpec> element_keys(bool radius_required) {
  KeySpec radius = q("radius", {d::length}, radius_required ? "the element radius" : "the element radius (required unless shape = \"polygon\")");
  radius.required = radius_required;
  return {
      words("shape", {"disk", "pre", "polygon"}, "a disk, a pseudo-rectangle element (PRE), or a rigid convex polygon ([[element]], [[lattice]])", "disk"),
      need(text("material", "a [[material]] name")),
      radius,
      words("pre_mass", {"square", "disk"}, "pre: the mass and inertia of the square (M17) or the disk (M18)", "square"),
      q("mass", {d::mass}, "the mass (overrides ρ · area · l)"),
      words("motion", {"free", "fixed", "driven"}, "free, fixed, or driven by `drive`", "free"),
      text("drive", "a [[drive]] name (motion = \"driven\")"),
      many("velocity", SpecKind::vector, d::velocity, "the initial velocity [vx, vy]", 0, json::array({0.0, 0.0})),
      q("angular_velocity", {d::angular_velocity}, "the initial angular velocity", 0.0),
  };
}

std::vector<TableSpec> element_tables() {
  // [[element]] and [[lattice]] take polygons, which have no radius: the radius is required unless shape =
  // "polygon" (the schema says so with an if/else, case_schema.cpp)
  TableSpec element{"element", "One element.", element_keys(false)};
  element.keys.push_back(need(many("position", SpecKind::vector, d::length, "the centre [x, y]")));
  element.keys.push_back(q("rotation", {d::angle}, "the rotation", "0 deg"));
  element.keys.push_back(many("vertices", SpecKind::vectors, d::length, "polygon: the corners [[x, y], ...], counter-clockwise, relative to position"));
  element.keys.push_back(many("size", SpecKind::vector, d::length, "polygon: a rectangle [width, height] centred on position"));
  element.keys.push_back(sub("preload", SpecKind::table, "element.preload", "a static rigid rotation before the first step"));
  TableSpec lattice{"lattice", "columns × rows elements.", element_keys(false)};
  lattice.keys.push_back(need(many("origin", SpecKind::vector, d::length, "the centre of the first element")));
  lattice.keys.push_back(need(whole("columns", "elements along the lattice x axis", 1, 100000)));
  lattice.keys.push_back(need(whole("rows", "elements along the lattice y axis", 1, 100000)));
  lattice.keys.push_back(q("spacing", {d::length}, "the centre distance (default 2r)"));
  lattice.keys.push_back(q("rotation", {d::angle}, "the rotation of the lattice axes", "0 deg"));
  lattice.keys.push_back(flag("bonded", "the elements form one bonded group", true));
  lattice.keys.push_back(many("size", SpecKind::vector, d::length, "polygon: each rectangle [width, height] (they lie side by side)"));
  TableSpec row{"row", "count elements from start along step.", element_keys(true)};
  row.keys.push_back(need(many("start", SpecKind::vector, d::length, "the first centre")));
  row.keys.push_back(need(many("step", SpecKind::vector, d::length, "from one centre to the next")));
  row.keys.push_back(need(whole("count", "the element count", 1, 10000000)));
  TableSpec fill{"arrangement", "A generated fill (lib/dem/cases/generators.hpp).", element_keys(false)};
  fill.keys.insert(fill.keys.begin(), need(words("kind", {"ordered", "random"}, "Kiyama's (s-1)/s rows, or random addition")));
  for (KeySpec k : {whole("s", "ordered: disks in the bottom row", 2, 100000), q("left", {d::length}, "ordered: the left wall x"),
                    q("right", {d::length}, "ordered: the right wall x"), q("floor", {d::length}, "ordered: the floor y"),
                    q("gap", {d::length}, "the surface gap between neighbours (and to the walls)", "0 m"),
                    whole("rows", "ordered: the row count; or count_near", 1, 1000000),
                    whole("count_near", "ordered: the row count whose disk count is nearest this", 1, 20000000),
                    q("jitter", {d::length}, "ordered: a uniform random shift of every centre in [-jitter, jitter]", "0 m"),
                    whole("seed", "the random seed (splitmix64); random: required", 0, std::nullopt),
                    many("radius_range", SpecKind::quantities, d::length, "random: uniform radii [min, max]", 2),
                    many("radii", SpecKind::quantities, d::length, "random: the radii of a polydisperse fill, with fractions"),
                    KeySpec(base("fractions", SpecKind::numbers, "random: the number fraction of each of radii (sum 1)")),
                    many("region", SpecKind::vectors, d::length, "random: [[x0, y0], [x1, y1]], the lower-left and upper-right corners", 2),
                    whole("count", "random: the disk count", 1, 20000000)})
    fill.keys.push_back(k);
  return {element, lattice, row, fill};
}

std::vector<TableSpec> run_tables() {
  return {
      {"wall", "A segment or point wall.", {
          text("name", "the wall's name (unique; default wall<k>)"),
          words("type", {"segment", "point"}, "a segment (from, to) or a point (at)", "segment"),
          many("from", SpecKind::vector, d::length, "segment: one end"),
          many("to", SpecKind::vector, d::length, "segment: the other end"),
          many("at", SpecKind::vector, d::length, "point: the position"),
          need(text("material", "a [[material]] name")),
          text("drive", "a [[drive]] name: the wall moves with it"),
      }},
      {"numerics", "Integrator, time step, duration and blow-up bounds (docs/running.md).", {
          words("integrator", {"K18", "K19"}, "Kiyama's K18, or the averaged increment K19", "K18"),
          words("velocity_start", {"plain", "staggered"}, "v_-1 = v(0), or v(0) - a(0) dt/2", "plain"),
          need(q("dt", {d::time}, "the time step Δt")),
          need(q("duration", {d::time}, "the simulated time (at most 2^53 steps)")),
          q("skin", {d::length}, "the Verlet skin (default a quarter of the smallest radius)"),
          flag("allow_unstable", "run above the stability limit", false),
          q("energy_limit", {d::energy}, "replaces the automatic blow-up bound"),
          num("max_step_fraction", "blow-up when an element moves more than this times its radius in one step", 0.25),
          q("guard_reach", {d::length}, "the time-step guard's partners: those a free element reaches moving at most this far (default: all; docs/model.md G7)"),
          whole("reorder_every", "renumber elements in space every this many rebuilds (0: never; linear laws only)", 0,
                std::int64_t{1} << 40, 0),
      }},
      {"output", "Series, snapshots, pictures and other files of a run.", {
          base("every", SpecKind::interval, "series row interval: steps (500) or a time (\"1 ms\"); 0: first and last"),
          KeySpec(base("series", SpecKind::strings, "quantity names (lib/dem/run/quantities.hpp)")),
          flag("vtk", "write VTK snapshots", true),
          base("vtk_every", SpecKind::interval, "snapshot interval: steps or a time; 0: first and last only"),
          flag("lammps_dump", "write dump.lammpstrj (LAMMPS dump custom) at each series row", false),
          flag("contacts", "write contacts.csv: every contact at the first and last step (and every contacts_every)", false),
          base("contacts_every", SpecKind::interval, "contacts.csv interval: steps or a time; 0: first and last only"),
          flag("pictures", "force-network pictures at the first and last step", false),
          base("picture_every", SpecKind::interval, "a picture every this many steps or this time; 0: none"),
          many("picture_times", SpecKind::quantities, d::time, "pictures at these times (increasing)"),
          KeySpec(base("wall_contacts", SpecKind::strings, "segment wall names: wall_contacts.csv at the end")),
          flag("bond_breaks", "write bond_breaks.csv (PRE links broken in tension)", false),
          whole("picture_width", "picture width [px]", 64, 8000, 800),
          q("picture_max_force", {d::force}, "the force drawn at the widest line (default: each picture's largest)"),
      }},
      {"discharge", "A silo's discharge (lib/dem/core/discharge.hpp).", {
          need(text("slit", "the name of the fixed segment wall across the slit (opened)")),
          q("open_at", {d::time}, "when the slit opens", "0 s"),
          need(q("outlet_depth", {d::length}, "an element this far below the slit (along g) is removed and counted")),
          q("keystone_after", {d::time}, "remove a stalled arch's keystone after this long without discharge (0: never)", "0 s"),
      }},
      {"stop", "Stop when settled (every criterion given, over settle_window steps) or past a peak.", {
          q("settled_increment", {d::length}, "the mean |Δx|, |Δy| per step is below this"),
          num("settled_increment_factor", "Kiyama: the mean increment is below factor · Δt² · |g|"),
          num("settled_force_ratio", "the unbalanced-force ratio is below this"),
          whole("settle_window", "consecutive steps every criterion must hold", 1, std::int64_t{1} << 40, 1000),
          q("settle_min_time", {d::time}, "not before this time", "0 s"),
          sub("after_peak", SpecKind::table, "stop.after_peak", "stop past the peak of a quantity"),
      }},
      {"probe", "A quantity of interest in summary.json.", {
          need(text("name", "the probe's name (unique)")),
          words("kind", {"value", "max", "min", "mean", "time_of_max", "time_of_min", "crossing", "slope", "restitution",
                         "contact_duration", "ratio"}, "what is measured", "value"),
          text("quantity", "a series quantity name"),
          q("at", {d::time}, "value: at this time (default the end)"),
          q("from", {d::time}, "the window's start (slope: required)"),
          q("to", {d::time}, "the window's end (slope: required; default the end)"),
          text("against", "slope: against this quantity instead of t", ""),
          num("level", "crossing: the level (SI)"),
          words("direction", {"up", "down", "either"}, "crossing: the direction", "either"),
          whole("element", "restitution, contact_duration: element i", 0, std::nullopt),
          whole("other", "restitution, contact_duration: element j; or wall", 0, std::nullopt),
          text("wall", "restitution, contact_duration: a wall name; or other"),
          text("of", "ratio: the probe over `over`"),
          text("over", "ratio: the denominator probe"),
      }},
  };
}

std::vector<TableSpec> make_tables() {
  std::vector<TableSpec> all{top_level()};
  for (auto* part : {small_tables, element_tables, run_tables})
    for (TableSpec& t : part()) all.push_back(std::move(t));
  TableSpec contact = contact_table();
  contact.keys.front() = need(base("between", SpecKind::strings, "the two material names, e.g. [\"sand\", \"steel\"]"));
  contact.keys.front().length = 2;
  all.push_back(std::move(contact));
  return all;
}

}  // namespace

const KeySpec* TableSpec::find(const std::string& key) const {
  for (const KeySpec& k : keys)
    if (k.key == key) return &k;
  return nullptr;
}

const std::vector<TableSpec>& case_key_tables() {
  static const std::vector<TableSpec> tables = make_tables();
  return tables;
}

const TableSpec* find_case_table(const std::string& path) {
  for (const TableSpec& t : case_key_tables())
    if (t.path == path) return &t;
  return nullptr;
}

}  // namespace dem
