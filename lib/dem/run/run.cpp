#include "dem/run/run.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cmath>
#include <ctime>
#include <limits>
#include <optional>
#include <utility>
#include <unistd.h>

#include <fmt/format.h>
#include <toml++/impl/version.h>

#include "dem/run/quantities.hpp"
#include "dem/cases/text.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/resolved_case.hpp"
#include "dem/run/vtk_writer.hpp"
#include "dem/run/picture/force_network.hpp"

#include "dem2d_version.hpp"  // generated at build time: DEM2D_VERSION
#ifndef DEM2D_BUILD_TYPE
#define DEM2D_BUILD_TYPE "unknown"
#endif

namespace dem {

static std::string compiler() {
#if defined(__clang__)
  return "clang++ " __clang_version__;
#elif defined(__GNUC__)
  return "g++ " __VERSION__;
#else
  return "unknown compiler";
#endif
}

nlohmann::json provenance() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::tm utc{};
  gmtime_r(&now, &utc);  // not std::gmtime: its one static buffer is shared by the runs of a study (threads)
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return {{"code_version", DEM2D_VERSION}, {"build_type", DEM2D_BUILD_TYPE}, {"date", date}, {"machine", host},
          {"compiler", compiler()},
          {"libraries", fmt::format("toml++ {}.{}.{}, nlohmann_json {}.{}.{}, fmt {}.{}.{}", TOML_LIB_MAJOR, TOML_LIB_MINOR,
                                    TOML_LIB_PATCH, NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                                    NLOHMANN_JSON_VERSION_PATCH, FMT_VERSION / 10000, FMT_VERSION / 100 % 100,
                                    FMT_VERSION % 100)}};
}

namespace {

// CPU time of this run: the calling thread's clock and the run's worker threads (not the process's: a study
// runs several runs in one process), for the time loop's cpu_seconds.
double run_cpu_seconds(const Simulation& sim) {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec) + sim.worker_cpu_seconds();
}

/// Tracks one probe during the run.
struct ProbeState {
  const ProbeSpec* spec = nullptr;
  QuantityFn q;
  double prev_t = 0.0, prev_v = 0.0;
  std::optional<double> value;
  double extreme = 0.0;
  bool have_extreme = false;
  double vn_prev = 0.0;  // normal relative velocity of the state before this step (approach positive)
  double extreme_t = 0.0;                                    // time_of_max / time_of_min
  double st = 0.0, sq = 0.0, stt = 0.0, stq = 0.0, sn = 0.0;  // slope: least-squares sums; mean: sq, sn
  std::optional<double> crossing;
  // restitution: the first contact event; duration: steps with force
  Vec2 n_prev, n_in;     // contact normal of the state before this step, and at the first touch
  double vn_in = 0.0, vn_out = 0.0;
  bool touched = false, separated = false;
  QuantityFn x;                                               // slope `against`: abscissa (else t)
  double x0 = 0.0;                                            //   its first value in the window
  std::int64_t force_steps = 0;
  bool in_contact = false;
};

// i, j: element ids (the case's numbering), mapped to the arrays' indices here (spatial_order.hpp)
Vec2 contact_normal(const Simulation& s, std::uint32_t i, std::uint32_t j, bool wall) {
  i = s.index_of(i);
  if (!wall) j = s.index_of(j);
  const Elements& e = s.model().elements;
  const Vec2 c{e.x[i], e.y[i]};
  const Vec2 o = wall ? closest_point(s.model().walls[j], c) : Vec2{e.x[j], e.y[j]};
  const Vec2 d = o - c;
  return d * (1.0 / norm(d));
}

Vec2 body_velocity(const Simulation& s, std::uint32_t j, bool wall) {
  const Model& m = s.model();
  if (wall) {
    const Wall& w = m.walls[j];
    return w.drive >= 0 ? m.drives[static_cast<std::size_t>(w.drive)].at(s.time()) : Vec2{};
  }
  j = s.index_of(j);
  return {m.elements.vx[j], m.elements.vy[j]};
}

/// Normal relative velocity of i towards j (or wall j) along n, approach positive.
double approach_velocity(const Simulation& s, std::uint32_t i, std::uint32_t j, bool wall, Vec2 n) {
  const Elements& e = s.model().elements;
  const std::uint32_t ii = s.index_of(i);
  const Vec2 vi{e.vx[ii], e.vy[ii]};
  return dot(vi - body_velocity(s, j, wall), n);
}

bool is_tty() { return isatty(STDERR_FILENO) != 0; }

/// A quantity compiled with its location in the case file for errors.
QuantityFn compile_located(const std::string& name, const std::string& location, const std::string& key, const Model& m) {
  try {
    return compile_quantity(name, m);
  } catch (const std::invalid_argument& e) {
    throw CaseError(fmt::format("{}: {}: {}", location, key, e.what()));
  }
}

/// The energy scale of a run (what the blow-up bound is made of) [J]: the kinetic and elastic energy
/// after the first step `e1`, plus the work gravity can do over the region the elements can reach, plus
/// the work the drives can do.
struct EnergyScale {
  double total = 0.0, gravity_work = 0.0, drive_work = 0.0, drop = 0.0;
};
EnergyScale energy_scale(const Model& m, double e1) {
  EnergyScale es;
  const Elements& e = m.elements;
  const double g = norm(m.gravity);
  const double T = m.numerics.duration;
  double mass = 0.0, v0 = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i] || e.motion[i] != Motion::free) continue;
    mass += e.mass[i];
    v0 = std::max(v0, std::hypot(e.vx[i], e.vy[i]));
  }
  double v_drive = 0.0;
  for (const VelocityHistory& h : m.drives)
    for (const Vec2& v : h.v) v_drive = std::max(v_drive, norm(v));
  if (g > 0.0) {
    // the drop along g: across the region of the elements and walls; if no wall lies beyond every
    // element along g, an element may also fall freely for the whole run
    const Vec2 down = m.gravity * (1.0 / g);
    double lo = 1e300, hi = -1e300, elem_low = -1e300, wall_low = -1e300;
    for (std::size_t i = 0; i < e.size(); ++i) {
      const double p = dot(down, Vec2{e.x[i], e.y[i]});
      lo = std::min(lo, p - e.radius[i]);
      hi = std::max(hi, p + e.radius[i]);
      elem_low = std::max(elem_low, p + e.radius[i]);
    }
    for (const Wall& w : m.walls)
      for (const Vec2& q : {w.a, w.b}) {
        const double p = dot(down, q);
        lo = std::min(lo, p);
        hi = std::max(hi, p);
        wall_low = std::max(wall_low, p);
      }
    es.drop = hi - lo;
    const bool moving_walls = std::any_of(m.walls.begin(), m.walls.end(), [](const Wall& w) { return w.drive >= 0; });
    if (wall_low < elem_low || moving_walls) es.drop += (v0 + v_drive) * T + 0.5 * g * T * T;
    es.gravity_work = mass * g * es.drop;
  }
  // drives: an element thrown by a wall moving at v leaves at most at 2v; and the drive may lift the
  // weight of every element over its travel
  es.drive_work = v_drive > 0.0 ? 0.5 * mass * 4.0 * v_drive * v_drive + mass * g * v_drive * T : 0.0;
  es.total = e1 + es.gravity_work + es.drive_work;
  return es;
}

// The run loop's own state, for checkpoints: the blow-up bound and the settle window, then per probe
// its accumulators. Every member of ProbeState that changes during a run must be listed here, or a
// restart is no longer bit for bit (tests/lib/outputs_tests.cpp).
struct LoopState {
  double energy_limit = 0.0, potential0 = 0.0;
  EnergyScale scale;
  std::int64_t quiet_steps = 0;
  double peak_so_far = 0.0;  // [stop] after_peak: the largest |q| so far
  // [discharge]: the time of the last removal (a disk out, or a keystone), and every keystone removed
  double last_release = 0.0;
  bool slit_opened = false;  // open_at reached (the case's wall is closed until then)
  struct Keystone {
    double t = 0.0, element = 0.0, x = 0.0, y = 0.0;
  };
  std::vector<Keystone> keystones;
};
constexpr std::size_t kLoopNumbers = 11;  // then the probes' numbers, then 4 per keystone
constexpr std::size_t kProbeNumbers = 26;
std::vector<double> loop_state(const LoopState& l, const std::vector<ProbeState>& probes) {
  std::vector<double> v{l.energy_limit,       l.potential0, l.scale.total, l.scale.gravity_work, l.scale.drive_work,
                        l.scale.drop, static_cast<double>(l.quiet_steps), l.peak_so_far, l.last_release,
                        static_cast<double>(l.keystones.size()), l.slit_opened ? 1.0 : 0.0};
  for (const ProbeState& p : probes) {
    v.insert(v.end(), {p.prev_t, p.prev_v, p.value ? 1.0 : 0.0, p.value.value_or(0.0), p.extreme,
                       p.have_extreme ? 1.0 : 0.0, p.vn_prev, p.extreme_t, p.st, p.sq, p.stt, p.stq, p.sn,
                       p.crossing ? 1.0 : 0.0, p.crossing.value_or(0.0), p.n_prev.x, p.n_prev.y, p.n_in.x, p.n_in.y,
                       p.vn_in, p.vn_out, p.touched ? 1.0 : 0.0, p.separated ? 1.0 : 0.0,
                       static_cast<double>(p.force_steps), p.in_contact ? 1.0 : 0.0, p.x0});
  }
  for (const LoopState::Keystone& k : l.keystones) v.insert(v.end(), {k.t, k.element, k.x, k.y});
  return v;
}
void restore_loop_state(const std::vector<double>& v, LoopState& l, std::vector<ProbeState>& probes) {
  const std::size_t n_keystones = v.size() >= kLoopNumbers ? static_cast<std::size_t>(v[9]) : 0;
  if (v.size() != kLoopNumbers + kProbeNumbers * probes.size() + 4 * n_keystones)
    throw CaseError("restart: the checkpoint's run state does not match the case's probes");
  l.energy_limit = v[0], l.potential0 = v[1];
  l.scale.total = v[2], l.scale.gravity_work = v[3], l.scale.drive_work = v[4], l.scale.drop = v[5];
  l.quiet_steps = static_cast<std::int64_t>(v[6]);
  l.peak_so_far = v[7];
  l.last_release = v[8];
  l.slit_opened = v[10] != 0.0;
  l.keystones.clear();
  for (std::size_t k = 0; k < n_keystones; ++k) {
    const double* q = v.data() + kLoopNumbers + kProbeNumbers * probes.size() + 4 * k;
    l.keystones.push_back({q[0], q[1], q[2], q[3]});
  }
  const double* x = v.data() + kLoopNumbers;
  for (ProbeState& p : probes) {
    p.prev_t = x[0], p.prev_v = x[1];
    if (x[2] != 0.0) p.value = x[3];
    else p.value.reset();
    p.extreme = x[4], p.have_extreme = x[5] != 0.0;
    p.vn_prev = x[6], p.extreme_t = x[7];
    p.st = x[8], p.sq = x[9], p.stt = x[10], p.stq = x[11], p.sn = x[12];
    if (x[13] != 0.0) p.crossing = x[14];
    else p.crossing.reset();
    p.n_prev = {x[15], x[16]}, p.n_in = {x[17], x[18]};
    p.vn_in = x[19], p.vn_out = x[20];
    p.touched = x[21] != 0.0, p.separated = x[22] != 0.0;
    p.force_steps = static_cast<std::int64_t>(x[23]), p.in_contact = x[24] != 0.0;
    p.x0 = x[25];
    x += kProbeNumbers;
  }
}

/// Stop criterion `[stop] after_peak`: true once |q| has fallen to (1 − drop) × the largest |q| seen
/// so far (updated here). A load–displacement test is then past its peak and can end.
bool past_peak(double value, double drop, double& peak) {
  peak = std::max(peak, std::abs(value));
  return peak > 0.0 && std::abs(value) <= (1.0 - drop) * peak;
}

}  // namespace

void check_outputs(const Case& c) {
  for (std::size_t k = 0; k < c.output.series.size(); ++k) {
    const std::string at = k < c.output.series_locations.size() ? c.output.series_locations[k] : c.path.string();
    compile_located(c.output.series[k], at, "output.series", c.model);
  }
  for (std::size_t k = 0; k < c.probes.size(); ++k) {
    const ProbeSpec& p = c.probes[k];
    const std::string at = p.location.empty() ? c.path.string() : p.location;
    if (!p.quantity.empty()) compile_located(p.quantity, at, fmt::format("probe.{}.quantity", k), c.model);
    if (!p.against.empty()) compile_located(p.against, at, fmt::format("probe.{}.against", k), c.model);
  }
  if (!c.stop.after_peak_quantity.empty())
    compile_located(c.stop.after_peak_quantity, c.path.string(), "stop.after_peak.quantity", c.model);
}

RunResult run_case(Case c, const RunOptions& opt) {
  const double limit = check_case(c);  // throws CaseError before anything runs
  check_outputs(c);
  // A restart reads its checkpoint first (it may lie in the output folder, which is cleared below).
  std::optional<Checkpoint> restart;
  if (!opt.restart.empty()) {
    restart = read_checkpoint(opt.restart);
    if (!opt.restart_other_case && restart->case_hash != case_hash(c))
      throw CaseError(fmt::format("{}: --restart {}: the checkpoint belongs to another case ({}, case hash {}, this "
                                  "case {}); to start this case from it, use --start-from",
                                  c.path.string(), opt.restart.string(), restart->case_path, restart->case_hash,
                                  case_hash(c)));
  }
  // What summary.json reports of the case as given (counts, masses, walls: the state at the start), taken
  // before the model moves into the Simulation; c.model is empty from here on (read sim.model()).
  const nlohmann::json resolved_si = resolved_case_si(c);
  Simulation sim(std::move(c.model));
  sim.set_threads(opt.threads, opt.min_per_thread);
  const Model& m = std::as_const(sim).model();  // the const overload: the mutable one voids the rebuild test
  const std::int64_t total_steps = std::llround(std::ceil(m.numerics.duration / m.numerics.dt - 1e-9));

  // Outputs.
  const bool write = !opt.out_dir.empty();
  std::vector<QuantityFn> series;
  for (const auto& name : c.output.series) series.push_back(compile_quantity(name, m));
  std::vector<ProbeState> probes;
  for (const auto& p : c.probes) {
    ProbeState s;
    s.spec = &p;
    if (!p.quantity.empty()) {
      s.q = compile_quantity(p.quantity, m);
      s.prev_v = s.q(sim);
    } else {
      s.n_prev = contact_normal(sim, p.element, p.other, p.other_is_wall);  // ids (the case's numbering)
      s.vn_prev = approach_velocity(sim, p.element, p.other, p.other_is_wall, s.n_prev);
    }
    probes.push_back(s);
  }
  for (auto& p : probes)
    if (!p.spec->against.empty()) {
      try {
        p.x = compile_quantity(p.spec->against, m);
      } catch (const std::invalid_argument& e) {
        throw CaseError(
            fmt::format("{}: probe \"{}\": against: {}", c.path.string(), p.spec->name, e.what()));
      }
    }
  QuantityFn peak_quantity;
  if (!c.stop.after_peak_quantity.empty()) {
    try {
      peak_quantity = compile_quantity(c.stop.after_peak_quantity, m);
    } catch (const std::invalid_argument& e) {
      throw CaseError(fmt::format("{}: stop.after_peak.quantity: {}", c.path.string(), e.what()));
    }
  }
  // Blow-up criteria (README "Running a case"):
  // - energy: the mechanical energy change (kinetic + elastic + potential − initial potential) may not
  //   exceed F × the run's energy scale (energy_scale()); F = 4, or 2/(1 − r²) below the stability
  //   limit (r = Δt/limit: a stable explicit scheme's energy swings by up to 1/(1 − r²) at the limit);
  //   numerics.energy_limit replaces the bound;
  // - kinematics: no element moves more than numerics.max_step_fraction × its radius in one step.
  LoopState loop;
  loop.energy_limit = m.numerics.energy_limit;
  loop.potential0 = sim.energies().potential;  // the blow-up criterion's zero of potential energy
  const double ratio = m.numerics.dt / limit;
  const double energy_factor = ratio < 1.0 ? std::max(4.0, 2.0 / (1.0 - ratio * ratio)) : 4.0;
  const double gravity_norm = norm(m.gravity);
  // The run's state from a checkpoint: the Simulation's, and the loop's (probes, energy bound, settle
  // window).
  loop.last_release = sim.time();
  if (restart) {
    restore_simulation(sim, *restart, opt.restart_other_case);
    loop.last_release = sim.time();  // a discharge from a saved state: its clock starts at the state's time
    if (opt.restart_other_case) loop.potential0 = sim.energies().potential;
    else restore_loop_state(restart->loop, loop, probes);
    if (loop.slit_opened) sim.open_wall(static_cast<std::uint32_t>(m.discharge.slit));  // opened before the checkpoint
  }
  double& energy_limit = loop.energy_limit;
  const double& potential0 = loop.potential0;
  EnergyScale& scale = loop.scale;
  std::int64_t& quiet_steps = loop.quiet_steps;  // consecutive steps meeting every settle criterion
  double& peak_so_far = loop.peak_so_far;
  const std::int64_t first_step = sim.steps();

  // Outputs: a cleared folder (never two runs mixed), summary.json saying "running" until the end,
  // the series as series.csv.partial until it is complete; every write checked (OutputError).
  StreamedFile csv;
  std::vector<std::pair<double, std::string>> snapshots;
  const std::filesystem::path checkpoint_file = write ? opt.out_dir / "checkpoint.bin" : std::filesystem::path();
  if (write) {
    prepare_run_folder(opt.out_dir);
    write_file_atomic(opt.out_dir / "summary.json",
                      nlohmann::json{{"case", c.path.string()}, {"overrides", c.overrides}, {"provenance", provenance()},
                                     {"status", "running"}, {"case_hash", case_hash(c)}}
                              .dump(2) + "\n");
    if (!series.empty()) {
      csv.open(opt.out_dir / "series.csv");
      // one header line, each column with its unit ("t [s]"): pandas.read_csv reads it with its
      // defaults; the case and the code version are in summary.json
      std::string head;
      for (std::size_t k = 0; k < series.size(); ++k) head += (k ? "," : "") + csv_field(series_header(c.output.series[k]));
      csv.write(head + "\n");
    }
    if (c.output.vtk) std::filesystem::create_directories(opt.out_dir / "vtk");
    if (c.output.any_pictures()) std::filesystem::create_directories(opt.out_dir / "pictures");
  }
  std::string row;
  std::int64_t row_step = -1, snapshot_step = -1;  // the step of the last row / snapshot written
  auto write_row = [&] {
    if (!csv.is_open()) return;
    row_step = sim.steps();
    row.clear();
    for (std::size_t k = 0; k < series.size(); ++k) {
      if (k) row += ',';
      row += fmt::format("{:.17g}", series[k](sim));
    }
    row += '\n';
    csv.write(row);
  };
  std::optional<std::int64_t> checkpoint_step;
  auto checkpoint = [&] {
    if (!write) return;
    write_checkpoint(checkpoint_file, sim, c, loop_state(loop, probes));
    checkpoint_step = sim.steps();
  };
  auto snapshot = [&] {
    if (!write || !c.output.vtk) return;
    snapshot_step = sim.steps();
    const std::string name = fmt::format("snapshot_{:09d}.vtp", sim.steps());
    write_vtp(opt.out_dir / "vtk" / name, sim);
    snapshots.emplace_back(sim.time(), "vtk/" + name);
  };
  // Force-network pictures: the steps of the chosen times (the first step at or after each time).
  std::vector<std::int64_t> picture_steps;
  if (write && c.output.any_pictures()) {
    auto step_of = [&](double t) { return std::llround(std::ceil(t / m.numerics.dt - 1e-9)); };
    if (c.output.picture_every > 0.0)
      for (std::int64_t n = 1;; ++n) {
        const std::int64_t k = step_of(static_cast<double>(n) * c.output.picture_every);
        if (k > total_steps) break;
        picture_steps.push_back(k);
      }
    for (double t : c.output.picture_times)
      if (step_of(t) <= total_steps) picture_steps.push_back(step_of(t));
    std::sort(picture_steps.begin(), picture_steps.end());
    picture_steps.erase(std::unique(picture_steps.begin(), picture_steps.end()), picture_steps.end());
  }
  std::size_t next_picture = static_cast<std::size_t>(
      std::lower_bound(picture_steps.begin(), picture_steps.end(), sim.steps()) - picture_steps.begin());
  std::int64_t picture_step = -1;  // the step of the last picture written
  std::vector<std::pair<double, std::string>> pictures;
  const PictureOptions picture_options{static_cast<int>(c.output.picture_width), c.output.picture_max_force, 0.0};
  auto picture = [&](bool wanted) {
    while (next_picture < picture_steps.size() && picture_steps[next_picture] <= sim.steps()) {
      wanted = wanted || picture_steps[next_picture] == sim.steps();
      ++next_picture;
    }
    if (!wanted || !write || picture_step == sim.steps()) return;
    picture_step = sim.steps();
    const std::string name = fmt::format("picture_{:09d}.png", sim.steps());
    write_force_network_png(opt.out_dir / "pictures" / name, sim, picture_options);
    pictures.emplace_back(sim.time(), "pictures/" + name);
  };
  write_row();
  snapshot();
  picture(c.output.pictures);

  RunResult res;
  res.stability_limit = limit;
  res.status = "completed";
  const bool show = opt.progress && is_tty();
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(sim);
  auto last_print = t0;
  const std::int64_t check_every = 64;
  // Contact forces (each linear element–element contact's resultant) are kept by every step if anything
  // the case asks for may read them after any step (a series, picture, snapshot, probe, stop criterion or
  // checkpoint); else only by the last step, and by the step that ends the run on a signal
  // (Simulation::keep_contact_forces: a reader of a step that did not keep them throws).
  bool series_forces = false;
  for (const auto& name : c.output.series) series_forces = series_forces || reads_contact_forces(name);
  const bool forces_every_step = series_forces || c.output.vtk || c.output.any_pictures() || !probes.empty() ||
                                 c.stop.any() || static_cast<bool>(peak_quantity) || opt.checkpoint_every > 0 ||
                                 opt.checkpoint_at_end;
  const auto slit = static_cast<std::uint32_t>(std::max(m.discharge.slit, 0));
  for (std::int64_t k = first_step; k < total_steps; ++k) {
    // [discharge] open_at: the gate opens at the first step that starts at or after open_at (derived
    // from the clock alone, so a restart opens it at the same point of the loop)
    if (m.discharge.enabled && !m.walls[slit].open && sim.time() >= m.discharge.open_at - 1e-9 * m.numerics.dt) {
      sim.open_wall(slit);
      loop.slit_opened = true;
      loop.last_release = sim.time();
    }
    sim.keep_contact_forces(forces_every_step || k + 1 == total_steps || interrupt_signal() != 0 ||
                            sim.steps() + 1 == opt.interrupt_at_step);
    sim.step();
    if (k == first_step && energy_limit <= 0.0) {
      const Energies e1 = sim.energies();
      scale = energy_scale(m, e1.kinetic + e1.elastic);
      energy_limit = energy_factor * scale.total + 1e-300;
    }
    // kinematic blow-up check: the largest increment of the step relative to the radius, found inside
    // the step by each thread over its elements (Simulation::overstep)
    if (const Simulation::Overstep o = sim.overstep(); o.index != Simulation::Overstep::npos) {
      const Elements& e = m.elements;
      const std::size_t worst = o.index;
      res.status = "blow-up";
      res.message = fmt::format(
          "stopped at t = {:.6g} s (step {}): element {} moved {:.4g} m in one step, {:.4g} of its radius "
          "(numerics.max_step_fraction = {:.3g}: contacts would be missed) (the stability limit of this assembly "
          "is {:.6g} s, dt = {:.6g} s)",
          sim.time(), sim.steps(), sim.id_of(worst), std::hypot(e.dx[worst], e.dy[worst]), std::sqrt(o.fraction2),
          m.numerics.max_step_fraction, limit, m.numerics.dt);
      break;
    }
    // discharge (core/discharge.hpp): disks below the outlet line leave the run; a stalled arch loses
    // its keystone once no disk has left for keystone_after
    // (the model is taken mutable only in a step that removes a disk: that voids the rebuild test the
    // step's integration made for the next step, which then makes its own)
    if (m.discharge.enabled && m.walls[slit].open) {
      if (may_discharge(m) && remove_discharged(sim.model()) > 0) {
        loop.last_release = sim.time();
      } else if (m.discharge.keystone_after > 0.0 &&
                 sim.time() - loop.last_release >= m.discharge.keystone_after - 1e-9 * m.numerics.dt) {
        if (const auto k = keystone(m)) {
          sim.model().elements.active[*k] = 0;
          loop.last_release = sim.time();
          loop.keystones.push_back({sim.time(), static_cast<double>(sim.id_of(*k)), m.elements.x[*k], m.elements.y[*k]});
        }
      }
    }
    // probes
    for (auto& p : probes) {
      const ProbeSpec& s = *p.spec;
      if (s.kind == ProbeKind::value) {
        if (s.at && !p.value) {
          const double v = p.q(sim);
          if (sim.time() >= *s.at - 1e-12 * m.numerics.dt) {
            const double w = (sim.time() - *s.at) / (sim.time() - p.prev_t);
            p.value = w <= 0.0 ? v : v + (p.prev_v - v) * w;
          }
          p.prev_t = sim.time();
          p.prev_v = v;
        }
      } else if (s.kind == ProbeKind::slope) {
        const double t = sim.time();
        if (t >= s.from - 1e-12 && t <= s.to + 1e-12) {
          double tt = t - s.from;  // centred on `from` (or the first abscissa) for conditioning
          if (p.x) {
            if (p.sn == 0.0) p.x0 = p.x(sim);
            tt = p.x(sim) - p.x0;
          }
          const double v = p.q(sim);
          p.st += tt;
          p.sq += v;
          p.stt += tt * tt;
          p.stq += tt * v;
          p.sn += 1.0;
        }
      } else if (s.kind == ProbeKind::max || s.kind == ProbeKind::min || s.kind == ProbeKind::time_of_max ||
                 s.kind == ProbeKind::time_of_min || s.kind == ProbeKind::mean || s.kind == ProbeKind::crossing) {
        const double t = sim.time();
        if (t >= s.from - 1e-12 && t <= s.to + 1e-12) {
          const double v = p.q(sim);
          if (s.kind == ProbeKind::mean) {
            p.sq += v;
            p.sn += 1.0;
          } else if (s.kind == ProbeKind::crossing) {
            const double a = p.prev_v - s.level, b = v - s.level;
            const bool up = a < 0.0 && b >= 0.0, down = a > 0.0 && b <= 0.0;
            if (!p.crossing && t > p.prev_t && ((s.direction >= 0 && up) || (s.direction <= 0 && down)))
              p.crossing = p.prev_t + (t - p.prev_t) * (a / (a - b));
          } else {
            const bool want_max = s.kind == ProbeKind::max || s.kind == ProbeKind::time_of_max;
            if (!p.have_extreme || (want_max ? v > p.extreme : v < p.extreme)) {
              p.extreme = v;
              p.extreme_t = t;
            }
            p.have_extreme = true;
          }
          p.prev_t = t;
          p.prev_v = v;
        } else if (s.kind == ProbeKind::crossing && t < s.from) {
          p.prev_t = t;  // the sample before the window starts the first interval
          p.prev_v = p.q(sim);
        }
      } else {
        const ContactView cv = sim.contact(sim.index_of(s.element), s.other_is_wall ? s.other : sim.index_of(s.other),
                                           s.other_is_wall);
        p.in_contact = cv.fn != 0.0;
        if (p.in_contact) ++p.force_steps;
        if (s.kind == ProbeKind::restitution) {
          // the first contact event, along the normal at first touch: the approach velocity of the
          // state before the first step with force, the separation velocity after the first step
          // without force that follows (velocities are v_k, after the step's forces)
          if (!p.touched && p.in_contact) {
            p.touched = true;
            p.n_in = p.n_prev;
            p.vn_in = p.vn_prev;
          } else if (p.touched && !p.separated && !p.in_contact) {
            p.separated = true;
            p.vn_out = approach_velocity(sim, s.element, s.other, s.other_is_wall, p.n_in);
          }
          if (!p.touched) {
            p.n_prev = contact_normal(sim, s.element, s.other, s.other_is_wall);
            p.vn_prev = approach_velocity(sim, s.element, s.other, s.other_is_wall, p.n_prev);
          }
        }
      }
    }
    // settle: every criterion given holds at every step of a window of consecutive steps
    if (c.stop.any() && sim.time() >= c.stop.settle_min_time) {
      const double inc = (c.stop.settled_increment || c.stop.settled_increment_factor) ? mean_increment(sim) : 0.0;
      bool quiet = true;
      if (c.stop.settled_increment) quiet = inc < *c.stop.settled_increment;
      if (quiet && c.stop.settled_increment_factor)
        quiet = inc < *c.stop.settled_increment_factor * m.numerics.dt * m.numerics.dt * gravity_norm;  // Kiyama
      if (quiet && c.stop.settled_force_ratio) quiet = unbalanced_force_ratio(sim) < *c.stop.settled_force_ratio;
      quiet_steps = quiet ? quiet_steps + 1 : 0;
      if (quiet_steps >= c.stop.settle_window) {
        res.status = "settled";
        res.message = fmt::format("settled at t = {:.6g} s (step {}): the criteria held for {} consecutive steps",
                                  sim.time(), sim.steps(), quiet_steps);
        break;
      }
    }
    if (peak_quantity && sim.time() >= c.stop.after_peak_from &&
        past_peak(peak_quantity(sim), c.stop.after_peak_drop, peak_so_far)) {
      res.status = "past peak";
      res.message = fmt::format("stopped at t = {:.6g} s (step {}): {} fell to {:.4g} of its peak {:.6g}", sim.time(),
                                sim.steps(), c.stop.after_peak_quantity, 1.0 - c.stop.after_peak_drop, peak_so_far);
      break;
    }
    const bool last = k + 1 == total_steps;
    if (c.output.every > 0 && sim.steps() % c.output.every == 0 && !last) write_row();
    if (c.output.vtk_every > 0 && sim.steps() % c.output.vtk_every == 0 && !last) snapshot();
    if (next_picture < picture_steps.size() && picture_steps[next_picture] == sim.steps()) picture(false);
    if (sim.steps() % check_every == 0 || last) {
      const Energies en = sim.energies();
      const double mech = en.kinetic + en.elastic + (en.potential - potential0);
      if (!std::isfinite(mech) || mech > energy_limit) {
        res.status = "blow-up";
        res.message = fmt::format("stopped at t = {:.6g} s (step {}): {} (the stability limit of this assembly is {:.6g} s, dt = {:.6g} s)",
                                  sim.time(), sim.steps(),
                                  std::isfinite(mech) ? fmt::format("runaway energy {:.4g} J above the bound {:.4g} J{}", mech, energy_limit,
                                                                    m.numerics.energy_limit > 0.0 ? std::string(" (numerics.energy_limit)") :
                                                                    fmt::format(" = {:.3g} × (energy after the first step + gravity over {:.4g} m + drives {:.4g} J)",
                                                                                energy_factor, scale.drop, scale.drive_work))
                                                      : std::string("the energy is not a number"),
                                  limit, m.numerics.dt);
        break;
      }

      if (show) {
        const auto now = std::chrono::steady_clock::now();
        if (now - last_print > std::chrono::milliseconds(500)) {
          const double secs = std::chrono::duration<double>(now - t0).count();
          fmt::print(stderr, "\r  t = {:.4g} s / {:.4g} s ({:.0f} %), {:.3g} steps/s   ", sim.time(), m.numerics.duration,
                     100.0 * static_cast<double>(k + 1) / static_cast<double>(total_steps),
                     static_cast<double>(k + 1) / secs);
          last_print = now;
        }
      }
    }
    // Checkpoints, and SIGINT / SIGTERM (or the test hook): stop here and write everything.
    if (opt.checkpoint_every > 0 && sim.steps() % opt.checkpoint_every == 0 && !last) checkpoint();
    const int sig = interrupt_signal();
    // (a signal during a step that did not keep the contact forces: the next step keeps them and stops)
    if ((sig != 0 && sim.contact_forces_current()) || (opt.interrupt_at_step > 0 && sim.steps() == opt.interrupt_at_step)) {
      res.status = "interrupted";
      res.message = fmt::format("stopped at t = {:.6g} s (step {}) by {}", sim.time(), sim.steps(),
                                sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : sig ? fmt::format("signal {}", sig) : "request");
      break;
    }
  }
  if (show) fmt::print(stderr, "\r{:70s}\r", "");
  const auto t1 = std::chrono::steady_clock::now();
  const double cpu1 = run_cpu_seconds(sim);
  // The final row and snapshot (an interrupted run does not repeat the ones of its last step).
  const bool interrupted = res.status == "interrupted";
  if (!(interrupted && row_step == sim.steps())) write_row();
  if (!(interrupted && snapshot_step == sim.steps())) snapshot();
  picture(c.output.pictures);

  res.steps = sim.steps();
  res.time = sim.time();
  res.wall_seconds = std::chrono::duration<double>(t1 - t0).count();
  res.cpu_seconds = cpu1 - cpu0;
  std::size_t n_active = 0;
  for (auto a : m.elements.active) n_active += a;
  res.element_steps_per_second =
      res.wall_seconds > 0 ? static_cast<double>(n_active) * static_cast<double>(res.steps) / res.wall_seconds : 0.0;
  for (auto& p : probes) {
    const ProbeSpec& s = *p.spec;
    std::optional<double> v;
    switch (s.kind) {
      case ProbeKind::value:
        v = s.at ? p.value : std::optional<double>(p.q(sim));
        break;
      case ProbeKind::max:
      case ProbeKind::min:
        if (p.have_extreme) v = p.extreme;
        break;
      case ProbeKind::time_of_max:
      case ProbeKind::time_of_min:
        if (p.have_extreme) v = p.extreme_t;
        break;
      case ProbeKind::mean:
        if (p.sn > 0.0) v = p.sq / p.sn;
        break;
      case ProbeKind::crossing:
        v = p.crossing;
        break;
      case ProbeKind::slope:
        if (p.sn >= 2.0) v = (p.sn * p.stq - p.st * p.sq) / (p.sn * p.stt - p.st * p.st);
        break;
      case ProbeKind::restitution:
        // the first contact event only; none if it never touched, never separated, or did not approach
        if (p.touched && p.separated && p.vn_in > 0.0) v = -p.vn_out / p.vn_in;
        break;
      case ProbeKind::contact_duration:
        if (!p.in_contact && p.force_steps > 0) v = static_cast<double>(p.force_steps) * m.numerics.dt;
        break;
    }
    if (v && !std::isfinite(*v)) v.reset();
    res.probes[s.name] = v;
  }

  nlohmann::json probes_json = nlohmann::json::object();
  for (const ProbeSpec& s : c.probes) {  // each value with its SI unit
    const auto& v = res.probes.at(s.name);
    probes_json[s.name] = {{"value", v ? nlohmann::json(*v) : nlohmann::json(nullptr)}, {"unit", probe_unit(s)}};
  }
  const Energies en = sim.energies();
  res.summary = {
      {"case", c.path.string()},
      {"title", c.title},
      {"source", c.source},
      {"overrides", c.overrides},
      {"provenance", provenance()},
      {"status", res.status},
      {"message", res.message},
      {"steps", res.steps},
      {"time", res.time},
      {"dt", m.numerics.dt},
      {"integrator", m.numerics.integrator == Integrator::k18 ? "K18" : "K19"},
      {"stability_limit", limit},
      {"elements", n_active},
      {"contacts", sim.contact_count()},
      {"rebuilds", sim.rebuilds()},
      {"wall_seconds", res.wall_seconds},
      {"cpu_seconds", res.cpu_seconds},
      {"element_steps_per_second", res.element_steps_per_second},
      {"energies", {{"kinetic", en.kinetic}, {"potential", en.potential}, {"elastic", en.elastic}}},
      {"probes", probes_json},
      {"units", {{"time", "s"}, {"dt", "s"}, {"stability_limit", "s"}, {"wall_seconds", "s"},
                 {"cpu_seconds", "s"}, {"element_steps_per_second", "1/s"}, {"energies", "J"}}},
      {"case_as_read", c.resolved},
      {"resolved_case", resolved_si},
  };
  res.summary["case_hash"] = case_hash(c);
  if (m.discharge.enabled) {
    const Discharged d = discharged(m);
    nlohmann::json ks = nlohmann::json::array();
    double keystone_mass = 0.0;
    for (const LoopState::Keystone& k : loop.keystones) {
      ks.push_back({{"time", k.t}, {"element", static_cast<std::int64_t>(k.element)}, {"x", k.x}, {"y", k.y}});
      keystone_mass += m.elements.mass[sim.index_of(static_cast<std::uint32_t>(k.element))];  // k.element: an id
    }
    double remaining_mass = 0.0;
    for (std::size_t i = 0; i < m.elements.size(); ++i)
      if (m.elements.active[i]) remaining_mass += m.elements.mass[i];
    res.summary["discharge"] = {{"discharged", d.count}, {"discharged_mass", d.mass}, {"remaining", n_active},
                                {"remaining_mass", remaining_mass}, {"keystones_removed", loop.keystones.size()},
                                {"keystone_mass", keystone_mass}, {"keystones", ks},
                                {"units", {{"mass", "kg (per thickness l of the model)"}, {"time", "s"}, {"x", "m"}}}};
  }
  if (!pictures.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& [t, name] : pictures) list.push_back({{"time", t}, {"file", name}});
    res.summary["pictures"] = list;
  }
  if (restart)
    res.summary["restart"] = {{"checkpoint", opt.restart.string()}, {"from_case", restart->case_path},
                              {"step", restart->step}, {"time", restart->time}, {"other_case", opt.restart_other_case},
                              {"checkpoint_written_by", restart->meta}};
  if (write) {
    if (res.status == "interrupted" || opt.checkpoint_at_end) checkpoint();
    if (checkpoint_step) res.summary["checkpoint"] = {{"file", "checkpoint.bin"}, {"step", *checkpoint_step}};
    csv.commit();
    if (c.output.vtk) write_pvd(opt.out_dir / "snapshots.pvd", snapshots);
    write_file_atomic(opt.out_dir / "summary.json", res.summary.dump(2) + "\n");
  }
  return res;
}

}  // namespace dem
