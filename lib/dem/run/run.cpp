#include "dem/run/run.hpp"
#include "dem/run/run_threads.hpp"

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
#include "dem/core/simulation.hpp"
#include "dem/core/stability.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/loop_state.hpp"
#include "dem/run/probe_state.hpp"
#include "dem/run/resolved_case.hpp"
#include "dem/run/run_outputs.hpp"

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

bool is_tty() { return isatty(STDERR_FILENO) != 0; }

/// A quantity compiled with its location in the case file for errors.
QuantityFn compile_located(const std::string& name, const std::string& location, const std::string& key, const Model& m) {
  try {
    return compile_quantity(name, m);
  } catch (const std::invalid_argument& e) {
    throw CaseError(fmt::format("{}: {}: {}", location, key, e.what()));
  }
}

/// Stop criterion `[stop] after_peak`: true once |q| has fallen to (1 − drop) × the largest |q| seen
/// so far (updated here). A load–displacement test is then past its peak and can end.
bool past_peak(double value, double drop, double& peak) {
  peak = std::max(peak, std::abs(value));
  return peak > 0.0 && std::abs(value) <= (1.0 - drop) * peak;
}

/// The code version recorded in a checkpoint ("unknown" if it has none).
std::string checkpoint_code_version(const Checkpoint& ck) {
  const auto p = nlohmann::json::json_pointer("/provenance/code_version");
  return ck.meta.is_object() && ck.meta.contains(p) && ck.meta[p].is_string() ? ck.meta[p].get<std::string>() : "unknown";
}

/// A restart's checkpoint, read before anything is written (it may lie in the output folder, which is
/// cleared later); none without --restart / --start-from. Throws CaseError for another case's checkpoint.
std::optional<Checkpoint> read_restart(const Case& c, const RunOptions& opt) {
  std::optional<Checkpoint> restart;
  if (!opt.restart.empty()) {
    restart = read_checkpoint(opt.restart);
    // A restart continues bit for bit only with the code that wrote the checkpoint: another version is refused
    // unless the user says so (and summary.json's "restart" records both versions).
    const std::string written = checkpoint_code_version(*restart);
    if (written != DEM2D_VERSION && !opt.restart_any_version)
      throw CaseError(fmt::format("{}: {} {}: the checkpoint was written by dem2d {}, this is dem2d {}: a restart continues "
                                  "bit for bit only with the code that wrote it. Use that version, or give "
                                  "--restart-any-version to continue with this one",
                                  opt.restart.string(), opt.restart_other_case ? "--start-from" : "--restart",
                                  opt.restart.string(), written, DEM2D_VERSION));
    if (!opt.restart_other_case && restart->case_hash != case_hash(c))
      throw CaseError(fmt::format("{}: --restart {}: the checkpoint belongs to another case ({}, case hash {}, this "
                                  "case {}); to start this case from it, use --start-from",
                                  c.path.string(), opt.restart.string(), restart->case_path, restart->case_hash,
                                  case_hash(c)));
  }
  return restart;
}

/// The quantity of `[stop] after_peak`, compiled; empty when the case has none.
QuantityFn after_peak_quantity(const Case& c, const Model& m) {
  QuantityFn peak_quantity;
  if (!c.stop.after_peak_quantity.empty()) {
    try {
      peak_quantity = compile_quantity(c.stop.after_peak_quantity, m);
    } catch (const std::invalid_argument& e) {
      throw CaseError(fmt::format("{}: stop.after_peak.quantity: {}",
                                  c.stop.after_peak_location.empty() ? c.path.string() : c.stop.after_peak_location, e.what()));
    }
  }
  return peak_quantity;
}

/// The loop's state at the start: the blow-up bound's zero of potential energy, the discharge clock;
/// after a restart the Simulation's state and (same case) the loop's from the checkpoint.
LoopState start_loop(Simulation& sim, const std::optional<Checkpoint>& restart, const RunOptions& opt,
                     std::vector<ProbeState>& probes, const RestartInto& into) {
  const Model& m = std::as_const(sim).model();
  LoopState loop;
  loop.energy_limit = m.numerics.energy_limit;
  loop.potential0 = sim.energies().potential;  // the blow-up criterion's zero of potential energy
  // The run's state from a checkpoint: the Simulation's, and the loop's (probes, energy bound, settle
  // window).
  loop.last_release = sim.time();
  if (restart) {
    restore_simulation(sim, *restart, opt.restart_other_case, into);
    loop.last_release = sim.time();  // a discharge from a saved state: its clock starts at the state's time
    if (opt.restart_other_case) loop.potential0 = sim.energies().potential;
    else restore_loop_state(restart->loop, loop, probes, restart->file);
    if (loop.slit_opened) sim.open_wall(static_cast<std::uint32_t>(m.discharge.slit));  // opened before the checkpoint
  }
  return loop;
}

/// Contact forces (each linear element–element contact's resultant) are kept by every step if anything
/// the case asks for may read them after any step (a series, picture, snapshot, contacts.csv, probe, stop criterion or
/// checkpoint); else only by the last step, and by the step that ends the run on a signal
/// (Simulation::keep_contact_forces: a reader of a step that did not keep them throws).
bool forces_every_step(const Case& c, bool probes, bool peak_quantity, const RunOptions& opt) {
  bool series_forces = false;
  for (const auto& name : c.output.series) series_forces = series_forces || reads_contact_forces(name);
  return series_forces || c.output.vtk || c.output.contacts || c.output.any_pictures() || probes || c.stop.any() || peak_quantity ||
         opt.checkpoint_every > 0 || opt.checkpoint_at_end;
}

/// The run in progress: what the time loop reads and changes, and each thing it does after a step.
struct RunLoop {
  const Case& c;
  const RunOptions& opt;
  Simulation& sim;
  const Model& m;
  LoopState& loop;
  std::vector<ProbeState>& probes;
  RunOutputs& out;
  const QuantityFn& peak_quantity;
  RunResult& res;
  double limit;               // the stability limit of the assembly [s]
  std::int64_t total_steps;
  double energy_factor;       // the blow-up bound's F (run_case)
  std::uint32_t slit;         // [discharge] the slit wall

  bool stop(const char* status, std::string message) {
    res.status = status;
    res.message = std::move(message);
    return true;
  }

  // [discharge] open_at: the gate opens at the first step that starts at or after open_at (derived
  // from the clock alone, so a restart opens it at the same point of the loop)
  void open_slit_when_due() {
    if (m.discharge.enabled && !m.walls[slit].open && sim.time() >= m.discharge.open_at - 1e-9 * m.numerics.dt) {
      sim.open_wall(slit);
      loop.slit_opened = true;
      loop.last_release = sim.time();
    }
  }

  // kinematic blow-up check: the largest increment of the step relative to the radius, found inside
  // the step by each thread over its elements (Simulation::overstep)
  bool overstepped() {
    const Simulation::Overstep o = sim.overstep();
    if (o.index == Simulation::Overstep::npos) return false;
    const Elements& e = m.elements;
    const std::size_t worst = o.index;
    return stop("blow-up",
                fmt::format("stopped at t = {:.6g} s (step {}): element {} moved {:.4g} m in one step, {:.4g} of its "
                            "radius (numerics.max_step_fraction = {:.3g}: contacts would be missed) (the stability "
                            "limit of this assembly is {:.6g} s, dt = {:.6g} s)",
                            sim.time(), sim.steps(), sim.id_of(worst), std::hypot(e.dx[worst], e.dy[worst]),
                            std::sqrt(o.fraction2), m.numerics.max_step_fraction, limit, m.numerics.dt));
  }

  // numerics.guard_reach (docs/model.md G7): the guard counted as partners only the elements within reach
  // of where the free elements were when it was evaluated; once one has moved farther, the guard of the
  // current positions is evaluated again (and becomes the new reference), and Δt above it stops the run
  std::vector<double> guard_x, guard_y;  // by element id: the positions the guard last assumed [m]
  void keep_guard_positions() {
    const Elements& e = m.elements;
    guard_x.assign(e.size(), 0.0), guard_y.assign(e.size(), 0.0);
    for (std::size_t i = 0; i < e.size(); ++i) guard_x[sim.id_of(i)] = e.x[i], guard_y[sim.id_of(i)] = e.y[i];
  }
  bool outside_guard_reach(bool now) {
    const double reach = m.numerics.guard_reach;
    if (!std::isfinite(reach)) return false;
    const Elements& e = m.elements;
    std::int64_t moved = -1;
    for (std::size_t i = 0; i < e.size() && !now && moved < 0; ++i) {
      if (!e.active[i] || e.motion[i] != Motion::free) continue;
      const std::uint32_t id = sim.id_of(i);
      if (std::hypot(e.x[i] - guard_x[id], e.y[i] - guard_y[id]) > reach) moved = static_cast<std::int64_t>(i);
    }
    if (!now && moved < 0) return false;
    const double before = limit;
    limit = assembly_stability_bound(m, registered_stability_terms(m)).limit;
    res.stability_limit = std::min(res.stability_limit, limit);
    keep_guard_positions();
    if ((m.numerics.dt <= limit && !std::isnan(limit)) || m.numerics.allow_unstable) return false;
    const std::string why = moved >= 0 ? fmt::format("element {} moved more than numerics.guard_reach = {:.4g} m from where the "
                                                     "time-step guard last assumed it", sim.id_of(static_cast<std::size_t>(moved)), reach)
                                       : std::string(sim.steps() > 0 ? "the run restarts from a checkpoint" : "the run starts (after its preloads)");
    return stop("refused", fmt::format("stopped at t = {:.6g} s (step {}): {}; the guard of the current positions is "
                                       "{:.6g} s (before: {:.6g} s), below dt = {:.6g} s (docs/model.md G7)",
                                       sim.time(), sim.steps(), why, limit, before, m.numerics.dt));
  }

  // discharge (core/discharge.hpp): disks below the outlet line leave the run; a stalled arch loses
  // its keystone once no disk has left for keystone_after
  // (the model is taken mutable only in a step that removes a disk: that voids the rebuild test the
  // step's integration made for the next step, which then makes its own)
  void discharge() {
    if (!m.discharge.enabled || !m.walls[slit].open) return;
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

  // settle: every criterion given holds at every step of a window of consecutive steps
  bool settled() {
    if (!c.stop.any() || sim.time() < c.stop.settle_min_time) return false;
    const double inc = (c.stop.settled_increment || c.stop.settled_increment_factor) ? mean_increment(sim) : 0.0;
    bool quiet = true;
    if (c.stop.settled_increment) quiet = inc < *c.stop.settled_increment;
    if (quiet && c.stop.settled_increment_factor)
      quiet = inc < *c.stop.settled_increment_factor * m.numerics.dt * m.numerics.dt * norm(m.gravity);  // Kiyama
    if (quiet && c.stop.settled_force_ratio) quiet = unbalanced_force_ratio(sim) < *c.stop.settled_force_ratio;
    loop.quiet_steps = quiet ? loop.quiet_steps + 1 : 0;  // consecutive steps meeting every settle criterion
    if (loop.quiet_steps < c.stop.settle_window) return false;
    return stop("settled", fmt::format("settled at t = {:.6g} s (step {}): the criteria held for {} consecutive steps",
                                       sim.time(), sim.steps(), loop.quiet_steps));
  }

  bool fell_past_peak() {
    if (!peak_quantity || sim.time() < c.stop.after_peak_from ||
        !past_peak(peak_quantity(sim), c.stop.after_peak_drop, loop.peak_so_far))
      return false;
    return stop("past peak", fmt::format("stopped at t = {:.6g} s (step {}): {} fell to {:.4g} of its peak {:.6g}",
                                         sim.time(), sim.steps(), c.stop.after_peak_quantity,
                                         1.0 - c.stop.after_peak_drop, loop.peak_so_far));
  }

  // energy blow-up check: the mechanical energy change against the bound (run_case)
  bool energy_ran_away() {
    const Energies en = sim.energies();
    const double mech = en.kinetic + en.elastic + (en.potential - loop.potential0);
    if (std::isfinite(mech) && !(mech > loop.energy_limit)) return false;
    const std::string what =
        std::isfinite(mech)
            ? fmt::format("runaway energy {:.4g} J above the bound {:.4g} J{}", mech, loop.energy_limit,
                          m.numerics.energy_limit > 0.0
                              ? std::string(" (numerics.energy_limit)")
                              : fmt::format(" = {:.3g} × (energy after the first step + gravity over {:.4g} m + drives "
                                            "{:.4g} J)", energy_factor, loop.scale.drop, loop.scale.drive_work))
            : std::string("the energy is not a number");
    return stop("blow-up", fmt::format("stopped at t = {:.6g} s (step {}): {} (the stability limit of this assembly is "
                                       "{:.6g} s, dt = {:.6g} s)", sim.time(), sim.steps(), what, limit, m.numerics.dt));
  }

  // SIGINT / SIGTERM (or the test hook): stop here and write everything
  // (a signal during a step that did not keep the contact forces: the next step keeps them and stops)
  bool interrupted() {
    const int sig = interrupt_signal();
    if (!((sig != 0 && sim.contact_forces_current()) || (opt.interrupt_at_step > 0 && sim.steps() == opt.interrupt_at_step)))
      return false;
    return stop("interrupted", fmt::format("stopped at t = {:.6g} s (step {}) by {}", sim.time(), sim.steps(),
                                           sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : sig ? fmt::format("signal {}", sig) : "request"));
  }

  // progress on a terminal, at most every half second
  /// The progress line, counted from this run's own start (a restart continues at its checkpoint's
  /// step: its share, speed and time left are those of the steps it runs).
  void print_progress(std::int64_t k, std::int64_t first_step, std::chrono::steady_clock::time_point t0,
                      std::chrono::steady_clock::time_point& last_print) const {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_print > std::chrono::milliseconds(500)) {
      const double secs = std::chrono::duration<double>(now - t0).count();
      const auto done = static_cast<double>(k + 1 - first_step), todo = static_cast<double>(total_steps - first_step);
      const double left = secs / done * (todo - done);
      fmt::print(stderr, "\r  t = {:.4g} s / {:.4g} s ({:.0f} % of this run), {:.3g} steps/s, ~{}:{:02} left   ", sim.time(),
                 m.numerics.duration, 100.0 * done / todo, done / secs, static_cast<long long>(left) / 60,
                 static_cast<long long>(left) % 60);
      last_print = now;
    }
  }

  void steps();
};

/// The time loop: steps until the end or a stop (blow-up, settled, past peak, interrupted), with the
/// outputs, probes and checkpoints of each step, progress on a terminal; sets the wall and CPU time.
void RunLoop::steps() {
  const bool show = opt.progress && is_tty();
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = run_cpu_seconds(sim);
  auto last_print = t0;
  const std::int64_t check_every = 64;
  const bool forces = forces_every_step(c, !probes.empty(), static_cast<bool>(peak_quantity), opt);
  const std::int64_t first_step = sim.steps();
  keep_guard_positions();
  // with guard_reach, the guard of the positions the loop starts from (after preloads; a restart's)
  const bool refused = std::isfinite(m.numerics.guard_reach) && outside_guard_reach(true);
  for (std::int64_t k = first_step; !refused && k < total_steps; ++k) {
    open_slit_when_due();
    sim.keep_contact_forces(forces || k + 1 == total_steps || interrupt_signal() != 0 ||
                            sim.steps() + 1 == opt.interrupt_at_step);
    sim.step();
    if (c.output.bond_breaks) out.bond_breaks(sim, sim.take_bond_breaks());
    if (k == first_step && loop.energy_limit <= 0.0) {
      const Energies e1 = sim.energies();
      loop.scale = energy_scale(m, e1.kinetic + e1.elastic);
      loop.energy_limit = energy_factor * loop.scale.total + 1e-300;
    }
    if (overstepped() || outside_guard_reach(false)) break;
    discharge();
    for (auto& p : probes) sample_probe(p, sim);
    if (settled() || fell_past_peak()) break;
    const bool last = k + 1 == total_steps;
    if (c.output.every > 0 && sim.steps() % c.output.every == 0 && !last) out.write_row(sim);
    if (c.output.vtk_every > 0 && sim.steps() % c.output.vtk_every == 0 && !last) out.snapshot(sim);
    if (c.output.contacts_every > 0 && sim.steps() % c.output.contacts_every == 0 && !last) out.contacts(sim);
    if (out.picture_due(sim.steps())) out.picture(sim, false);
    if (sim.steps() % check_every == 0 || last) {
      if (energy_ran_away()) break;
      if (show) print_progress(k, first_step, t0, last_print);
    }
    // Checkpoints, and SIGINT / SIGTERM (or the test hook): stop here and write everything.
    if (opt.checkpoint_every > 0 && sim.steps() % opt.checkpoint_every == 0 && !last)
      out.checkpoint(sim, loop_state(loop, probes));
    if (interrupted()) break;
  }
  if (show) fmt::print(stderr, "\r{:70s}\r", "");
  const auto t1 = std::chrono::steady_clock::now();
  const double cpu1 = run_cpu_seconds(sim);
  res.wall_seconds = std::chrono::duration<double>(t1 - t0).count();
  res.cpu_seconds = cpu1 - cpu0;
}

/// summary.json of a finished run (without its pictures, checkpoint and restart: run_case adds them).
nlohmann::json run_summary(const Case& c, const Simulation& sim, const RunResult& res, const nlohmann::json& resolved_si,
                           std::size_t n_active) {
  const Model& m = sim.model();
  nlohmann::json probes_json = nlohmann::json::object();
  for (const ProbeSpec& s : c.probes) {  // each value with its SI unit
    const auto& v = res.probes.at(s.name);
    probes_json[s.name] = {{"value", v ? nlohmann::json(*v) : nlohmann::json(nullptr)}, {"unit", probe_unit(s)}};
  }
  const Energies en = sim.energies();
  nlohmann::json summary = {
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
      {"stability_limit", res.stability_limit},
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
  summary["case_hash"] = case_hash(c);
  return summary;
}

/// summary.json's "discharge": what left the silo, what remains, the keystones removed.
nlohmann::json discharge_summary(const Simulation& sim, const LoopState& loop, std::size_t n_active) {
  const Model& m = sim.model();
  const Discharged d = discharged(m);
  nlohmann::json ks = nlohmann::json::array();
  double keystone_mass = 0.0;
  for (const LoopState::Keystone& k : loop.keystones) {
    ks.push_back({{"time", k.t}, {"element", static_cast<std::int64_t>(k.element)}, {"x", k.x}, {"y", k.y}});
    keystone_mass += m.elements.mass[sim.index_of(static_cast<std::uint32_t>(k.element))];  // k.element: an id
  }
  const double remaining_mass = total_mass(m);
  return {{"discharged", d.count}, {"discharged_mass", d.mass}, {"remaining", n_active},
          {"remaining_mass", remaining_mass}, {"keystones_removed", loop.keystones.size()},
          {"keystone_mass", keystone_mass}, {"keystones", ks},
          {"units", {{"mass", "kg (per thickness l of the model)"}, {"time", "s"}, {"x", "m"}}}};
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
    compile_located(c.stop.after_peak_quantity,
                    c.stop.after_peak_location.empty() ? c.path.string() : c.stop.after_peak_location,
                    "stop.after_peak.quantity", c.model);
}

/// The run once its output folder is open: the loop, the last outputs and the summary.
static RunResult run_opened(const Case& c, const RunOptions& opt, Simulation& sim, LoopState& loop, std::vector<ProbeState>& probes,
                     RunOutputs& out, const QuantityFn& peak_quantity, double limit, std::int64_t total_steps,
                     double energy_factor, const nlohmann::json& resolved_si, const std::optional<Checkpoint>& restart) {
  const Model& m = std::as_const(sim).model();
  out.write_row(sim);
  out.snapshot(sim);
  out.contacts(sim);
  out.picture(sim, c.output.pictures);

  RunResult res;
  res.stability_limit = limit;
  res.status = "completed";
  RunLoop run{c,     opt,         sim,           m,    loop, probes, out, peak_quantity, res, limit, total_steps,
              energy_factor, static_cast<std::uint32_t>(std::max(m.discharge.slit, 0))};
  run.steps();
  out.finish(sim, res.status == "interrupted");

  res.steps = sim.steps();
  res.time = sim.time();
  std::size_t n_active = 0;
  for (auto a : m.elements.active) n_active += a;
  res.element_steps_per_second =
      res.wall_seconds > 0 ? static_cast<double>(n_active) * static_cast<double>(res.steps) / res.wall_seconds : 0.0;
  for (const auto& p : probes) res.probes[p.spec->name] = probe_result(p, sim);
  ratio_results(probes, res.probes);

  res.summary = run_summary(c, sim, res, resolved_si, n_active);
  res.summary["threads"] = threads_summary(sim, opt.threads_asked > 0 ? opt.threads_asked : opt.threads);
  if (opt.timings) res.summary["timings"] = timings_summary(sim);
  if (m.discharge.enabled) res.summary["discharge"] = discharge_summary(sim, loop, n_active);
  if (restart)
    res.summary["restart"] = {{"checkpoint", opt.restart.string()}, {"from_case", restart->case_path},
                              {"step", restart->step}, {"time", restart->time}, {"other_case", opt.restart_other_case},
                              {"checkpoint_written_by", restart->meta},
                              {"code_version_differs", checkpoint_code_version(*restart) != DEM2D_VERSION}};
  // (an interrupted run writes a checkpoint to resume from, except a case with polygon elements or gap springs:
  // none yet)
  out.commit(sim, res.summary, (res.status == "interrupted" && m.polygons.empty() && sim.gap_springs().empty()) || opt.checkpoint_at_end,
             loop_state(loop, probes));
  return res;
}

RunResult run_case(Case c, const RunOptions& opt) {
  const double limit = check_case(c);  // throws CaseError before anything runs
  check_outputs(c);
  // What the checkpoint format does not hold yet: a polygon's contact points, a gap spring's bond.
  const bool gap_springs = std::any_of(c.model.laws.begin(), c.model.laws.end(), [](const PairLaw& l) { return l.gap.enabled; });
  const char* unsaved = !c.model.polygons.empty() ? "polygon elements (their contact points' histories"
                        : gap_springs            ? "gap springs (their bonds"
                                                 : nullptr;
  if (unsaved && (opt.checkpoint_every > 0 || opt.checkpoint_at_end || !opt.restart.empty()))
    throw CaseError(fmt::format("{}: checkpoints of a case with {} are not in the checkpoint format) are not written or read "
                                "yet; run it without --checkpoint-every, --checkpoint-at-end, --restart and --start-from",
                                c.path.string(), unsaved));
  const std::optional<Checkpoint> restart = read_restart(c, opt);
  if (restart && !opt.restart_other_case) {  // nothing left to run: refused, not "completed" with a row twice
    const std::int64_t steps = std::llround(std::ceil(c.model.numerics.duration / c.model.numerics.dt - 1e-9));
    if (restart->step >= steps)
      throw CaseError(fmt::format("{}: --restart {}: the checkpoint is at step {} (t = {:.6g} s), at or past the end of "
                                  "the run (numerics.duration = {:.6g} s, {} steps); give a longer numerics.duration",
                                  c.path.string(), opt.restart.string(), restart->step, restart->time,
                                  c.model.numerics.duration, steps));
  }
  // What summary.json reports of the case as given (counts, masses, walls: the state at the start), taken
  // before the model moves into the Simulation; c.model is empty from here on (read sim.model()).
  const nlohmann::json resolved_si = resolved_case_si(c);
  Simulation sim(std::move(c.model));
  sim.set_threads(opt.threads, opt.min_per_thread, opt.governed);
  sim.set_timings(opt.timings);
  const Model& m = std::as_const(sim).model();  // the const overload: the mutable one voids the rebuild test
  const std::int64_t total_steps = std::llround(std::ceil(m.numerics.duration / m.numerics.dt - 1e-9));

  // What the run reads: the series and the probes compiled against the state at the start.
  std::vector<QuantityFn> series;
  for (const auto& name : c.output.series) series.push_back(compile_quantity(name, m));
  std::vector<ProbeState> probes = start_probes(c, sim);
  const QuantityFn peak_quantity = after_peak_quantity(c, m);
  // Blow-up criteria (docs/running.md):
  // - energy: the mechanical energy change (kinetic + elastic + potential − initial potential) may not
  //   exceed F × the run's energy scale (energy_scale()); F = 4, or 2/(1 − r²) below the stability
  //   limit (r = Δt/limit: a stable explicit scheme's energy swings by up to 1/(1 − r²) at the limit);
  //   numerics.energy_limit replaces the bound;
  // - kinematics: no element moves more than numerics.max_step_fraction × its radius in one step.
  const double ratio = m.numerics.dt / limit;
  const double energy_factor = ratio < 1.0 ? std::max(4.0, 2.0 / (1.0 - ratio * ratio)) : 4.0;
  LoopState loop = start_loop(sim, restart, opt, probes, {c.path.string(), c.dt_location});

  RunOutputs out(c, opt, std::move(series));
  out.open(sim, total_steps);
  try {
    return run_opened(c, opt, sim, loop, probes, out, peak_quantity, limit, total_steps, energy_factor, resolved_si, restart);
  } catch (const std::exception& e) {
    out.record_failure(e.what());  // summary.json says "failed" with the message, not "running" as after SIGKILL
    throw;
  }
}


}  // namespace dem
