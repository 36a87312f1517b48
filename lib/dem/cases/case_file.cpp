#include "dem/cases/extent.hpp"
#include "dem/cases/case_file.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "dem/cases/case_reader.hpp"
#include "dem/cases/generators.hpp"
#include "dem/cases/text.hpp"
#include "dem/contact/constants.hpp"
#include "dem/core/simulation.hpp"

namespace dem {

namespace {

// ---- overrides --------------------------------------------------------------------------------

bool is_index(const std::string& s) {  // at most 9 digits: std::stoul cannot overflow
  return !s.empty() && s.size() <= 9 && s.find_first_not_of("0123456789") == std::string::npos;
}

/// The index `s` if it is one below `size`, else nothing (no overflow for long digit strings).
std::optional<std::size_t> index_below(const std::string& s, std::size_t size) {
  if (!is_index(s) || s.size() > 18) return std::nullopt;
  const auto v = static_cast<std::size_t>(std::stoull(s));
  if (v >= size) return std::nullopt;
  return v;
}

/// Applies `path=value` to the tree: value is parsed as a TOML value when it is one ("1e-6", "true",
/// "[1, 2]", "\"12 kN/mm\""), otherwise taken as a string ("12 kN/mm").
void apply_override(toml::table& root, const std::string& kv) {
  // One line: "v = 1\nx = 2" would read as the value 1 and a second key, silently dropped.
  if (const auto bad = kv.find_first_of("\n\r"); bad != std::string::npos) {
    std::string shown;
    for (char ch : kv) shown += ch == '\n' ? std::string("\\n") : ch == '\r' ? std::string("\\r") : std::string(1, ch);
    throw CaseError(fmt::format("--set {}: expected key=value on one line, found a line break at character {}", shown, bad + 1));
  }
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0)
    throw CaseError(fmt::format("--set {}: expected key=value, e.g. --set numerics.dt=1e-6", kv));
  const std::string path = kv.substr(0, eq), value = kv.substr(eq + 1);
  const std::string origin = "--set " + kv;
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value, origin);
  } catch (const toml::parse_error&) {
    std::string quoted;  // not a TOML value: take it as a string ("12 kN/mm")
    for (char ch : value) {
      if (ch == '"' || ch == '\\') quoted += '\\';
      quoted += ch;
    }
    try {
      parsed = toml::parse("v = \"" + quoted + "\"", origin);
    } catch (const toml::parse_error& e) {
      throw CaseError(fmt::format("{}: cannot read the value: {}", origin, e.description()));
    }
  }
  const auto parts = split(path, '.');
  toml::node* cur = &root;
  std::string so_far;
  for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
    const std::string& p = parts[k];
    so_far += (so_far.empty() ? "" : ".") + p;
    if (auto* arr = cur->as_array()) {
      const auto at = index_below(p, arr->size());
      if (!at) throw CaseError(fmt::format("{}: {}: expected an index below {} into this array", origin, so_far, arr->size()));
      cur = arr->get(*at);
    } else if (auto* tbl = cur->as_table()) {
      toml::node* next = tbl->get(p);
      if (!next) {
        // a table created by the override names the override as its source (errors inside it say
        // "--set …", not "file:0")
        toml::table made = toml::parse("t = {}", origin);
        made.get("t")->visit([&](auto& n) { tbl->insert(p, std::move(n)); });
        next = tbl->get(p);
      }
      cur = next;
    } else {
      throw CaseError(fmt::format("{}: {}: is a value, not a table", origin, so_far));
    }
  }
  const std::string& last = parts.back();
  toml::node* v = parsed.get("v");
  if (auto* tbl = cur->as_table()) {
    // move, not copy: toml++ keeps the source ("--set …") of a moved node only
    v->visit([&](auto& n) { tbl->insert_or_assign(last, std::move(n)); });
  } else if (auto* arr = cur->as_array(); arr && index_below(last, arr->size())) {
    const auto idx = *index_below(last, arr->size());
    v->visit([&](auto& n) { arr->replace(arr->begin() + static_cast<std::ptrdiff_t>(idx), std::move(n)); });
  } else if (cur->as_array()) {
    throw CaseError(fmt::format("{}: {}: expected an index below {} into this array", origin, path, cur->as_array()->size()));
  } else {
    throw CaseError(fmt::format("{}: {}: cannot set this path", origin, path));
  }
}

// ---- tables -----------------------------------------------------------------------------------

// Element limit of one case: ~0.6 kB per element (its arrays, neighbour candidates and about three
// contact slots), so 2e7 elements need about 12 GB.
constexpr std::int64_t kMaxElements = 20'000'000;

/// Refuses a point (a disk of `radius` at it) outside the represented extent (extent.hpp), at `key`.
void in_extent(const TableReader& r, const std::string& key, Vec2 p, double radius = 0.0) {
  if (!within_extent(p, radius)) r.fail(key, outside_extent(p, radius));
}
constexpr double kBytesPerElement = 600.0;

struct Reader {
  std::string file;
  Case& c;
  std::map<std::string, std::int32_t> material_index, drive_index, wall_index;
  std::int32_t next_group = 0;
  std::map<std::int32_t, std::string> rotated_lever_at;  // law index → "file:line: contact[k].lever" (M19.r)

  // The tables of a case file, one function each (defined below, after the helpers they call); read_case
  // calls them in the order of the file format, each table may refer to those before it.
  void read_case_table(const TableReader& top);
  void read_physics(const TableReader& top);
  void read_materials(const TableReader& top, std::vector<double>& base_mu, std::string& base_mu_line);
  void read_drives(const TableReader& top);
  void read_elements(const TableReader& top);
  void read_lattices(const TableReader& top);
  void read_rows(const TableReader& top);
  void read_walls(const TableReader& top);
  void check_laws_and_masses(const TableReader& top) const;
  void read_numerics(const TableReader& top);
  void read_output(const TableReader& top);
  void read_discharge(const TableReader& top);
  void read_stop(const TableReader& top);
  void read_probes(const TableReader& top);

  /// Iterates an array of tables `name` ([[name]] in TOML).
  template <class F>
  void each(const TableReader& top, const std::string& name, F&& f) {
    const toml::node* n = top.node(name);
    top.mark(name);
    if (!n) return;
    const toml::array* arr = n->as_array();
    if (!arr) top.fail(name, fmt::format("expected [[{}]] tables", name));
    for (std::size_t k = 0; k < arr->size(); ++k) {
      const toml::table* t = arr->get(k)->as_table();
      if (!t) top.fail(name, fmt::format("expected [[{}]] tables", name));
      TableReader r(*t, fmt::format("{}.{}", name, k), file);
      const std::size_t before = c.model.elements.size();
      f(r, k);
      r.finish();
      if (c.model.elements.size() > before)  // the table that made these elements, for check_case's errors
        c.element_sources.push_back({before, where(*t, file), fmt::format("{}.{}", name, k)});
    }
  }

  std::int32_t material(const TableReader& r, const std::string& key) {
    const std::string name = r.string(key);
    auto it = material_index.find(name);
    if (it == material_index.end()) r.fail(key, fmt::format("unknown material \"{}\" (declare it in [[material]])", name));
    return it->second;
  }

  /// Refuses a generator that would take the case past kMaxElements (before allocating anything).
  void room_for(const TableReader& r, const std::string& key, std::int64_t more) {
    const auto total = static_cast<std::int64_t>(c.model.elements.size()) + more;
    if (total > kMaxElements)
      r.fail(key, fmt::format("{} elements in all would need about {:.3g} GB ({} bytes per element with its contacts); "
                              "a case may have at most {} elements", total,
                              static_cast<double>(total) * kBytesPerElement * 1e-9, kBytesPerElement, kMaxElements));
  }

  void positive(const TableReader& r, const std::string& key, double v) {
    if (!(v > 0.0)) r.fail(key, fmt::format("must be positive, got {}", v));
  }
  void non_negative(const TableReader& r, const std::string& key, double v) {
    if (!(v >= 0.0)) r.fail(key, fmt::format("must not be negative, got {}", v));
  }

  /// rolling = { friction = 0.1, stiffness_factor = 2.25 | stiffness = "2e-3 N*m/rad", damping_ratio = 0.3 }:
  /// the rolling resistance of a linear contact (docs/model.md §4, R1–R6). `stiffness` in N·m/rad is taken
  /// as is, in N/rad (per unit thickness) times l.
  RollingLaw read_rolling(const TableReader& t, double l) {
    RollingLaw r;
    r.enabled = true;
    r.mu_r = t.number("friction");
    non_negative(t, "friction", r.mu_r);
    if (t.has("stiffness") == t.has("stiffness_factor"))
      t.fail_here("give exactly one of stiffness (k_r, N*m/rad) or stiffness_factor (β of k_r = β k_n μ_r² R_r², R2)");
    if (t.has("stiffness")) {
      auto [kr, dim] = t.quantity_either("stiffness", dims::energy / dims::angle, dims::force / dims::angle);
      r.kr = dim == dims::energy / dims::angle ? kr : kr * l;
      positive(t, "stiffness", r.kr);
    } else {
      r.stiffness_factor = t.number("stiffness_factor");
      positive(t, "stiffness_factor", r.stiffness_factor);
      if (!(r.mu_r > 0.0)) t.fail("stiffness_factor", "k_r = β k_n μ_r² R_r² is 0 with friction = 0: give friction > 0 or a stiffness");
    }
    r.damping_ratio = t.number("damping_ratio", 0.0);
    non_negative(t, "damping_ratio", r.damping_ratio);
    t.finish();
    return r;
  }

  /// gap = { distance = "0.1 mm", kn = "1e6 N/m", ks = "4e5 N/m", damping_ratio = 0.1, tensile_strength = "20 N",
  /// shear_strength = "20 N", break_distance = "0.05 mm" }: gap springs (B1–B5).
  GapSpringLaw read_gap(const TableReader& t) {
    GapSpringLaw g;
    g.enabled = true;
    g.distance = t.quantity("distance", dims::length);  // (B1)
    non_negative(t, "distance", g.distance);
    g.kn = t.quantity("kn", dims::stiffness);
    positive(t, "kn", g.kn);
    g.ks = t.quantity("ks", dims::stiffness);
    non_negative(t, "ks", g.ks);
    g.damping_ratio = t.number("damping_ratio", 0.0);
    non_negative(t, "damping_ratio", g.damping_ratio);
    if (t.has("tensile_strength")) {  // (B4.a); (B4.b) and (B4.c) below
      g.tensile_strength = t.quantity("tensile_strength", dims::force);
      positive(t, "tensile_strength", g.tensile_strength);
    }
    if (t.has("shear_strength")) {
      g.shear_strength = t.quantity("shear_strength", dims::force);
      positive(t, "shear_strength", g.shear_strength);
    }
    if (t.has("break_distance")) {
      g.break_gap = t.quantity("break_distance", dims::length);
      positive(t, "break_distance", g.break_gap);
    }
    t.finish();
    return g;
  }

  /// kn_from_elastic = { E = "750 kgf/cm^2", nu = 0.3, q = "0.068 kgf/cm", radius = "1 cm", c = 1.5,
  /// factor = 1 }: Kiyama's K_n per unit thickness [Pa] from the 2D elastic contact of two equal
  /// cylinders (K22.b, K23), times `factor` (Kiyama's walls: 2).
  double kn_from_elastic(const TableReader& t) {
    const double e = t.quantity("E", dims::pressure);
    positive(t, "E", e);
    const double nu = t.number("nu");
    if (!(nu >= 0.0 && nu < 0.5)) t.fail("nu", "expected Poisson's ratio 0 <= nu < 0.5");
    const double q = t.quantity("q", dims::force_per_length);
    positive(t, "q", q);
    const double radius = t.quantity("radius", dims::length);
    positive(t, "radius", radius);
    const double cc = t.number("c", 1.5);
    const double factor = t.number("factor", 1.0);
    positive(t, "factor", factor);
    const double kn = factor * hertz_2d_stiffness(e, nu, radius, q, cc);  // (K22.b, K23)
    if (!(kn > 0.0) || !std::isfinite(kn))
      t.fail("c", fmt::format("K23 gives no positive stiffness (c + 2 ln(4r/b) <= 0): {:.6g} Pa", kn));
    t.finish();
    return kn;
  }

  void read_contact(const TableReader& r) {
    Model& m = c.model;
    const toml::node* between = r.node("between");
    r.strings("between");
    const auto names = r.strings("between");
    if (!between || names.size() != 2) r.fail("between", "expected two material names, e.g. [\"sand\", \"steel\"]");
    std::int32_t ma = -1, mb = -1;
    for (int k = 0; k < 2; ++k) {
      auto it = material_index.find(names[static_cast<std::size_t>(k)]);
      if (it == material_index.end()) r.fail("between", fmt::format("unknown material \"{}\"", names[static_cast<std::size_t>(k)]));
      (k == 0 ? ma : mb) = it->second;
    }
    const std::size_t nm = m.materials.size();
    if (m.law_of_pair[static_cast<std::size_t>(ma) * nm + mb] >= 0)
      r.fail("between", fmt::format("the pair {} – {} already has a [[contact]]", names[0], names[1]));
    PairLaw law;
    const std::string kind = r.choice("law", {"linear", "face"}, "linear");
    law.kind = kind == "linear" ? LawKind::linear : LawKind::face;
    const double l = m.thickness;
    // friction: μ = tan φ (K28), also the tan φ of the face law's Mohr–Coulomb strength (M11)
    if (r.has("friction") && r.has("friction_angle")) r.fail("friction", "give either friction or friction_angle");
    double mu = r.has("friction_angle") ? std::tan(r.quantity("friction_angle", dims::angle)) : r.number("friction", 0.0);
    if (r.has("friction_angle")) {
      const double phi = std::atan(mu);
      if (!(phi >= 0.0 && phi < std::numbers::pi / 2)) r.fail("friction_angle", "expected 0 <= phi < 90 deg");
    }
    non_negative(r, r.has("friction") ? "friction" : "friction_angle", mu);
    // damping
    law.damping_from_ratio = !r.has("eta_n");
    if (law.damping_from_ratio) {
      law.damping_ratio = r.number("damping_ratio", 0.0);
      non_negative(r, "damping_ratio", law.damping_ratio);
      law.mass_basis = r.choice("mass_basis", {"reduced", "particle"}, "reduced") == "reduced" ? MassBasis::reduced : MassBasis::particle;
      if (r.has("eta_s")) r.fail("eta_s", "give eta_s only together with eta_n");
    } else {
      if (r.has("damping_ratio")) r.fail("damping_ratio", "give either damping_ratio or eta_n");
      auto [en, dn] = r.quantity_either("eta_n", dims::damping, dims::damping_per_thickness);
      law.eta_n = dn == dims::damping ? en : en * l;
      non_negative(r, "eta_n", law.eta_n);
    }
    law.onset = r.choice("onset", {"increment", "overlap"}, "increment") == "increment" ? Onset::increment : Onset::overlap;

    if (law.kind == LawKind::linear) {
      if (r.has("kn") == r.has("kn_from_elastic"))
        r.fail_here("give exactly one of kn or kn_from_elastic = { E, nu, q, radius, c, factor } (K23)");
      if (r.has("kn_from_elastic")) {
        law.linear.kn = kn_from_elastic(TableReader(*r.table("kn_from_elastic"), r.key_path("kn_from_elastic"), file)) * l;
      } else {
        auto [kn, dkn] = r.quantity_either("kn", dims::stiffness, dims::pressure);
        law.linear.kn = dkn == dims::stiffness ? kn : kn * l;  // a 2D stiffness per unit thickness × l
        positive(r, "kn", law.linear.kn);
      }
      if (r.has("ks") && r.has("ks_ratio")) r.fail("ks", "give either ks or ks_ratio");
      if (r.has("ks")) {
        auto [ks, dks] = r.quantity_either("ks", dims::stiffness, dims::pressure);
        law.linear.ks = dks == dims::stiffness ? ks : ks * l;
      } else {
        law.linear.ks = r.number("ks_ratio", 0.0) * law.linear.kn;  // (K24): K_s = s K_n
      }
      non_negative(r, r.has("ks") ? "ks" : "ks_ratio", law.linear.ks);
      law.linear.mu = mu;
      if (r.has("rolling")) law.rolling = read_rolling(TableReader(*r.table("rolling"), r.key_path("rolling"), file), l);
      if (r.has("gap")) law.gap = read_gap(TableReader(*r.table("gap"), r.key_path("gap"), file));
      law.linear.end_rule = r.choice("end_rule", {"elastic", "total"}, "elastic") == "elastic" ? EndRule::elastic : EndRule::total;
      if (!law.damping_from_ratio) {
        if (r.has("eta_s")) {
          auto [es, ds] = r.quantity_either("eta_s", dims::damping, dims::damping_per_thickness);
          law.eta_s = ds == dims::damping ? es : es * l;
        } else {
          law.eta_s = law.eta_n * std::sqrt(law.linear.ks / law.linear.kn);  // (K25.b): η_s = η_n √s
        }
      }
    } else {
      if (r.has("rolling")) r.fail("rolling", "rolling resistance is an option of the linear law (a PRE face resists rotation by its segments)");
      if (r.has("gap")) r.fail("gap", "gap springs are an option of the linear law (a PRE face bonds by its links: bond_at_start)");
      FaceLaw& f = law.face;
      f.positions = r.choice("positions", {"centres", "ends"}, "centres") == "centres" ? SegmentPositions::centres : SegmentPositions::ends;
      f.segments = static_cast<int>(r.integer("segments", 1, kMaxSegments, f.positions == SegmentPositions::ends ? 2 : 1));
      if (f.positions == SegmentPositions::ends && f.segments != 2)
        r.fail("segments", "face-end positions (M13.2) need exactly 2 segments");
      f.normal = r.choice("normal_increment", {"exact", "linearised"}, "linearised") == "exact" ? NormalIncrement::exact : NormalIncrement::linearised;
      const std::string tan = r.choice("tangential_increment", {"exact", "literal", "linearised", "hisatake"}, "linearised");
      f.tangential = tan == "exact" ? TangentialIncrement::exact : tan == "literal" ? TangentialIncrement::literal
                   : tan == "hisatake" ? TangentialIncrement::hisatake : TangentialIncrement::linearised;
      f.tensile_strength = r.quantity("tensile_strength", dims::pressure, 0.0);
      f.cohesion = r.quantity("cohesion", dims::pressure, 0.0);
      non_negative(r, "tensile_strength", f.tensile_strength);
      non_negative(r, "cohesion", f.cohesion);
      f.tan_phi = mu;
      f.healing = r.boolean("healing", false);
      if (r.choice("lever", {"wall_frame", "rotated_corner"}, "wall_frame") == "rotated_corner") {  // (M19), (M19.r)
        f.lever = FaceLever::rotated_corner;
        rotated_lever_at[static_cast<std::int32_t>(m.laws.size())] = fmt::format("{}: {}", where(*r.node("lever"), file), r.key_path("lever"));
      }
      law.bond_at_start = r.boolean("bonded", false);
      // springs: discrete per segment (N/m, M6.1, M6.2) or moduli k_n, k_s per unit area per unit strain
      // (Pa, M4, M5) that the face constants turn into K_n, K_s (M6.3, M6.4)
      if (r.has("kn") == r.has("kn_modulus")) r.fail_here("give exactly one of kn (per segment, N/m) or kn_modulus (Pa)");
      law.face_modulus = r.has("kn_modulus");
      law.face_kn = law.face_modulus ? r.quantity("kn_modulus", dims::pressure) : r.quantity("kn", dims::stiffness);
      positive(r, law.face_modulus ? "kn_modulus" : "kn", law.face_kn);
      const int given = int(r.has("ks")) + int(r.has("ks_ratio")) + int(r.has("ks_modulus"));
      if (given > 1) r.fail_here("give only one of ks, ks_ratio, ks_modulus");
      if (r.has("ks_ratio")) law.face_ks = r.number("ks_ratio") * law.face_kn;
      else if (law.face_modulus) law.face_ks = r.quantity("ks_modulus", dims::pressure, 0.0);
      else law.face_ks = r.quantity("ks", dims::stiffness, 0.0);
      if (r.has("ks") && law.face_modulus) r.fail("ks", "with kn_modulus give ks_modulus or ks_ratio");
      if (r.has("ks_modulus") && !law.face_modulus) r.fail("ks_modulus", "with kn give ks or ks_ratio");
      non_negative(r, "ks", law.face_ks);
      if (!law.damping_from_ratio) {
        law.eta_s = r.has("eta_s") ? r.quantity("eta_s", dims::damping) : law.eta_n * std::sqrt(law.face_ks / law.face_kn);
      }
    }
    const auto idx = static_cast<std::int32_t>(m.laws.size());
    m.laws.push_back(law);
    m.law_of_pair[static_cast<std::size_t>(ma) * nm + mb] = idx;
    m.law_of_pair[static_cast<std::size_t>(mb) * nm + ma] = idx;
  }

  struct ElementCommon {
    Shape shape;
    std::int32_t material;
    double radius;
    PreMass pre_mass;
    double mass;
    Motion motion;
    std::int32_t drive;
    Vec2 velocity;
    double omega;
  };

  ElementCommon common(const TableReader& r, bool radius_required = true, bool polygon_allowed = false) {
    ElementCommon e{};
    const std::string shape = r.choice("shape", {"disk", "pre", "polygon"}, "disk");
    e.shape = shape == "disk" ? Shape::disk : shape == "pre" ? Shape::pre : Shape::polygon;
    if (e.shape == Shape::polygon && !polygon_allowed)
      r.fail("shape", "polygons are given in [[element]] (vertices or size) or as a block in [[lattice]] (size)");
    e.material = material(r, "material");
    if (e.shape == Shape::polygon) {
      if (r.has("radius")) r.fail("radius", "a polygon's size comes from its vertices (or size), not a radius");
    } else if (radius_required || r.has("radius")) {
      e.radius = r.quantity("radius", dims::length);
      positive(r, "radius", e.radius);
    }
    e.pre_mass = r.choice("pre_mass", {"square", "disk"}, "square") == "square" ? PreMass::square : PreMass::disk;
    if (e.shape != Shape::pre && r.has("pre_mass")) r.fail("pre_mass", "only for shape = \"pre\"");
    e.mass = r.quantity("mass", dims::mass, 0.0);
    if (r.has("mass")) positive(r, "mass", e.mass);
    const std::string motion = r.choice("motion", {"free", "fixed", "driven"}, "free");
    e.motion = motion == "free" ? Motion::free : motion == "fixed" ? Motion::fixed : Motion::driven;
    e.drive = -1;
    if (e.motion == Motion::driven) {
      const std::string d = r.string("drive");
      auto it = drive_index.find(d);
      if (it == drive_index.end()) r.fail("drive", fmt::format("unknown drive \"{}\" (declare it in [[drive]])", d));
      e.drive = it->second;
    } else if (r.has("drive")) {
      r.fail("drive", "only for motion = \"driven\"");
    }
    e.velocity = r.vector("velocity", dims::velocity, Vec2{});
    e.omega = r.quantity("angular_velocity", dims::angular_velocity, 0.0);
    return e;
  }

  /// [[arrangement]] kind = "ordered": Kiyama's (s−1)/s rows between x = left and x = right on the
  /// floor y = floor (y up); kind = "random": random sequential addition in a rectangle.
  void read_arrangement(const TableReader& r) {
    const std::string kind = r.string("kind");
    if (kind != "ordered" && kind != "random") r.fail("kind", "expected \"ordered\" ((s-1)/s rows, refs §6.1) or \"random\"");
    if (kind == "ordered") {
      const auto ec = common(r);
      const int s = static_cast<int>(r.integer("s", 2, 100000));
      const double left = r.quantity("left", dims::length), right = r.quantity("right", dims::length);
      const double floor = r.quantity("floor", dims::length);
      const double gap = r.quantity("gap", dims::length, 0.0);
      non_negative(r, "gap", gap);
      if (!(right > left)) r.fail("right", "must be right of left");
      in_extent(r, "left", {left, 0.0});
      in_extent(r, "right", {right, 0.0});
      in_extent(r, "floor", {0.0, floor});
      if (r.has("rows") == r.has("count_near")) r.fail_here("give exactly one of rows or count_near (the row count whose disk count is nearest)");
      int rows = 0;
      try {
        rows = r.has("rows") ? static_cast<int>(r.integer("rows", 1, 1000000))
                             : rows_nearest_count(s, r.integer("count_near", 1, kMaxElements));
      } catch (const std::invalid_argument& e) {
        r.fail("count_near", e.what());
      }
      OrderedArrangement a;
      try {
        a = ordered_arrangement(s, rows, right - left, ec.radius, gap);
      } catch (const std::invalid_argument& e) {
        r.fail("s", e.what());
      }
      room_for(r, "s", a.count);
      // jitter: each centre moved by a uniform random amount in [−jitter, jitter] in x and in y (splitmix64
      // from `seed`), e.g. the members of an ensemble of fills that differ only in the last digits (a
      // discharge is chaotic); two centres then move apart by at most 2√2 jitter, which must not close a gap
      const double jitter = r.quantity("jitter", dims::length, 0.0);
      non_negative(r, "jitter", jitter);
      if (r.has("seed") && jitter == 0.0) r.fail("seed", "has no effect without a jitter > 0");
      const auto seed = static_cast<std::uint64_t>(r.integer("seed", 0, std::numeric_limits<std::int64_t>::max(), 0));
      if (2.0 * std::numbers::sqrt2 * jitter > a.min_gap)
        r.fail("jitter", fmt::format("at most {:.6g} m here (2√2 jitter must not exceed the smallest gap, {:.6g} m)",
                                     a.min_gap / (2.0 * std::numbers::sqrt2), a.min_gap));
      SplitMix64 rng(seed);
      for (Vec2 p : ordered_positions(a, left, floor, ec.radius, gap)) {
        if (jitter > 0.0) {
          p.x += jitter * (2.0 * rng.uniform() - 1.0);
          p.y += jitter * (2.0 * rng.uniform() - 1.0);
        }
        in_extent(r, "rows", p, ec.radius);
        place(ec, p, 0.0, -1);
      }
      return;
    }
    const auto base = common(r, false);
    RadiusDistribution dist;
    const int forms = int(r.has("radius")) + int(r.has("radius_range")) + int(r.has("radii"));
    if (forms != 1) r.fail_here("give exactly one of radius, radius_range = [min, max] (uniform) or radii = [...] with fractions = [...]");
    if (r.has("radius")) {
      dist.min = dist.max = base.radius;
    } else if (r.has("radius_range")) {
      const toml::array* arr = r.node("radius_range")->as_array();
      r.mark("radius_range");
      if (!arr || arr->size() != 2) r.fail("radius_range", "expected [min, max]");
      dist.min = r.quantity_of(*arr->get(0), "radius_range", dims::length);
      dist.max = r.quantity_of(*arr->get(1), "radius_range", dims::length);
      if (!(dist.min > 0.0 && dist.max >= dist.min)) r.fail("radius_range", "expected 0 < min <= max");
    } else {
      const toml::array* rs = r.node("radii")->as_array();
      const toml::array* fs = r.node("fractions") ? r.node("fractions")->as_array() : nullptr;
      r.mark("radii");
      r.mark("fractions");
      if (!rs || rs->empty()) r.fail("radii", "expected a list of radii");
      if (!fs || fs->size() != rs->size()) r.fail("radii", "expected fractions = [...] of the same length (number fractions)");
      double sum = 0.0;
      for (std::size_t k = 0; k < rs->size(); ++k) {
        dist.radii.push_back(r.quantity_of(*rs->get(k), "radii", dims::length));
        if (!(dist.radii.back() > 0.0)) r.fail("radii", "radii must be positive");
        const auto f = fs->get(k)->value<double>();
        if (!f || !(*f >= 0.0)) r.fail("fractions", "expected non-negative numbers");
        dist.fractions.push_back(*f);
        sum += *f;
      }
      if (std::abs(sum - 1.0) > 1e-9) r.fail("fractions", fmt::format("must sum to 1 (they sum to {})", sum));
    }
    const toml::array* region = r.node("region") ? r.node("region")->as_array() : nullptr;
    r.mark("region");
    if (!region || region->size() != 2 || !region->get(0)->is_array() || !region->get(1)->is_array())
      r.fail("region", "expected region = [[x0, y0], [x1, y1]] (lower-left and upper-right corners)");
    auto corner = [&](std::size_t k) {
      const toml::array* p = region->get(k)->as_array();
      if (p->size() != 2) r.fail("region", "expected [x, y] corners");
      return Vec2{r.quantity_of(*p->get(0), "region", dims::length), r.quantity_of(*p->get(1), "region", dims::length)};
    };
    const Vec2 lo = corner(0), hi = corner(1);
    in_extent(r, "region", lo);
    in_extent(r, "region", hi);
    if (std::max(hi.x - lo.x, hi.y - lo.y) > kMaxFillCells * (2.0 * dist.largest()))
      r.fail("region", fmt::format("spans more than {:g} disk diameters ({:.6g} m for a largest radius of {:.6g} m)",
                                   kMaxFillCells, std::max(hi.x - lo.x, hi.y - lo.y), dist.largest()));
    const auto count = r.integer("count", 1, kMaxElements);
    room_for(r, "count", count);
    const auto seed = static_cast<std::uint64_t>(r.integer("seed", 0, std::numeric_limits<std::int64_t>::max()));
    const double gap = r.quantity("gap", dims::length, 0.0);
    non_negative(r, "gap", gap);
    std::vector<PlacedDisk> disks;
    try {
      disks = random_fill(lo, hi, count, dist, seed, gap);
    } catch (const std::exception& e) {
      r.fail("count", e.what());
    }
    for (const auto& d : disks) {
      ElementCommon ec = base;
      ec.radius = d.radius;
      place(ec, d.centre, 0.0, -1);
    }
  }

  /// [[lattice]] shape = "polygon": a block cut into columns × rows rectangles of `size` = [w, h], the first
  /// centred on `origin`, the lattice axes turned by `rotation` (each rectangle with them). Polygons are not
  /// bonded (no bonds between polygons yet): bonded = false is required.
  void read_polygon_block(const TableReader& r, const ElementCommon& ec) {
    const Vec2 origin = r.vector("origin", dims::length);
    const auto nx = r.integer("columns", 1, 100000), ny = r.integer("rows", 1, 100000);
    room_for(r, "rows", nx * ny);
    const Vec2 size = r.vector("size", dims::length);
    if (!(size.x > 0.0) || !(size.y > 0.0) || !std::isfinite(size.x) || !std::isfinite(size.y))
      r.fail("size", "expected a positive width and height");
    if (r.has("spacing")) r.fail("spacing", "a polygon block's rectangles lie side by side: their size is the spacing");
    const double rot = r.quantity("rotation", dims::angle, 0.0);
    if (r.boolean("bonded", true)) r.fail("bonded", "polygons have no bonds yet: give bonded = false (a block of loose rectangles)");
    if (c.model.materials[static_cast<std::size_t>(ec.material)].density <= 0.0 && ec.mass <= 0.0)
      r.fail("mass", "the material has no density: give each polygon's mass");
    const Vec2 ex{std::cos(rot), std::sin(rot)}, ey = perp(ex);
    const double half = 0.5 * std::hypot(size.x, size.y);
    const Vec2 far = origin + ex * (size.x * static_cast<double>(nx - 1)) + ey * (size.y * static_cast<double>(ny - 1));
    in_extent(r, "origin", origin, half);
    in_extent(r, "size", far, half);
    std::vector<Vec2> corners;
    for (const Vec2& v : rectangle_vertices(size.x, size.y)) corners.push_back(ex * v.x + ey * v.y);
    for (std::int64_t b = 0; b < ny; ++b)
      for (std::int64_t a = 0; a < nx; ++a) {
        const std::size_t i = add_polygon(c.model, ec.material, corners, origin + ex * (size.x * a) + ey * (size.y * b),
                                          ec.velocity, ec.omega, ec.mass);
        c.model.elements.motion[i] = ec.motion;
        c.model.elements.drive[i] = ec.drive;
      }
  }

  /// A polygon element (docs/model.md §5): `vertices` = [[x, y], ...] counter-clockwise relative to `position`,
  /// or `size` = [w, h], a rectangle centred on it; its centre is the centroid (P1).
  std::size_t place_polygon(const TableReader& r, const ElementCommon& ec, Vec2 pos, double rotation) {
    if (r.has("vertices") == r.has("size")) r.fail_here("a polygon needs exactly one of vertices = [[x, y], ...] or size = [w, h]");
    std::vector<Vec2> corners;
    if (r.has("size")) {
      const Vec2 size = r.vector("size", dims::length);
      if (!(size.x > 0.0) || !(size.y > 0.0)) r.fail("size", "expected a positive width and height");
      corners = rectangle_vertices(size.x, size.y);
    } else {
      const toml::array* vs = r.node("vertices")->as_array();
      r.mark("vertices");
      if (!vs) r.fail("vertices", "expected vertices = [[x, y], ...], counter-clockwise, relative to position");
      for (std::size_t k = 0; k < vs->size(); ++k) {
        const toml::array* v = vs->get(k)->as_array();
        if (!v || v->size() != 2) r.fail_at(*vs->get(k), "vertices", "expected [x, y] corners");
        corners.push_back({r.quantity_of(*v->get(0), "vertices", dims::length), r.quantity_of(*v->get(1), "vertices", dims::length)});
      }
      if (corners.size() > 64) r.fail("vertices", fmt::format("at most 64 corners, got {}", corners.size()));
    }
    if (const std::string why = polygon_problem(corners); !why.empty()) r.fail(r.has("size") ? "size" : "vertices", why);
    const PolygonProperties p = polygon_properties(corners);
    in_extent(r, "vertices", pos + p.centroid, p.circumradius);
    if (c.model.materials[static_cast<std::size_t>(ec.material)].density <= 0.0 && ec.mass <= 0.0)
      r.fail("mass", "the material has no density: give the polygon's mass");
    const std::size_t i = add_polygon(c.model, ec.material, corners, pos, ec.velocity, ec.omega, ec.mass);
    Elements& e = c.model.elements;
    e.phi[i] = rotation;
    e.motion[i] = ec.motion;
    e.drive[i] = ec.drive;
    return i;
  }

  std::size_t place(const ElementCommon& ec, Vec2 pos, double rotation, std::int32_t group) {
    Model& m = c.model;
    const std::size_t i = add_element(m, ec.shape, ec.material, ec.radius, pos, ec.velocity, ec.omega, ec.pre_mass, ec.mass);
    m.elements.phi[i] = rotation;
    m.elements.motion[i] = ec.motion;
    m.elements.drive[i] = ec.drive;
    m.elements.group[i] = group;
    return i;
  }
};

/// [base_friction] (M21, base_friction.hpp): the base plate's velocity (constant, or a [[drive]]),
/// the gravity g_B pressing the model onto it and the regularisation speed v_ε; μ_B per [[material]].
void read_base_friction(const TableReader& top, Reader& rd, const std::vector<double>& mu,
                        const std::string& mu_line, std::string& v_eps_location) {
  BasePlate& plate = rd.c.model.base_plate;
  const bool any_mu = std::any_of(mu.begin(), mu.end(), [](double v) { return v > 0.0; });
  const toml::table* t = top.table("base_friction");
  if (!t) {
    if (any_mu)
      throw CaseError(fmt::format("{}: material.base_friction: a material has base friction (μ_B) but the case "
                                  "has no [base_friction] table (plate_velocity, regularisation_speed)", mu_line));
    return;
  }
  TableReader r(*t, "base_friction", rd.file);
  plate.enabled = true;
  plate.friction = mu;
  if (!any_mu) r.fail_here("no [[material]] has base_friction (μ_B) > 0");
  if (r.has("plate_velocity") == r.has("plate_drive"))
    r.fail_here("give exactly one of plate_velocity ([vx, vy] or { magnitude, direction }) or plate_drive (a [[drive]] name)");
  if (r.has("plate_drive")) {
    const std::string d = r.string("plate_drive");
    auto it = rd.drive_index.find(d);
    if (it == rd.drive_index.end()) r.fail("plate_drive", fmt::format("unknown drive \"{}\" (declare it in [[drive]])", d));
    plate.drive = it->second;
  } else if (r.node("plate_velocity")->is_table()) {
    TableReader v(*r.table("plate_velocity"), "base_friction.plate_velocity", rd.file);
    const double mag = v.quantity("magnitude", dims::velocity);
    const double dir = v.quantity("direction", dims::angle);
    plate.velocity = {mag * std::cos(dir), mag * std::sin(dir)};
    v.finish();
  } else {
    plate.velocity = r.vector("plate_velocity", dims::velocity);
  }
  plate.normal_gravity = r.quantity("normal_gravity", dims::acceleration, 9.80665);
  rd.positive(r, "normal_gravity", plate.normal_gravity);
  plate.regularisation_speed = r.quantity("regularisation_speed", dims::velocity);
  rd.positive(r, "regularisation_speed", plate.regularisation_speed);
  v_eps_location = where(*r.node("regularisation_speed"), rd.file);
  r.finish();
}

/// The linear range of the regularised (M21) is a dashpot of rate c: refuse cΔt > 1 (base_friction.hpp).
void check_base_friction_rate(const Model& m, const std::string& v_eps_location) {
  if (!m.base_plate.enabled || m.numerics.allow_unstable) return;
  const double rate = max_base_friction_rate(m.base_plate, m.elements);
  if (rate * m.numerics.dt > 1.0)
    throw CaseError(fmt::format(
        "{}: base_friction.regularisation_speed: {:.6g} m/s makes the base friction a dashpot of rate {:.6g} 1/s "
        "below it (μ_B g_B / v_ε, or its rotational analogue), and Δt × rate = {:.4g} > 1 (the explicit update "
        "would overshoot the plate velocity; unstable above 2). Use regularisation_speed >= {:.6g} m/s or "
        "numerics.dt <= {:.6g} s",
        v_eps_location, m.base_plate.regularisation_speed, rate, rate * m.numerics.dt,
        m.base_plate.regularisation_speed * rate * m.numerics.dt, 1.0 / rate));
}

/// [stop] after_peak = { quantity = "platen.fy", drop = 0.5, from = "1 ms" }: stop past the peak.
void read_after_peak(const TableReader& r, StopSpec& stop) {
  stop.after_peak_quantity = r.string("quantity");
  stop.after_peak_location = where(*r.node("quantity"), r.file());
  stop.after_peak_drop = r.number("drop", 0.5);
  stop.after_peak_from = r.quantity("from", dims::time, 0.0);
  if (!(stop.after_peak_drop > 0.0 && stop.after_peak_drop < 1.0))
    r.fail("drop", "expected the fraction of the peak lost before stopping, in (0, 1)");
  r.finish();
}

ProbeKind probe_kind(const std::string& s) {
  if (s == "value") return ProbeKind::value;
  if (s == "max") return ProbeKind::max;
  if (s == "min") return ProbeKind::min;
  if (s == "mean") return ProbeKind::mean;
  if (s == "time_of_max") return ProbeKind::time_of_max;
  if (s == "time_of_min") return ProbeKind::time_of_min;
  if (s == "crossing") return ProbeKind::crossing;
  if (s == "slope") return ProbeKind::slope;
  if (s == "restitution") return ProbeKind::restitution;
  if (s == "ratio") return ProbeKind::ratio;
  return ProbeKind::contact_duration;
}

/// [case]: the title and the source.
void Reader::read_case_table(const TableReader& top) {
  if (const toml::table* t = top.table("case")) {
    TableReader r(*t, "case", file);
    c.title = r.string("title");
    c.source = r.string("source", "");
    r.finish();
  } else {
    top.fail("case", "missing [case] table with a title");
  }
}

/// [physics]: thickness and gravity.
void Reader::read_physics(const TableReader& top) {
  Model& m = c.model;
  if (const toml::table* t = top.table("physics")) {
    TableReader r(*t, "physics", file);
    m.thickness = r.quantity("thickness", dims::length, 1.0);
    positive(r, "thickness", m.thickness);
    if (r.has("gravity") && r.node("gravity")->is_table()) {
      TableReader g(*r.table("gravity"), "physics.gravity", file);
      const double mag = g.quantity("magnitude", dims::acceleration);
      const double dir = g.quantity("direction", dims::angle);
      m.gravity = {mag * std::cos(dir), mag * std::sin(dir)};
      g.finish();
    } else {
      m.gravity = r.vector("gravity", dims::acceleration, Vec2{});
    }
    r.finish();
  }
}

/// [[material]]: name, density and μ_B (base friction, M21) per material; every material pair
/// starts without a law.
void Reader::read_materials(const TableReader& top, std::vector<double>& base_mu, std::string& base_mu_line) {
  Model& m = c.model;
  each(top, "material", [&](TableReader& r, std::size_t) {
    Material mat;
    mat.name = r.string("name");
    mat.density = r.quantity("density", dims::density, 0.0);
    if (material_index.count(mat.name)) r.fail("name", fmt::format("material \"{}\" declared twice", mat.name));
    non_negative(r, "density", mat.density);
    base_mu.push_back(r.number("base_friction", 0.0));  // μ_B (M21)
    non_negative(r, "base_friction", base_mu.back());
    if (r.has("base_friction")) base_mu_line = where(*r.node("base_friction"), file);
    material_index[mat.name] = static_cast<std::int32_t>(m.materials.size());
    m.materials.push_back(mat);
  });
  if (m.materials.empty()) top.fail("material", "missing: declare at least one [[material]]");
  m.law_of_pair.assign(m.materials.size() * m.materials.size(), -1);
}

/// [[drive]]: a velocity, constant or piecewise linear in time, by name.
void Reader::read_drives(const TableReader& top) {
  Model& m = c.model;
  each(top, "drive", [&](TableReader& r, std::size_t) {
    const std::string name = r.string("name");
    VelocityHistory h;
    if (r.has("velocity")) {
      h.t = {0.0};
      h.v = {r.vector("velocity", dims::velocity)};
    } else {
      const toml::array* ts = r.node("times") ? r.node("times")->as_array() : nullptr;
      const toml::array* vs = r.node("velocities") ? r.node("velocities")->as_array() : nullptr;
      r.mark("times");
      r.mark("velocities");
      if (!ts || !vs || ts->size() != vs->size() || ts->empty())
        r.fail_here("expected velocity = [vx, vy], or times = [...] and velocities = [[vx, vy], ...] of equal length");
      for (std::size_t k = 0; k < ts->size(); ++k) {
        const double t = r.quantity_of(*ts->get(k), "times", dims::time);
        const toml::array* v = vs->get(k)->as_array();
        if (!v || v->size() != 2) r.fail("velocities", "expected [vx, vy] pairs");
        if (!h.t.empty() && t <= h.t.back()) r.fail("times", "must increase strictly");
        h.t.push_back(t);
        h.v.push_back({r.quantity_of(*v->get(0), "velocities", dims::velocity),
                       r.quantity_of(*v->get(1), "velocities", dims::velocity)});
      }
    }
    if (drive_index.count(name)) r.fail("name", fmt::format("drive \"{}\" declared twice", name));
    drive_index[name] = static_cast<std::int32_t>(m.drives.size());
    m.drives.push_back(h);
  });
}

/// [[element]]: one element each, with an optional preload.
void Reader::read_elements(const TableReader& top) {
  Model& m = c.model;
  each(top, "element", [&](TableReader& r, std::size_t) {
    const auto ec = common(r, true, true);
    const Vec2 pos = r.vector("position", dims::length);
    in_extent(r, "position", pos, ec.radius);
    const double rot = r.quantity("rotation", dims::angle, 0.0);
    const std::size_t idx = ec.shape == Shape::polygon ? place_polygon(r, ec, pos, rot) : place(ec, pos, rot, -1);
    if (const toml::table* pt = r.table("preload")) {
      TableReader pr(*pt, r.key_path("preload"), file);
      Preload p;
      p.element = static_cast<std::uint32_t>(idx);
      p.rotation = pr.quantity("rotation", dims::angle);
      p.about = pr.vector("about", dims::length);
      pr.finish();
      m.preloads.push_back(p);
    }
  });
}

/// [[lattice]]: a grid of elements, bonded into a group by default.
void Reader::read_lattices(const TableReader& top) {
  // [[lattice]]: columns × rows elements, axes rotated by `rotation`, spacing 2r by default
  each(top, "lattice", [&](TableReader& r, std::size_t) {
    const auto ec = common(r, true, true);
    if (ec.shape == Shape::polygon) return read_polygon_block(r, ec);
    if (r.has("size")) r.fail("size", "only for shape = \"polygon\"");
    const Vec2 origin = r.vector("origin", dims::length);
    const auto nx = r.integer("columns", 1, 100000), ny = r.integer("rows", 1, 100000);
    room_for(r, "rows", nx * ny);
    const double spacing = r.quantity("spacing", dims::length, 2.0 * ec.radius);
    positive(r, "spacing", spacing);
    const double rot = r.quantity("rotation", dims::angle, 0.0);
    const bool bonded = r.boolean("bonded", true);
    const std::int32_t group = bonded ? next_group++ : -1;
    const Vec2 ex{std::cos(rot), std::sin(rot)}, ey = perp(ex);
    const Vec2 far = origin + ex * (spacing * static_cast<double>(nx - 1)) + ey * (spacing * static_cast<double>(ny - 1));
    if (!std::isfinite(far.x) || !std::isfinite(far.y))
      r.fail("spacing", fmt::format("the lattice reaches a position that is not a finite number ({}, {})", far.x, far.y));
    in_extent(r, "origin", origin, ec.radius);
    in_extent(r, "spacing", far, ec.radius);
    for (std::int64_t b = 0; b < ny; ++b)
      for (std::int64_t a = 0; a < nx; ++a)
        place(ec, origin + ex * (spacing * a) + ey * (spacing * b), rot, group);
  });
}

/// [[row]]: elements in a line.
void Reader::read_rows(const TableReader& top) {
  // [[row]]: count elements from `start` along `step`
  each(top, "row", [&](TableReader& r, std::size_t) {
    const auto ec = common(r);
    const Vec2 start = r.vector("start", dims::length);
    const Vec2 step = r.vector("step", dims::length);
    const auto n = r.integer("count", 1, 10000000);
    room_for(r, "count", n);
    const Vec2 far = start + step * static_cast<double>(n - 1);
    if (!std::isfinite(far.x) || !std::isfinite(far.y))
      r.fail("step", fmt::format("the row reaches a position that is not a finite number ({}, {})", far.x, far.y));
    in_extent(r, "start", start, ec.radius);
    in_extent(r, "step", far, ec.radius);
    for (std::int64_t k = 0; k < n; ++k) place(ec, start + step * static_cast<double>(k), 0.0, -1);
  });
}

/// [[wall]]: segment and point walls, fixed or driven, by name.
void Reader::read_walls(const TableReader& top) {
  Model& m = c.model;
  each(top, "wall", [&](TableReader& r, std::size_t k) {
    Wall w;
    w.name = r.string("name", fmt::format("wall{}", k));
    const std::string type = r.choice("type", {"segment", "point"}, "segment");
    w.kind = type == "segment" ? WallKind::segment : WallKind::point;
    if (w.kind == WallKind::segment) {
      w.a = r.vector("from", dims::length);
      w.b = r.vector("to", dims::length);
      in_extent(r, "from", w.a);
      in_extent(r, "to", w.b);
      if (w.a == w.b) r.fail("to", "a segment wall needs two different end points");
    } else {
      w.a = w.b = r.vector("at", dims::length);
      in_extent(r, "at", w.a);
    }
    w.material = material(r, "material");
    if (r.has("drive")) {
      const std::string d = r.string("drive");
      auto it = drive_index.find(d);
      if (it == drive_index.end()) r.fail("drive", fmt::format("unknown drive \"{}\"", d));
      w.drive = it->second;
    }
    if (wall_index.count(w.name)) r.fail("name", fmt::format("wall \"{}\" declared twice", w.name));
    wall_index[w.name] = static_cast<std::int32_t>(m.walls.size());
    m.walls.push_back(w);
  });
}

/// Every material pair that can meet needs a law; every element a mass.
void Reader::check_laws_and_masses(const TableReader& top) const {
  const Model& m = c.model;
  std::vector<int> used(m.materials.size(), 0), wall_used(m.materials.size(), 0);
  for (auto mat : m.elements.material) ++used[static_cast<std::size_t>(mat)];
  for (const auto& w : m.walls) wall_used[static_cast<std::size_t>(w.material)] = 1;
  for (std::size_t a = 0; a < used.size(); ++a) {
    for (std::size_t b = 0; b < used.size(); ++b) {
      const bool elements_meet = used[a] && used[b] && (a != b || used[a] > 1);
      if (!used[a] || !(elements_meet || wall_used[b])) continue;
      const std::int32_t law = m.law_of_pair[a * used.size() + b];
      if (law < 0)
        top.fail("contact", fmt::format("missing [[contact]] between \"{}\" and \"{}\"", m.materials[a].name, m.materials[b].name));
      if (elements_meet && rotated_lever_at.count(law))  // (M19.r) follows one element's corner on a wall
        throw CaseError(fmt::format("{}: \"rotated_corner\" is for walls (M19.r), but elements of \"{}\" and \"{}\" can "
                                    "meet under this law; give the element pair its own [[contact]]",
                                    rotated_lever_at.at(law), m.materials[a].name, m.materials[b].name));
    }
  }
  for (std::size_t i = 0; i < m.elements.size(); ++i)
    if (!(m.elements.mass[i] > 0.0) || !std::isfinite(m.elements.mass[i]))
      top.fail("material", fmt::format("element {} has no mass: give its material a density or the element a mass", i));
}

/// [numerics]: integrator, velocity start, Δt, duration, skin and the blow-up bounds.
void Reader::read_numerics(const TableReader& top) {
  Model& m = c.model;
  if (const toml::table* t = top.table("numerics")) {
    TableReader r(*t, "numerics", file);
    Numerics& n = m.numerics;
    n.integrator = r.choice("integrator", {"K18", "K19"}, "K18") == "K18" ? Integrator::k18 : Integrator::k19;
    n.velocity_start = r.choice("velocity_start", {"plain", "staggered"}, "plain") == "plain" ? VelocityStart::plain : VelocityStart::staggered;
    n.dt = r.quantity("dt", dims::time);
    if (const toml::node* dtn = r.node("dt")) c.dt_location = where(*dtn, file);
    positive(r, "dt", n.dt);
    n.duration = r.quantity("duration", dims::time);
    positive(r, "duration", n.duration);
    n.skin = r.quantity("skin", dims::length, 0.0);
    non_negative(r, "skin", n.skin);
    n.allow_unstable = r.boolean("allow_unstable", false);
    n.energy_limit = r.quantity("energy_limit", dims::energy, 0.0);
    non_negative(r, "energy_limit", n.energy_limit);
    n.max_step_fraction = r.number("max_step_fraction", 0.25);
    positive(r, "max_step_fraction", n.max_step_fraction);
    n.guard_reach = r.quantity("guard_reach", dims::length, std::numeric_limits<double>::infinity());
    positive(r, "guard_reach", n.guard_reach);
    // spatial reordering every this many neighbour-list rebuilds (core/spatial_order.hpp); 0: never
    n.reorder_every = r.integer("reorder_every", 0, std::int64_t{1} << 40, 0);
    if (n.reorder_every > 0)
      for (const PairLaw& law : m.laws)
        if (law.kind == LawKind::face)
          r.fail("reorder_every", "spatial reordering needs linear contact laws only (this case has a face law); "
                                  "expected 0 or no reorder_every");
    // the step count must be a number an int64 (and a double, exactly) holds
    const double steps = std::ceil(n.duration / n.dt - 1e-9);
    if (!(steps <= 9.007199254740992e15))
      r.fail("duration", fmt::format("{:.6g} s / dt = {:.6g} s is {:.4g} steps; at most 2^53 (9.0e15) steps", n.duration,
                                     n.dt, steps));
    r.finish();
  } else {
    top.fail("numerics", "missing [numerics] table (dt, duration)");
  }
}

/// An output interval: a whole number of steps (500, or "500") or a time ("1 ms"), which must be a
/// whole number of steps of dt (within 1e-9); 0: none. Returned in steps.
std::int64_t steps_or_time(const TableReader& r, const std::string& key, double dt) {
  const toml::node* n = r.node(key);
  r.mark(key);
  if (!n) return 0;
  if (n->is_integer()) return r.integer(key, 0, std::int64_t{1} << 40, 0);
  if (!n->is_string()) r.fail(key, "expected a whole number of steps (500) or a time (\"1 ms\")");
  Quantity q;
  try {
    q = parse_quantity(*n->value<std::string>());
  } catch (const UnitError& e) {
    r.fail(key, e.what());
  }
  if (q.dim == dims::dimensionless) {  // "500": steps
    if (!(q.value >= 0.0 && q.value <= 1e12 && q.value == std::floor(q.value)))
      r.fail(key, fmt::format("expected a whole number of steps, got {:g}", q.value));
    return static_cast<std::int64_t>(q.value);
  }
  const double t = r.quantity(key, dims::time);
  const double steps = t / dt;
  if (!(t >= 0.0) || std::abs(steps - std::round(steps)) > 1e-9 * std::max(1.0, steps) || steps > 1e12)
    r.fail(key, fmt::format("{:.6g} s is {:.6g} steps of dt = {:.6g} s; give a whole number of steps, or a time that is one",
                            t, steps, dt));
  return static_cast<std::int64_t>(std::llround(steps));
}

/// [output]: series, VTK snapshots and force-network pictures.
void Reader::read_output(const TableReader& top) {
  Model& m = c.model;
  if (const toml::table* t = top.table("output")) {
    TableReader r(*t, "output", file);
    c.output.every = steps_or_time(r, "every", m.numerics.dt);
    c.output.series = r.strings("series");
    if (const toml::array* arr = r.node("series") ? r.node("series")->as_array() : nullptr)
      for (const auto& item : *arr) c.output.series_locations.push_back(where(item, file));
    c.output.vtk = r.boolean("vtk", true);
    c.output.vtk_every = steps_or_time(r, "vtk_every", m.numerics.dt);
    OutputSpec& o = c.output;
    o.lammps_dump = r.boolean("lammps_dump", false);
    o.contacts = r.boolean("contacts", false);
    o.contacts_every = steps_or_time(r, "contacts_every", m.numerics.dt);
    if (o.contacts_every > 0 && !o.contacts) r.fail("contacts_every", "contacts.csv is written only with contacts = true");
    o.pictures = r.boolean("pictures", false);
    o.picture_every = r.node("picture_every") && r.node("picture_every")->is_integer()
                          ? static_cast<double>(r.integer("picture_every", 0, std::int64_t{1} << 40, 0)) * m.numerics.dt
                          : r.quantity("picture_every", dims::time, 0.0);  // steps, or a time
    non_negative(r, "picture_every", o.picture_every);
    if (o.picture_every > 0.0 && o.picture_every < m.numerics.dt)
      r.fail("picture_every", fmt::format("{:.6g} s is shorter than dt = {:.6g} s; a picture interval of at least one step",
                                          o.picture_every, m.numerics.dt));
    if (o.picture_every > 0.0 && m.numerics.duration / o.picture_every > 10000.0)
      r.fail("picture_every", fmt::format("{:.6g} s gives {:.4g} pictures over {:.6g} s; at most 10000", o.picture_every,
                                          m.numerics.duration / o.picture_every, m.numerics.duration));
    if (const toml::node* pt = r.node("picture_times")) {
      r.mark("picture_times");
      const toml::array* ts = pt->as_array();
      if (!ts || ts->empty()) r.fail("picture_times", "expected a non-empty array of times, e.g. [\"0.5 s\", \"1 s\"]");
      if (ts->size() > 10000) r.fail("picture_times", "at most 10000 times");
      for (std::size_t k = 0; k < ts->size(); ++k) {
        const double t = r.quantity_of(*ts->get(k), "picture_times", dims::time);
        if (!(t >= 0.0)) r.fail("picture_times", "expected times >= 0 s");
        if (!o.picture_times.empty() && t <= o.picture_times.back()) r.fail("picture_times", "must increase strictly");
        o.picture_times.push_back(t);
      }
    }
    o.wall_contacts = r.strings("wall_contacts");
    for (const std::string& name : o.wall_contacts) {
      const auto it = wall_index.find(name);
      if (it == wall_index.end())
        r.fail("wall_contacts", fmt::format("unknown wall \"{}\" (expected names of [[wall]] tables)", name));
      if (m.walls[static_cast<std::size_t>(it->second)].kind != WallKind::segment)
        r.fail("wall_contacts", fmt::format("wall \"{}\" is a point wall: a contact profile needs a segment", name));
      if (std::count(o.wall_contacts.begin(), o.wall_contacts.end(), name) > 1)
        r.fail("wall_contacts", fmt::format("wall \"{}\" is named twice", name));
      o.wall_contact_walls.push_back(static_cast<std::uint32_t>(it->second));
    }
    o.bond_breaks = r.boolean("bond_breaks", false);
    o.picture_width = r.integer("picture_width", 64, 8000, 800);
    o.picture_max_force = r.optional_quantity("picture_max_force", dims::force);
    if (o.picture_max_force) positive(r, "picture_max_force", *o.picture_max_force);
    r.finish();
  }
}

/// [discharge]: the slit wall, when it opens, the outlet line and the keystone rule.
void Reader::read_discharge(const TableReader& top) {
  Model& m = c.model;
  // [discharge]: a silo's discharge stage (core/discharge.hpp): the slit wall is opened, disks below the
  // outlet line are removed, a stalled arch loses its keystone
  if (const toml::table* t = top.table("discharge")) {
    TableReader r(*t, "discharge", file);
    Discharge& d = m.discharge;
    d.enabled = true;
    const std::string slit = r.string("slit");
    auto it = wall_index.find(slit);
    if (it == wall_index.end()) r.fail("slit", fmt::format("unknown wall \"{}\" (expected the name of the wall that closes the slit)", slit));
    d.slit = it->second;
    Wall& w = m.walls[static_cast<std::size_t>(d.slit)];
    if (w.kind != WallKind::segment) r.fail("slit", fmt::format("wall \"{}\" is a point wall; expected a segment wall across the slit", slit));
    if (w.drive >= 0) r.fail("slit", fmt::format("wall \"{}\" is driven; expected a fixed wall", slit));
    d.open_at = r.quantity("open_at", dims::time, 0.0);
    non_negative(r, "open_at", d.open_at);
    w.open = d.open_at == 0.0;  // else the run opens it at open_at
    d.outlet_depth = r.quantity("outlet_depth", dims::length);
    non_negative(r, "outlet_depth", d.outlet_depth);
    d.keystone_after = r.quantity("keystone_after", dims::time, 0.0);
    non_negative(r, "keystone_after", d.keystone_after);
    if (!(norm(m.gravity) > 0.0)) r.fail_here("a discharge needs gravity (the outlet line lies below the slit along g)");
    r.finish();
  }
}

/// [stop]: the settle criteria and after_peak.
void Reader::read_stop(const TableReader& top) {
  Model& m = c.model;
  if (const toml::table* t = top.table("stop")) {
    TableReader r(*t, "stop", file);
    c.stop.settled_increment = r.optional_quantity("settled_increment", dims::length);
    if (c.stop.settled_increment) positive(r, "settled_increment", *c.stop.settled_increment);
    if (r.has("settled_increment_factor")) {
      c.stop.settled_increment_factor = r.number("settled_increment_factor");
      positive(r, "settled_increment_factor", *c.stop.settled_increment_factor);
      if (!(norm(m.gravity) > 0.0)) r.fail("settled_increment_factor", "needs gravity (the threshold is factor·dt²·|g|)");
    }
    if (r.has("settled_force_ratio")) {
      c.stop.settled_force_ratio = r.number("settled_force_ratio");
      positive(r, "settled_force_ratio", *c.stop.settled_force_ratio);
    }
    c.stop.settle_window = r.integer("settle_window", 1, std::int64_t{1} << 40, 1000);
    c.stop.settle_min_time = r.quantity("settle_min_time", dims::time, 0.0);
    non_negative(r, "settle_min_time", c.stop.settle_min_time);
    if (const toml::table* a = r.table("after_peak"))
      read_after_peak(TableReader(*a, "stop.after_peak", file), c.stop);
    r.finish();
  }
}

/// [[probe]]: quantities of interest, each by name.
void Reader::read_probes(const TableReader& top) {
  Model& m = c.model;
  each(top, "probe", [&](TableReader& r, std::size_t) {
    ProbeSpec p;
    p.name = r.string("name");
    p.kind = probe_kind(r.choice("kind", {"value", "max", "min", "mean", "time_of_max", "time_of_min", "crossing", "slope",
                                          "restitution", "contact_duration", "ratio"}, "value"));
    p.location = where(*r.node("name"), file);
    if (p.kind == ProbeKind::ratio) {  // of / over: probes declared before this one, not ratios themselves
      for (const char* key : {"of", "over"}) {
        const std::string name = r.string(key);
        const auto it = std::find_if(c.probes.begin(), c.probes.end(), [&](const ProbeSpec& q) { return q.name == name; });
        if (it == c.probes.end()) r.fail(key, fmt::format("no probe \"{}\" is declared before this one", name));
        if (it->kind == ProbeKind::ratio) r.fail(key, fmt::format("\"{}\" is a ratio itself (take the ratio of its parts)", name));
        (key[1] == 'f' ? p.of : p.over) = name;
      }
    } else if (p.kind != ProbeKind::restitution && p.kind != ProbeKind::contact_duration) {
      p.quantity = r.string("quantity");
      p.location = where(*r.node("quantity"), file);
      if (p.kind == ProbeKind::value) {
        p.at = r.optional_quantity("at", dims::time);
        if (p.at && *p.at < 0.0)  // a value before the start would be extrapolated
          r.fail("at", fmt::format("expected a time ≥ 0 (the run starts at t = 0), got {:g} s", *p.at));
      }
      if (p.kind == ProbeKind::slope) {
        p.from = r.quantity("from", dims::time);
        p.to = r.quantity("to", dims::time);
        p.against = r.string("against", "");
      } else if (p.kind != ProbeKind::value) {
        p.from = r.quantity("from", dims::time, 0.0);
        p.to = r.quantity("to", dims::time, std::numeric_limits<double>::infinity());
      }
      if (p.kind != ProbeKind::value && !(p.to > p.from)) r.fail("to", "must be later than from");
      if (p.kind == ProbeKind::crossing) {
        p.level = r.number("level");
        const std::string d = r.choice("direction", {"up", "down", "either"}, "either");
        p.direction = d == "up" ? 1 : d == "down" ? -1 : 0;
      }
    } else {
      p.element = static_cast<std::uint32_t>(r.integer("element", 0, static_cast<std::int64_t>(m.elements.size()) - 1));
      if (r.has("wall") == r.has("other")) r.fail_here("give exactly one of other (an element index) or wall (a wall name)");
      if (r.has("wall")) {
        const std::string w = r.string("wall");
        auto it = wall_index.find(w);
        if (it == wall_index.end()) r.fail("wall", fmt::format("unknown wall \"{}\"", w));
        p.other = static_cast<std::uint32_t>(it->second);
        p.other_is_wall = true;
      } else {
        p.other = static_cast<std::uint32_t>(r.integer("other", 0, static_cast<std::int64_t>(m.elements.size()) - 1));
      }
    }
    for (const auto& q : c.probes)
      if (q.name == p.name) r.fail("name", fmt::format("probe \"{}\" declared twice", p.name));
    c.probes.push_back(p);
  });
}

Case read_parsed_case(toml::table root, const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  const std::string file = path.string();
  for (const auto& kv : overrides) apply_override(root, kv);

  Case c;
  c.path = path;
  c.overrides = overrides;
  Reader rd{file, c, {}, {}, {}, 0, {}};
  TableReader top(root, "", file);

  // The tables in this order: each may refer to those before it (materials, drives, walls, Δt).
  rd.read_case_table(top);
  rd.read_physics(top);
  std::vector<double> base_mu;   // μ_B per material (base friction, M21)
  std::string base_mu_line;      // where one was given
  rd.read_materials(top, base_mu, base_mu_line);
  rd.read_drives(top);
  std::string v_eps_location;
  read_base_friction(top, rd, base_mu, base_mu_line, v_eps_location);
  // [[contact]]
  rd.each(top, "contact", [&](TableReader& r, std::size_t) { rd.read_contact(r); });
  rd.read_elements(top);
  rd.read_lattices(top);
  rd.read_rows(top);
  // [[arrangement]]: generated fills (generators.hpp, refs §6.1)
  rd.each(top, "arrangement", [&](TableReader& r, std::size_t) { rd.read_arrangement(r); });
  if (c.model.elements.size() == 0) top.fail_here("no elements: give [[element]], [[lattice]], [[row]] or [[arrangement]] tables");
  rd.read_walls(top);
  rd.check_laws_and_masses(top);
  rd.read_numerics(top);
  check_base_friction_rate(c.model, v_eps_location);
  rd.read_output(top);
  rd.read_discharge(top);
  rd.read_stop(top);
  rd.read_probes(top);
  top.finish();

  // The resolved case, for provenance.
  std::ostringstream os;
  os << toml::json_formatter{root};
  c.resolved = nlohmann::json::parse(os.str());
  c.model.elements.shrink_to_fit();  // the generators grew the arrays element by element
  return c;
}

}  // namespace

Case read_case(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  return read_parsed_case(parse_toml_file(path), path, overrides);
}

Case read_case_text(std::string_view text, const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  return read_parsed_case(parse_toml_text(text, path), path, overrides);
}

ElementSource element_source(const Case& c, std::size_t element) {
  const auto after = std::upper_bound(c.element_sources.begin(), c.element_sources.end(), element,
                                      [](std::size_t k, const ElementSource& s) { return k < s.first; });
  if (after == c.element_sources.begin()) return {0, c.path.string(), ""};
  return *std::prev(after);
}

double check_case(const Case& c, StabilityBound* bound) {
  const Model& m = c.model;
  const Elements& e = m.elements;
  const std::string file = c.path.string();
  // Overlapping geometry at the start: fixed bodies must not overlap each other; free bodies may
  // touch, but an overlap above 5 % of the smaller radius is almost certainly a mistake.
  std::vector<CandidatePair> pairs;
  NeighbourSearch ns;
  ns.build(e, 0.0, pairs);
  for (const auto& p : pairs) {
    const double overlap = element_overlap(m, p.i, p.j);
    const bool both_fixed = e.motion[p.i] != Motion::free && e.motion[p.j] != Motion::free;
    const double tol = both_fixed ? 1e-9 * std::min(e.radius[p.i], e.radius[p.j])
                                  : 0.05 * std::min(e.radius[p.i], e.radius[p.j]);
    if (overlap > tol) {
      const ElementSource a = element_source(c, p.i), b = element_source(c, p.j);
      throw CaseError(fmt::format("{}: {}elements {} and {} overlap by {:.4g} m at the start (element {}: {}{}){}", b.location,
                                  b.key.empty() ? "" : b.key + ": ", p.i, p.j, overlap, p.i, a.key.empty() ? "" : a.key + ", ",
                                  a.location, both_fixed ? " (both fixed: overlapping fixed geometry)" : " (more than 5 % of a radius)"));
    }
  }
  for (std::size_t i = 0; i < e.size(); ++i) {
    for (const Wall& w : m.walls) {
      const double overlap = wall_overlap(m, i, w);
      const double tol = e.motion[i] != Motion::free ? 1e-9 * e.radius[i] : 0.05 * e.radius[i];
      if (overlap > tol) {
        const ElementSource a = element_source(c, i);
        throw CaseError(fmt::format("{}: {}element {} overlaps wall \"{}\" by {:.4g} m at the start", a.location,
                                    a.key.empty() ? "" : a.key + ": ", i, w.name, overlap));
      }
    }
  }
  // The time step against the stability limit of every contact the case can form.
  // Simulation::stability_bound() of this model, without building a Simulation (a copy of the model with
  // its contact lists: as much memory as the run itself, bench/journal.md); the bound reads nothing that
  // the Simulation's constructor changes (velocities, increments, preloads).
  const StabilityBound b = assembly_stability_bound(m, registered_stability_terms(m));
  if (bound) *bound = b;
  const double limit = b.limit;
  const std::string dt_at = c.dt_location.empty() ? file : c.dt_location;
  if (std::isnan(limit))
    throw CaseError(fmt::format("{}: numerics.dt: the stability limit is not a number: element {} has {}", dt_at,
                                b.element, b.law));
  if (m.numerics.dt > limit && !m.numerics.allow_unstable && !(limit > 0.0)) {
    // K19 without damping (or a contact without a dashpot): its Hopf bound Δt < η/K is 0, no Δt is stable
    throw CaseError(fmt::format(
        "{}: numerics.dt: no time step is stable: the limit of {} for the contacts this case can form is 0 "
        "(set by element {}, {}; refs §1.5: K19 needs damping, Δt < η/K). Give the contacts a damping ratio, "
        "use integrator = \"K18\", or numerics.allow_unstable = true for a stability study.",
        dt_at, m.numerics.integrator == Integrator::k18 ? "K18" : "K19", b.element, b.law));
  }
  if (m.numerics.dt > limit && !m.numerics.allow_unstable) {
    throw CaseError(fmt::format(
        "{}: numerics.dt: {:.6g} s is above the stability limit {:.6g} s of {} for the contacts this case can "
        "form (set by element {} with {} element and {} wall contacts, {}; refs §1.5). "
        "Use numerics.dt <= {:.6g} s, or numerics.allow_unstable = true for a stability study.",
        dt_at, m.numerics.dt, limit, m.numerics.integrator == Integrator::k18 ? "K18" : "K19", b.element,
        b.element_contacts, b.wall_contacts, b.law, limit));
  }
  return limit;
}

}  // namespace dem
