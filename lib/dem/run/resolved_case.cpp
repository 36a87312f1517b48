#include "dem/run/resolved_case.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dem/run/quantities.hpp"

namespace dem {

namespace {

nlohmann::json vec(Vec2 v) { return nlohmann::json::array({v.x, v.y}); }

const char* name_of(Integrator i) { return i == Integrator::k18 ? "K18" : "K19"; }
const char* name_of(VelocityStart v) { return v == VelocityStart::plain ? "plain" : "staggered"; }
const char* name_of(EndRule r) { return r == EndRule::elastic ? "elastic" : "total"; }
const char* name_of(Onset o) { return o == Onset::increment ? "increment" : "overlap"; }
const char* name_of(SegmentPositions p) { return p == SegmentPositions::centres ? "centres" : "ends"; }
const char* name_of(NormalIncrement n) { return n == NormalIncrement::exact ? "exact" : "linearised"; }
const char* name_of(TangentialIncrement t) {
  switch (t) {
    case TangentialIncrement::exact: return "exact";
    case TangentialIncrement::literal: return "literal";
    case TangentialIncrement::linearised: return "linearised";
    case TangentialIncrement::hisatake: return "hisatake";
  }
  return "?";
}
const char* name_of(ProbeKind k) {
  switch (k) {
    case ProbeKind::value: return "value";
    case ProbeKind::max: return "max";
    case ProbeKind::min: return "min";
    case ProbeKind::mean: return "mean";
    case ProbeKind::time_of_max: return "time_of_max";
    case ProbeKind::time_of_min: return "time_of_min";
    case ProbeKind::crossing: return "crossing";
    case ProbeKind::slope: return "slope";
    case ProbeKind::restitution: return "restitution";
    case ProbeKind::contact_duration: return "contact_duration";
    case ProbeKind::ratio: return "ratio";
  }
  return "?";
}

nlohmann::json law_json(const Model& m, const PairLaw& law) {
  nlohmann::json j;
  j["law"] = law.kind == LawKind::linear ? "linear" : "face";
  j["onset"] = name_of(law.onset);
  if (law.damping_from_ratio) {
    j["damping_ratio"] = law.damping_ratio;
    j["mass_basis"] = law.mass_basis == MassBasis::reduced ? "reduced" : "particle";
  } else {
    j["eta_n"] = law.eta_n;  // [N·s/m] (per segment for the face law)
    j["eta_s"] = law.eta_s;
  }
  if (law.kind == LawKind::linear) {
    j["kn"] = law.linear.kn;  // [N/m], × thickness already applied
    j["ks"] = law.linear.ks;
    j["friction"] = law.linear.mu;
    j["end_rule"] = name_of(law.linear.end_rule);
    if (law.rolling.enabled) {  // (R1–R6); absent when off, so cases without it keep their resolved form
      nlohmann::json r;
      r["friction"] = law.rolling.mu_r;
      if (law.rolling.kr > 0.0) r["stiffness"] = law.rolling.kr;  // [N·m/rad], × thickness already applied
      else r["stiffness_factor"] = law.rolling.stiffness_factor;
      r["damping_ratio"] = law.rolling.damping_ratio;
      j["rolling"] = r;
    }
    if (law.gap.enabled) {  // (B1–B5); absent when off; a strength that never breaks is absent (no JSON infinity)
      nlohmann::json g;
      g["distance"] = law.gap.distance, g["kn"] = law.gap.kn, g["ks"] = law.gap.ks, g["damping_ratio"] = law.gap.damping_ratio;
      if (std::isfinite(law.gap.tensile_strength)) g["tensile_strength"] = law.gap.tensile_strength;
      if (std::isfinite(law.gap.shear_strength)) g["shear_strength"] = law.gap.shear_strength;
      if (std::isfinite(law.gap.break_gap)) g["break_distance"] = law.gap.break_gap;
      j["gap"] = g;
    }
  } else {
    const FaceLaw& f = law.face;
    j["segments"] = f.segments;
    j["positions"] = name_of(f.positions);
    j["normal_increment"] = name_of(f.normal);
    j["tangential_increment"] = name_of(f.tangential);
    if (law.face_modulus) {
      j["kn_modulus"] = law.face_kn;  // [Pa]
      j["ks_modulus"] = law.face_ks;
    } else {
      j["kn"] = law.face_kn;  // per segment [N/m]
      j["ks"] = law.face_ks;
    }
    j["friction"] = f.tan_phi;
    j["tensile_strength"] = f.tensile_strength;
    j["cohesion"] = f.cohesion;
    j["healing"] = f.healing;
    j["lever"] = f.lever == FaceLever::wall_frame ? "wall_frame" : "rotated_corner";
    j["bonded"] = law.bond_at_start;
  }
  (void)m;
  return j;
}

}  // namespace

double total_mass(const Model& m) {
  double sum = 0.0;
  for (std::size_t i = 0; i < m.elements.size(); ++i)
    if (m.elements.active[i]) sum += m.elements.mass[i];
  return sum;
}

std::string probe_unit(const ProbeSpec& p) {
  switch (p.kind) {
    case ProbeKind::time_of_max:
    case ProbeKind::time_of_min:
    case ProbeKind::crossing:
    case ProbeKind::contact_duration:
      return "s";
    case ProbeKind::restitution:
    case ProbeKind::ratio:
      return "1";
    case ProbeKind::slope: {
      const std::string q = quantity_unit(p.quantity), x = p.against.empty() ? "s" : quantity_unit(p.against);
      if (x == "1") return q;
      if (x == "s" && q.size() > 2 && q.compare(q.size() - 2, 2, "/s") == 0) return q + "^2";  // m/s per s: m/s^2
      const std::string num = q.find('/') != std::string::npos ? "(" + q + ")" : q;
      return num + "/" + (x.find_first_of("/*") != std::string::npos ? "(" + x + ")" : x);
    }
    default:
      return quantity_unit(p.quantity);
  }
}

nlohmann::json resolved_case_si(const Case& c) {
  const Model& m = c.model;
  nlohmann::json j;
  j["units"] = "SI: m, s, kg, N, N/m, Pa, N*s/m, rad";
  j["title"] = c.title;
  j["thickness"] = m.thickness;
  j["gravity"] = vec(m.gravity);
  const Numerics& n = m.numerics;
  const Elements& e = m.elements;
  double rmin = std::numeric_limits<double>::infinity(), rmax = 0.0;
  std::size_t disks = 0, pres = 0, polygons = 0, active = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    rmin = std::min(rmin, e.radius[i]);
    rmax = std::max(rmax, e.radius[i]);
    (e.shape[i] == Shape::disk ? disks : e.shape[i] == Shape::pre ? pres : polygons) += 1;
    active += e.active[i];
  }
  j["numerics"] = {{"integrator", name_of(n.integrator)},
                   {"velocity_start", name_of(n.velocity_start)},
                   {"dt", n.dt},
                   {"duration", n.duration},
                   {"steps", static_cast<std::int64_t>(std::ceil(n.duration / n.dt - 1e-9))},
                   {"skin", n.skin > 0.0 ? n.skin : (e.size() ? 0.25 * rmin : 0.0)},
                   {"allow_unstable", n.allow_unstable},
                   {"energy_limit", n.energy_limit},
                   {"max_step_fraction", n.max_step_fraction}};
  if (n.reorder_every > 0) j["numerics"]["reorder_every"] = n.reorder_every;  // (absent: 0, never)
  if (std::isfinite(n.guard_reach)) j["numerics"]["guard_reach"] = n.guard_reach;  // (absent: +inf, every element)
  nlohmann::json mats = nlohmann::json::array();
  for (const Material& mt : m.materials) mats.push_back({{"name", mt.name}, {"density", mt.density}});
  j["materials"] = mats;
  nlohmann::json laws = nlohmann::json::array();
  const std::size_t nm = m.materials.size();
  for (std::size_t a = 0; a < nm; ++a)
    for (std::size_t b = a; b < nm; ++b) {
      const std::int32_t k = m.law_of_pair[a * nm + b];
      if (k < 0) continue;
      nlohmann::json l = law_json(m, m.laws[static_cast<std::size_t>(k)]);
      l["between"] = {m.materials[a].name, m.materials[b].name};
      laws.push_back(l);
    }
  j["contacts"] = laws;
  j["elements"] = {{"count", e.size()}, {"active", active}, {"disks", disks}, {"pres", pres},
                   {"radius_min", e.size() ? rmin : 0.0}, {"radius_max", rmax}, {"total_mass", total_mass(m)}};
  if (polygons > 0) j["elements"]["polygons"] = polygons;  // (radius: a polygon's circumradius)
  nlohmann::json walls = nlohmann::json::array();
  for (const Wall& w : m.walls) {
    nlohmann::json wj = {{"name", w.name}, {"kind", w.kind == WallKind::point ? "point" : "segment"},
                         {"a", vec(w.a)}, {"material", m.materials[static_cast<std::size_t>(w.material)].name},
                         {"driven", w.drive >= 0}};
    if (w.kind != WallKind::point) wj["b"] = vec(w.b);
    walls.push_back(wj);
  }
  j["walls"] = walls;
  if (m.discharge.enabled)
    j["discharge"] = {{"slit", m.walls[static_cast<std::size_t>(m.discharge.slit)].name},
                      {"outlet_depth", m.discharge.outlet_depth}, {"keystone_after", m.discharge.keystone_after},
                      {"open_at", m.discharge.open_at}};
  if (m.base_plate.enabled)
    j["base_plate"] = {{"velocity", vec(m.base_plate.velocity)}, {"driven", m.base_plate.drive >= 0},
                       {"normal_gravity", m.base_plate.normal_gravity},
                       {"regularisation_speed", m.base_plate.regularisation_speed},
                       {"friction", m.base_plate.friction}};
  nlohmann::json series = nlohmann::json::array();
  for (const std::string& s : c.output.series) series.push_back({{"quantity", s}, {"unit", quantity_unit(s)}});
  j["output"] = {{"every", c.output.every}, {"series", series}, {"vtk", c.output.vtk}, {"vtk_every", c.output.vtk_every},
                 {"pictures", c.output.pictures}, {"picture_every", c.output.picture_every},
                 {"picture_times", c.output.picture_times}, {"picture_width", c.output.picture_width},
                 {"picture_max_force", c.output.picture_max_force ? nlohmann::json(*c.output.picture_max_force)
                                                                  : nlohmann::json(nullptr)}};
  if (!c.output.wall_contacts.empty()) j["output"]["wall_contacts"] = c.output.wall_contacts;
  if (c.output.bond_breaks) j["output"]["bond_breaks"] = true;
  if (c.output.contacts) j["output"]["contacts"] = true, j["output"]["contacts_every"] = c.output.contacts_every;
  const StopSpec& st = c.stop;
  nlohmann::json stop = {{"settle_window", st.settle_window}, {"settle_min_time", st.settle_min_time}};
  stop["settled_increment"] = st.settled_increment ? nlohmann::json(*st.settled_increment) : nlohmann::json(nullptr);
  stop["settled_increment_factor"] =
      st.settled_increment_factor ? nlohmann::json(*st.settled_increment_factor) : nlohmann::json(nullptr);
  stop["settled_force_ratio"] = st.settled_force_ratio ? nlohmann::json(*st.settled_force_ratio) : nlohmann::json(nullptr);
  if (!st.after_peak_quantity.empty())
    stop["after_peak"] = {{"quantity", st.after_peak_quantity}, {"drop", st.after_peak_drop}, {"from", st.after_peak_from}};
  j["stop"] = stop;
  nlohmann::json probes = nlohmann::json::array();
  for (const ProbeSpec& p : c.probes) {
    nlohmann::json pj = {{"name", p.name}, {"kind", name_of(p.kind)}, {"unit", probe_unit(p)}};
    if (!p.quantity.empty()) pj["quantity"] = p.quantity;
    if (p.kind == ProbeKind::value) pj["at"] = p.at ? nlohmann::json(*p.at) : nlohmann::json("end");
    if (p.kind == ProbeKind::ratio) {
      pj["of"] = p.of;
      pj["over"] = p.over;
    } else if (p.kind == ProbeKind::restitution || p.kind == ProbeKind::contact_duration) {
      pj["element"] = p.element;
      pj[p.other_is_wall ? "wall" : "other"] = p.other_is_wall ? nlohmann::json(m.walls[p.other].name) : nlohmann::json(p.other);
    } else if (p.kind != ProbeKind::value) {
      pj["from"] = p.from;
      pj["to"] = std::isfinite(p.to) ? nlohmann::json(p.to) : nlohmann::json("end");
    }
    if (p.kind == ProbeKind::crossing) pj["level"] = p.level, pj["direction"] = p.direction;
    if (!p.against.empty()) pj["against"] = p.against;
    probes.push_back(pj);
  }
  j["probes"] = probes;
  return j;
}

}  // namespace dem
