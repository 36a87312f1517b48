#include "dem/run/run.hpp"

#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <limits>
#include <unistd.h>

#include <fmt/format.h>
#include <fmt/os.h>

#include "dem/run/quantities.hpp"
#include "dem/cases/text.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/vtk_writer.hpp"

#include "dem2d_version.hpp"  // generated at build time: DEM2D_VERSION
#ifndef DEM2D_BUILD_TYPE
#define DEM2D_BUILD_TYPE "unknown"
#endif

namespace dem {

nlohmann::json provenance() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return {{"code_version", DEM2D_VERSION}, {"build_type", DEM2D_BUILD_TYPE}, {"date", date}, {"machine", host},
          {"compiler", fmt::format("g++ {}.{}", __GNUC__, __GNUC_MINOR__)}};
}

namespace {

/// Tracks one probe during the run.
struct ProbeState {
  const ProbeSpec* spec = nullptr;
  QuantityFn q;
  double prev_t = 0.0, prev_v = 0.0;
  std::optional<double> value;
  double extreme = 0.0;
  bool have_extreme = false;
  double st = 0.0, sq = 0.0, stt = 0.0, stq = 0.0, sn = 0.0;  // slope: least-squares sums
  QuantityFn x;                                               // slope `against`: abscissa (else t)
  double x0 = 0.0;                                            //   its first value in the window
  // restitution / duration
  Vec2 n0;
  double vn0 = 0.0;
  std::int64_t force_steps = 0;
  bool in_contact = false;
};

Vec2 contact_normal(const Simulation& s, std::uint32_t i, std::uint32_t j, bool wall) {
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
  return {m.elements.vx[j], m.elements.vy[j]};
}

bool is_tty() { return isatty(STDERR_FILENO) != 0; }

/// Stop criterion `[stop] after_peak`: true once |q| has fallen to (1 − drop) × the largest |q| seen
/// so far (updated here). A load–displacement test is then past its peak and can end.
bool past_peak(double value, double drop, double& peak) {
  peak = std::max(peak, std::abs(value));
  return peak > 0.0 && std::abs(value) <= (1.0 - drop) * peak;
}

}  // namespace

RunResult run_case(const Case& c, const RunOptions& opt) {
  const double limit = check_case(c);  // throws CaseError before anything runs
  Simulation sim(c.model);
  const Model& m = sim.model();
  const std::int64_t total_steps = std::llround(std::ceil(m.numerics.duration / m.numerics.dt - 1e-9));

  // Outputs.
  const bool write = !opt.out_dir.empty();
  std::vector<QuantityFn> series;
  for (const auto& name : c.output.series) {
    try {
      series.push_back(compile_quantity(name, m));
    } catch (const std::invalid_argument& e) {
      throw CaseError(fmt::format("{}: output.series: {}", c.path.string(), e.what()));
    }
  }
  std::vector<ProbeState> probes;
  for (const auto& p : c.probes) {
    ProbeState s;
    s.spec = &p;
    if (!p.quantity.empty()) {
      try {
        s.q = compile_quantity(p.quantity, m);
      } catch (const std::invalid_argument& e) {
        throw CaseError(fmt::format("{}: probe \"{}\": {}", c.path.string(), p.name, e.what()));
      }
      s.prev_v = s.q(sim);
    } else {
      s.n0 = contact_normal(sim, p.element, p.other, p.other_is_wall);
      const Vec2 vi{m.elements.vx[p.element], m.elements.vy[p.element]};
      s.vn0 = dot(vi - body_velocity(sim, p.other, p.other_is_wall), s.n0);
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
  double peak_so_far = 0.0;
  if (!c.stop.after_peak_quantity.empty()) {
    try {
      peak_quantity = compile_quantity(c.stop.after_peak_quantity, m);
    } catch (const std::invalid_argument& e) {
      throw CaseError(fmt::format("{}: stop.after_peak.quantity: {}", c.path.string(), e.what()));
    }
  }
  std::ofstream csv;
  std::vector<std::pair<double, std::string>> snapshots;
  if (write) {
    std::filesystem::create_directories(opt.out_dir);
    if (!series.empty()) {
      csv.open(opt.out_dir / "series.csv");
      csv << "# case: " << c.path.string() << ", code " << provenance()["code_version"].get<std::string>() << "\n";
      for (std::size_t k = 0; k < series.size(); ++k) csv << (k ? "," : "") << csv_field(c.output.series[k]);
      csv << "\n";
    }
    if (c.output.vtk) std::filesystem::create_directories(opt.out_dir / "vtk");
  }
  auto write_row = [&] {
    if (!csv.is_open()) return;
    for (std::size_t k = 0; k < series.size(); ++k) csv << (k ? "," : "") << fmt::format("{:.17g}", series[k](sim));
    csv << "\n";
  };
  auto snapshot = [&] {
    if (!write || !c.output.vtk) return;
    const std::string name = fmt::format("snapshot_{:09d}.vtp", sim.steps());
    write_vtp(opt.out_dir / "vtk" / name, sim);
    snapshots.emplace_back(sim.time(), "vtk/" + name);
  };
  write_row();
  snapshot();

  // Blow-up criterion: the mechanical energy may not exceed a bound far above what the state after
  // the first step (when the initial contacts carry their forces) and gravity over the extent of the
  // assembly can supply.
  double energy_limit = m.numerics.energy_limit;
  double mg_extent = 0.0;
  {
    double mg = 0.0, xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (std::size_t i = 0; i < m.elements.size(); ++i) {
      mg += m.elements.mass[i] * norm(m.gravity);
      xmin = std::min(xmin, m.elements.x[i]);
      xmax = std::max(xmax, m.elements.x[i]);
      ymin = std::min(ymin, m.elements.y[i]);
      ymax = std::max(ymax, m.elements.y[i]);
    }
    mg_extent = mg * (std::hypot(xmax - xmin, ymax - ymin) + 1.0);
  }
  const double potential0 = sim.energies().potential;

  RunResult res;
  res.stability_limit = limit;
  res.status = "completed";
  const bool show = opt.progress && is_tty();
  const auto t0 = std::chrono::steady_clock::now();
  auto last_print = t0;
  const std::int64_t check_every = 64;
  for (std::int64_t k = 0; k < total_steps; ++k) {
    sim.step();
    if (k == 0 && energy_limit <= 0.0) {
      const Energies e1 = sim.energies();
      energy_limit = 1e3 * (e1.kinetic + e1.elastic + mg_extent) + 1e-300;
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
      } else if (s.kind == ProbeKind::max || s.kind == ProbeKind::min) {
        const double v = p.q(sim);
        if (!p.have_extreme || (s.kind == ProbeKind::max ? v > p.extreme : v < p.extreme)) p.extreme = v;
        p.have_extreme = true;
      } else {
        const ContactView cv = sim.contact(s.element, s.other, s.other_is_wall);
        p.in_contact = cv.fn != 0.0;
        if (p.in_contact) ++p.force_steps;
      }
    }
    if (peak_quantity && sim.time() >= c.stop.after_peak_from &&
        past_peak(peak_quantity(sim), c.stop.after_peak_drop, peak_so_far)) {
      res.status = "past peak";
      break;
    }
    const bool last = k + 1 == total_steps;
    if (c.output.every > 0 && sim.steps() % c.output.every == 0 && !last) write_row();
    if (c.output.vtk_every > 0 && sim.steps() % c.output.vtk_every == 0 && !last) snapshot();
    if (sim.steps() % check_every == 0 || last) {
      const Energies en = sim.energies();
      const double mech = en.kinetic + en.elastic + (en.potential - potential0);
      if (!std::isfinite(mech) || mech > energy_limit) {
        res.status = "blow-up";
        res.message = fmt::format("stopped at t = {:.6g} s (step {}): {} (the stability limit of this assembly is {:.6g} s, dt = {:.6g} s)",
                                  sim.time(), sim.steps(),
                                  std::isfinite(mech) ? fmt::format("runaway energy {:.4g} J above the bound {:.4g} J", mech, energy_limit)
                                                      : std::string("the energy is not a number"),
                                  limit, m.numerics.dt);
        break;
      }
      if (c.stop.settled_increment && sim.time() >= c.stop.settle_min_time &&
          mean_increment(sim) < *c.stop.settled_increment) {
        res.status = "settled";
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
  }
  if (show) fmt::print(stderr, "\r{:70s}\r", "");
  const auto t1 = std::chrono::steady_clock::now();
  write_row();
  snapshot();

  res.steps = sim.steps();
  res.time = sim.time();
  res.wall_seconds = std::chrono::duration<double>(t1 - t0).count();
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
      case ProbeKind::slope:
        if (p.sn >= 2.0) v = (p.sn * p.stq - p.st * p.sq) / (p.sn * p.stt - p.st * p.st);
        break;
      case ProbeKind::restitution: {
        if (p.in_contact || p.force_steps == 0 || p.vn0 == 0.0) break;  // not ended, or never touched
        const Vec2 vi{m.elements.vx[s.element], m.elements.vy[s.element]};
        v = -dot(vi - body_velocity(sim, s.other, s.other_is_wall), p.n0) / p.vn0;
        break;
      }
      case ProbeKind::contact_duration:
        if (!p.in_contact && p.force_steps > 0) v = static_cast<double>(p.force_steps) * m.numerics.dt;
        break;
    }
    if (v && !std::isfinite(*v)) v.reset();
    res.probes[s.name] = v;
  }

  nlohmann::json probes_json = nlohmann::json::object();
  for (const auto& [k, v] : res.probes) probes_json[k] = v ? nlohmann::json(*v) : nlohmann::json(nullptr);
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
      {"element_steps_per_second", res.element_steps_per_second},
      {"energies", {{"kinetic", en.kinetic}, {"potential", en.potential}, {"elastic", en.elastic}}},
      {"probes", probes_json},
      {"resolved_case", c.resolved},
  };
  if (write) {
    std::ofstream(opt.out_dir / "summary.json") << res.summary.dump(2) << "\n";
    if (c.output.vtk) write_pvd(opt.out_dir / "snapshots.pvd", snapshots);
  }
  return res;
}

}  // namespace dem
