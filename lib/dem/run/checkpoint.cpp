#include "dem/run/checkpoint.hpp"

#include <bit>
#include <cstring>
#include <type_traits>

#include <fmt/format.h>

#include "dem/run/checkpoint_checks.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"

namespace dem {

namespace {

constexpr char kMagic[] = "DEM2D-CHECKPOINT\n";

// A new field in one of these types must be added to write_state / read_state below; these
// assertions fail the build until it is (the sizes are those of the fields listed there).
static_assert(sizeof(LinearSlot) == 88 + sizeof(RollingState), "LinearSlot changed: add the new field to the checkpoint (checkpoint.cpp)");
static_assert(sizeof(RollingState) == 40, "RollingState changed: add the new field to the checkpoint (checkpoint.cpp)");
static_assert(sizeof(LinearContactState) == 32 && sizeof(LinearContactResultant) == 32 && sizeof(SlotPair) == 8 &&
                  sizeof(LinearPairSlots) == 6 * sizeof(std::vector<double>) + alignof(std::vector<double>),
              "LinearPairSlots changed: add the new field to the checkpoint (checkpoint.cpp)");
static_assert(sizeof(SegmentState) == 32 && sizeof(FaceConstants) == 48 && sizeof(FaceForce) == 32 &&
                  sizeof(FaceHistory) == 24 + 32 * kMaxSegments &&
                  sizeof(FaceSlot) == 16 + 48 + sizeof(FaceHistory) + 32 + 16,
              "FaceSlot changed: add the new field to the checkpoint (checkpoint.cpp)");
static_assert(sizeof(Elements) == 24 * sizeof(std::vector<double>),
              "Elements changed: add the new field to the checkpoint (checkpoint.cpp)");
static_assert(sizeof(Wall) == sizeof(std::string) + 80, "Wall changed: add the new field to the checkpoint (checkpoint.cpp)");

std::uint64_t fnv1a(std::string_view s, std::uint64_t h = 1469598103934665603ull) {
  for (unsigned char ch : s) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

struct Writer {
  std::string out;
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put_str(std::string_view s) {
    put<std::uint64_t>(s.size());
    out.append(s);
  }
  template <class T>
  void put_vec(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    for (const T& x : v) put(x);
  }
};

struct Reader {
  std::string_view in;
  std::size_t pos = 0;
  std::string what;  // for errors
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    if (pos + sizeof(T) > in.size()) throw CaseError(fmt::format("{}: truncated checkpoint", what));
    T v;
    std::memcpy(&v, in.data() + pos, sizeof v);
    pos += sizeof v;
    return v;
  }
  bool get_bool(const std::string& field) {  // a bool is read as its byte: any other value than 0 or 1 is refused
    const auto b = get<std::uint8_t>();
    check_flag(what, field, b);
    return b != 0;
  }
  std::string get_str() {
    const auto n = get<std::uint64_t>();
    if (n > in.size() - pos) throw CaseError(fmt::format("{}: truncated checkpoint", what));
    std::string s(in.substr(pos, n));
    pos += n;
    return s;
  }
  template <class T>
  void get_vec(std::vector<T>& v) {
    const auto n = get<std::uint64_t>();
    if (n > (in.size() - pos) / sizeof(T)) throw CaseError(fmt::format("{}: truncated checkpoint", what));
    v.resize(n);
    for (T& x : v) x = get<T>();
  }
};

// version 6: every linear slot carries its rolling state (R1–R6), zero when its law does not roll
void put_rolling(Writer& w, const RollingState& s) { w.put(s.mk), w.put(s.kr), w.put(s.cr), w.put(s.arm), w.put(s.m); }
RollingState get_rolling(Reader& r) {
  RollingState s;
  s.mk = r.get<double>(), s.kr = r.get<double>(), s.cr = r.get<double>(), s.arm = r.get<double>(), s.m = r.get<double>();
  return s;
}
void put_slot(Writer& w, const LinearSlot& s) {
  w.put(s.i), w.put(s.j), w.put(s.law), w.put(s.touching), w.put(s.eta_n), w.put(s.eta_s);
  w.put(s.h.en), w.put(s.h.es), w.put(s.f.fn), w.put(s.f.fs), w.put(s.f.opened), w.put(s.nx), w.put(s.ny);
  put_rolling(w, s.rolling);
}
void get_slot(Reader& r, LinearSlot& s) {
  s.i = r.get<std::uint32_t>(), s.j = r.get<std::uint32_t>(), s.law = r.get<std::int32_t>();
  s.touching = r.get<std::uint8_t>(), s.eta_n = r.get<double>(), s.eta_s = r.get<double>();
  s.h.en = r.get<double>(), s.h.es = r.get<double>(), s.f.fn = r.get<double>(), s.f.fs = r.get<double>();
  s.f.opened = r.get_bool("linear wall slot opened"), s.nx = r.get<double>(), s.ny = r.get<double>();
  s.rolling = get_rolling(r);
}
void put_slot(Writer& w, const FaceSlot& s) {
  w.put(s.i), w.put(s.j), w.put(s.law), w.put(s.touching);
  w.put(s.c.kn), w.put(s.c.ks), w.put(s.c.eta_n), w.put(s.c.eta_s), w.put(s.c.half_length), w.put(s.c.segment_area);
  w.put(s.h.theta1), w.put(s.h.theta2), w.put(s.h.geometric_start);
  for (const SegmentState& g : s.h.seg) w.put(g.u), w.put(g.pe), w.put(g.qe), w.put(g.linked), w.put(g.intact);
  w.put(s.f.p), w.put(s.f.q), w.put(s.f.p_moment), w.put(s.f.links), w.put(s.f.any_tensile), w.put(s.nx), w.put(s.ny);
}
void get_slot(Reader& r, FaceSlot& s) {
  s.i = r.get<std::uint32_t>(), s.j = r.get<std::uint32_t>(), s.law = r.get<std::int32_t>();
  s.touching = r.get<std::uint8_t>();
  s.c.kn = r.get<double>(), s.c.ks = r.get<double>(), s.c.eta_n = r.get<double>(), s.c.eta_s = r.get<double>();
  s.c.half_length = r.get<double>(), s.c.segment_area = r.get<double>();
  s.h.theta1 = r.get<double>(), s.h.theta2 = r.get<double>(), s.h.geometric_start = r.get<std::uint8_t>();
  for (SegmentState& g : s.h.seg) {
    g.u = r.get<double>(), g.pe = r.get<double>(), g.qe = r.get<double>();
    g.linked = r.get<std::uint8_t>(), g.intact = r.get<std::uint8_t>();
  }
  s.f.p = r.get<double>(), s.f.q = r.get<double>(), s.f.p_moment = r.get<double>(), s.f.links = r.get<int>();
  s.f.any_tensile = r.get_bool("face slot any_tensile"), s.nx = r.get<double>(), s.ny = r.get<double>();
}
// The linear element–element slots: the fields of a LinearSlot but ContactForce::opened (always false in
// a stored slot: a contact that opens is reset at once).
void put_slots(Writer& w, const LinearPairSlots& v) {
  w.put<std::uint64_t>(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) {
    const LinearContactState& s = v.state[k];
    const LinearContactResultant f = v.touching[k] ? v.resultant[k] : LinearContactResultant{};  // else: stale
    w.put(v.pair[k].i), w.put(v.pair[k].j), w.put(v.law[k]), w.put(v.touching[k]), w.put(s.eta_n), w.put(s.eta_s);
    w.put(s.h.en), w.put(s.h.es), w.put(f.fn), w.put(f.fs), w.put(f.nx), w.put(f.ny);
    put_rolling(w, v.with_rolling ? v.rolling[k] : RollingState{});
  }
}
void get_slots(Reader& r, LinearPairSlots& v) {
  const auto n = r.get<std::uint64_t>();
  if (n > r.in.size()) throw CaseError(fmt::format("{}: truncated checkpoint", r.what));
  v.clear();
  v.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    LinearContactState& s = v.state[k];
    LinearContactResultant& f = v.resultant[k];
    v.pair[k].i = r.get<std::uint32_t>(), v.pair[k].j = r.get<std::uint32_t>(), v.law[k] = r.get<std::int32_t>();
    v.touching[k] = r.get<std::uint8_t>(), s.eta_n = r.get<double>(), s.eta_s = r.get<double>();
    s.h.en = r.get<double>(), s.h.es = r.get<double>(), f.fn = r.get<double>(), f.fs = r.get<double>();
    f.nx = r.get<double>(), f.ny = r.get<double>();
    const RollingState ro = get_rolling(r);
    if (v.with_rolling) v.rolling[k] = ro;  // a case without rolling drops it (only another case can differ)
  }
}
template <class Slot>
void put_slots(Writer& w, const std::vector<Slot>& v) {
  w.put<std::uint64_t>(v.size());
  for (const Slot& s : v) put_slot(w, s);
}
template <class Slot>
void get_slots(Reader& r, std::vector<Slot>& v) {
  const auto n = r.get<std::uint64_t>();
  if (n > r.in.size()) throw CaseError(fmt::format("{}: truncated checkpoint", r.what));
  v.assign(n, Slot{});
  for (Slot& s : v) get_slot(r, s);
}

}  // namespace

/// Friend of Simulation: reads and writes its private state.
namespace {
// "the case FILE" (or "the case" when it is not named): what a restart into it that does not fit names.
std::string case_named(const RestartInto& into) {
  return into.case_file.empty() ? std::string("the case") : fmt::format("the case {}", into.case_file);
}
std::string material_name(const Model& m, std::int32_t k) {
  return k >= 0 && static_cast<std::size_t>(k) < m.materials.size() ? m.materials[static_cast<std::size_t>(k)].name : "?";
}
}  // namespace

struct SimulationAccess {
  static std::string write(const Simulation& sim) {
    Writer w;
    const Elements& e = sim.m_.elements;
    w.put<std::uint64_t>(e.size());
    // the order of the elements (spatial_order.hpp): the id of the element at each index
    std::vector<std::uint32_t> ids(e.size());
    for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = sim.id_of(k);
    w.put_vec(ids);
    for (const auto* v : {&e.x, &e.y, &e.phi, &e.dx, &e.dy, &e.dphi, &e.vx, &e.vy, &e.omega, &e.fx, &e.fy, &e.moment})
      w.put_vec(*v);
    w.put_vec(e.active);
    w.put<std::uint64_t>(sim.m_.walls.size());
    for (const Wall& wl : sim.m_.walls) w.put(wl.a), w.put(wl.b), w.put(wl.increment), w.put(wl.force);
    w.put_vec(sim.candidates_);
    sim.require_contact_forces("write_checkpoint");  // saved: a restart's first outputs report them
    put_slots(w, sim.linear_pairs_);
    put_slots(w, sim.linear_walls_);
    put_slots(w, sim.face_pairs_);
    put_slots(w, sim.face_walls_);
    w.put_vec(sim.x_ref_);
    w.put_vec(sim.y_ref_);
    w.put_vec(sim.wall_ref_);
    w.put(sim.skin_), w.put(sim.time_), w.put(sim.step_), w.put(sim.rebuilds_), w.put(sim.preloading_);
    w.put(sim.plate_travel_.displacement), w.put(sim.plate_travel_.travel);  // version 5: base plate travel (M21)
    // Polygon elements (docs/model.md §5): their contact points, so that states compare in full (tests); run
    // refuses checkpoints of such a case, and a restore reads no such part (no checkpoint holds one).
    if (sim.polygons_)
      for (const auto* list : {&sim.polygon_pairs_, &sim.polygon_walls_}) {
        w.put<std::uint64_t>(list->size());
        for (const PolygonSlot& p : *list) {
          w.put(p.i), w.put(p.j), w.put(p.law), w.put(p.swapped);
          w.put<std::uint64_t>(p.corners.size());
          for (const CornerSlot& c : p.corners)
            w.put(c.side), w.put(c.corner), w.put(c.eta_n), w.put(c.eta_s), w.put(c.h.en), w.put(c.h.es), w.put(c.f.fn),
                w.put(c.f.fs), w.put(c.px), w.put(c.py), w.put(c.nx), w.put(c.ny);
        }
      }
    return w.out;
  }

  static void read(Simulation& sim, const Checkpoint& ck, bool other_case, const RestartInto& into) {
    const std::string& file = ck.file;
    const std::string the_case = case_named(into);
    Reader r{ck.state, 0, file};
    Elements& e = sim.m_.elements;
    const auto n = r.get<std::uint64_t>();
    if (n != e.size())
      throw CaseError(fmt::format("{}: restart: the checkpoint has {} elements, {} has {}", file, n, the_case, e.size()));
    {  // the elements take the checkpoint's order first (their properties come from the case)
      std::vector<std::uint32_t> ids;
      r.get_vec(ids);
      try {
        sim.restore_order(ids);
      } catch (const std::invalid_argument& x) {
        throw CaseError(fmt::format("{}: corrupt checkpoint ({})", file, x.what()));
      }
    }
    for (auto* v : {&e.x, &e.y, &e.phi, &e.dx, &e.dy, &e.dphi, &e.vx, &e.vy, &e.omega, &e.fx, &e.fy, &e.moment}) {
      r.get_vec(*v);
      if (v->size() != n) throw CaseError(fmt::format("{}: corrupt checkpoint (element arrays)", file));
    }
    r.get_vec(e.active);
    check_element_state(file, e);
    const auto nw = r.get<std::uint64_t>();
    if (nw != sim.m_.walls.size())
      throw CaseError(fmt::format("{}: restart: the checkpoint has {} walls, {} has {}", file, nw, the_case, sim.m_.walls.size()));
    for (Wall& wl : sim.m_.walls) wl.a = r.get<Vec2>(), wl.b = r.get<Vec2>(), wl.increment = r.get<Vec2>(), wl.force = r.get<Vec2>();
    check_wall_state(file, sim.m_.walls);
    read_contacts(sim, r, !other_case);
    check_references(file, sim.x_ref_, sim.y_ref_, sim.wall_ref_, n, nw);
    sim.skin_ = r.get<double>(), sim.time_ = r.get<double>(), sim.step_ = r.get<std::int64_t>();
    sim.rebuilds_ = r.get<std::int64_t>(), sim.preloading_ = r.get_bool("preloading");
    sim.plate_travel_.displacement = r.get<Vec2>(), sim.plate_travel_.travel = r.get<double>();
    check_finite(file, "plate displacement", {sim.plate_travel_.displacement.x, sim.plate_travel_.displacement.y});
    if (!std::isfinite(sim.plate_travel_.travel) || sim.plate_travel_.travel < 0.0)
      corrupt_checkpoint(file, "plate travel", fmt::format("{} m", sim.plate_travel_.travel));
    check_clock(sim, ck);
    sim.tested_step_ = -1;  // the next step makes its own rebuild test
    sim.travel_ = Simulation::kTravelUnknown;  // not saved: the exact rebuild test until the next rebuild
    sim.forces_step_ = sim.step_;  // the contact resultants were saved with the step (write_state)
    if (r.pos != r.in.size()) throw CaseError(fmt::format("{}: corrupt checkpoint (trailing state bytes)", file));
    if (other_case) start_other_case(sim, file, the_case);
    // derived from the slot lists (not saved): made once they are final, since another case may drop wall
    // slots (the sweep's shares and the contact index would otherwise still count them)
    sim.index_contacts();
  }
  // The candidate pairs and the four slot lists, each checked (checkpoint_checks.hpp; their laws only for the
  // same case: another case gives them its own, start_other_case), then the reference positions of the
  // rebuild test.
  static void read_contacts(Simulation& sim, Reader& r, bool laws) {
    const std::string& file = r.what;
    r.get_vec(sim.candidates_);
    check_candidates(file, sim.candidates_, sim.m_.elements.size());
    get_slots(r, sim.linear_pairs_);
    check_slots(file, sim.linear_pairs_, sim.m_, laws);
    get_slots(r, sim.linear_walls_);
    check_slots(file, sim.linear_walls_, sim.m_, laws);
    get_slots(r, sim.face_pairs_);
    check_slots(file, sim.face_pairs_, sim.m_, false, laws);
    get_slots(r, sim.face_walls_);
    check_slots(file, sim.face_walls_, sim.m_, true, laws);
    r.get_vec(sim.x_ref_);
    r.get_vec(sim.y_ref_);
    r.get_vec(sim.wall_ref_);
  }
  // The state's clock: that of the header, a skin and a rebuild count that can be.
  static void check_clock(const Simulation& sim, const Checkpoint& ck) {
    if (!std::isfinite(sim.skin_) || sim.skin_ < 0.0) corrupt_checkpoint(ck.file, "skin", fmt::format("{} m", sim.skin_));
    if (sim.time_ != ck.time || sim.step_ != ck.step)
      corrupt_checkpoint(ck.file, "clock", fmt::format("step {} at t = {} s, the header says step {} at t = {} s", sim.step_,
                                                       sim.time_, ck.step, ck.time));
    if (sim.rebuilds_ < 0) corrupt_checkpoint(ck.file, "rebuilds", fmt::format("{} is negative", sim.rebuilds_));
  }
  // Another case: each slot takes the new case's law of its material pair, of the same kind.
  static void start_other_case(Simulation& sim, const std::string& file, const std::string& the_case) {
    const Elements& e = sim.m_.elements;
    const Model& m = sim.m_;
    // A wall the new case opens (a silo's slit in discharge) has no contacts: they are dropped.
    auto drop_open = [&](auto& slots) {
      std::erase_if(slots, [&](const auto& s) { return m.walls[s.j].open; });
    };
    drop_open(sim.linear_walls_);
    drop_open(sim.face_walls_);
    for (std::size_t k = 0; k < sim.linear_pairs_.size(); ++k) {
      const SlotPair p = sim.linear_pairs_.pair[k];
      const std::int32_t law = m.law_index(e.material[p.i], e.material[p.j]);
      if (law < 0 || m.laws[static_cast<std::size_t>(law)].kind != LawKind::linear)
        throw CaseError(fmt::format("{}: restart: element {} and element {}: {} has no linear contact law between \"{}\" and \"{}\"",
                                    file, sim.id_of(p.i), sim.id_of(p.j), the_case, material_name(m, e.material[p.i]),
                                    material_name(m, e.material[p.j])));
      sim.linear_pairs_.law[k] = law;
    }
    auto relaw = [&](auto& slots, bool wall, LawKind kind) {
      for (auto& s : slots) {
        const std::int32_t mj = wall ? m.walls[s.j].material : e.material[s.j];
        const std::int32_t law = m.law_index(e.material[s.i], mj);
        if (law < 0 || m.laws[static_cast<std::size_t>(law)].kind != kind)
          throw CaseError(fmt::format("{}: restart: element {} and {} {}: {} has no {} contact law between \"{}\" and \"{}\"", file,
                                      sim.id_of(s.i), wall ? "wall" : "element", wall ? s.j : sim.id_of(s.j), the_case,
                                      kind == LawKind::linear ? "linear" : "face", material_name(m, e.material[s.i]),
                                      material_name(m, mj)));
        s.law = law;
      }
    };
    relaw(sim.linear_walls_, true, LawKind::linear);
    relaw(sim.face_pairs_, false, LawKind::face);
    relaw(sim.face_walls_, true, LawKind::face);
    // A touching contact whose new law rolls but that did not roll in the checkpoint starts its rolling now,
    // from a zero moment (R2, R5); one whose new law does not roll forgets it.
    auto roll_start = [&](std::int32_t law, std::uint32_t i, std::uint32_t j, bool wall, std::uint8_t touching, RollingState& r) {
      const PairLaw& l = m.laws[static_cast<std::size_t>(law)];
      if (!l.rolling.enabled) r = {};
      else if (touching && r.kr == 0.0 && r.arm == 0.0) sim.start_rolling(l, i, j, wall, 0.0, r);
    };
    LinearPairSlots& lp = sim.linear_pairs_;
    if (lp.with_rolling)
      for (std::size_t k = 0; k < lp.size(); ++k) roll_start(lp.law[k], lp.pair[k].i, lp.pair[k].j, false, lp.touching[k], lp.rolling[k]);
    for (LinearSlot& s : sim.linear_walls_) roll_start(s.law, s.i, s.j, true, s.touching, s.rolling);
  }
};

std::string simulation_state(const Simulation& sim) { return SimulationAccess::write(sim); }

std::string case_hash(const Case& c) {
  nlohmann::json j = c.resolved;
  if (j.is_object()) {
    j.erase("output");
    if (j.contains("numerics") && j["numerics"].is_object()) j["numerics"].erase("duration");
  }
  return fmt::format("{:016x}", fnv1a(j.dump()));
}

void write_checkpoint(const std::filesystem::path& file, const Simulation& sim, const Case& c,
                      const std::vector<double>& loop) {
  Writer w;
  w.out.append(kMagic, sizeof kMagic - 1);
  w.put(kCheckpointVersion);
  w.put<std::uint32_t>(0x01020304u);
  w.put_str(case_hash(c));
  w.put_str(c.path.string());
  w.put_str(nlohmann::json{{"case", c.path.string()}, {"overrides", c.overrides}, {"provenance", provenance()}}.dump());
  w.put(sim.steps());
  w.put(sim.time());
  w.put(sim.dt());
  w.put_str(SimulationAccess::write(sim));
  w.put_vec(loop);
  w.put(checkpoint_checksum(w.out));
  write_file_atomic(file, w.out);
}

std::uint64_t checkpoint_checksum(std::string_view bytes) { return fnv1a(bytes); }

// A checkpoint is an input, as a case is: every error reading it is a CaseError (exit status 2), never an
// OutputError (4: an output could not be written).
Checkpoint read_checkpoint(const std::filesystem::path& file) {
  std::string bytes;
  try {
    bytes = read_file(file);
  } catch (const OutputError& e) {
    throw CaseError(e.what());
  }
  return parse_checkpoint(bytes, file.string());
}

Checkpoint parse_checkpoint(std::string_view bytes, const std::string& what) {
  if (bytes.compare(0, sizeof kMagic - 1, kMagic) != 0)
    throw CaseError(fmt::format("{}: not a dem2d checkpoint", what));
  if (bytes.size() < sizeof kMagic - 1 + 8 + 8) throw CaseError(fmt::format("{}: truncated checkpoint", what));
  Reader r{bytes, sizeof kMagic - 1, what};
  const auto version = r.get<std::uint32_t>();
  if (version != kCheckpointVersion)
    throw CaseError(fmt::format("{}: checkpoint format version {}, this dem2d reads version {}", what, version, kCheckpointVersion));
  if (r.get<std::uint32_t>() != 0x01020304u) throw CaseError(fmt::format("{}: checkpoint written with another byte order", what));
  std::uint64_t sum;
  std::memcpy(&sum, bytes.data() + bytes.size() - 8, 8);
  if (sum != fnv1a(std::string_view(bytes).substr(0, bytes.size() - 8)))
    throw CaseError(fmt::format("{}: checkpoint checksum mismatch (the file is damaged)", what));
  r.in = std::string_view(bytes).substr(0, bytes.size() - 8);
  Checkpoint ck;
  ck.file = what;
  ck.case_hash = r.get_str();
  ck.case_path = r.get_str();
  try {
    ck.meta = nlohmann::json::parse(r.get_str());
  } catch (const nlohmann::json::exception&) {
    throw CaseError(fmt::format("{}: corrupt checkpoint (meta)", what));
  }
  ck.step = r.get<std::int64_t>();
  ck.time = r.get<double>();
  ck.dt = r.get<double>();
  ck.state = r.get_str();
  r.get_vec(ck.loop);
  if (r.pos != r.in.size()) throw CaseError(fmt::format("{}: corrupt checkpoint (trailing bytes)", what));
  check_checkpoint_header(ck);
  check_finite(what, "run state", std::vector<double>(ck.loop.begin(), ck.loop.begin() + std::min<std::size_t>(ck.loop.size(), 11)));
  return ck;
}

void restore_simulation(Simulation& sim, const Checkpoint& ck, bool other_case, const RestartInto& into) {
  if (ck.dt != sim.dt()) {
    const std::string at = !into.dt_location.empty() ? into.dt_location : into.case_file;
    throw CaseError(fmt::format("{}: restart: the checkpoint was written with dt = {:.17g} s, {} has dt = {:.17g} s{}", ck.file, ck.dt,
                                case_named(into), sim.dt(), at.empty() ? "" : fmt::format(" ({}: numerics.dt)", at)));
  }
  SimulationAccess::read(sim, ck, other_case, into);
}

}  // namespace dem
