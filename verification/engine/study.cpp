#include "engine/study.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "dem/cases/case_file.hpp"
#include "dem/run/run.hpp"
#include "dem/cases/text.hpp"
#include "dem/cases/units.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/quantities.hpp"
#include "engine/convergence.hpp"
#include "engine/refinement_levels.hpp"
#include "engine/run_cache.hpp"
#include "engine/run_dispatch.hpp"
#include "engine/study_file.hpp"
#include "ref/registry.hpp"

namespace fs = std::filesystem;

namespace ver {

namespace {

[[noreturn]] void fail(const Study& s, const std::string& key, const std::string& what) {
  throw std::runtime_error(fmt::format("{}: {}: {}", s.file.string(), key, what));
}

/// One run of the base case with overrides; returns its probes (empty on a blow-up) and status.
struct RunOut {
  std::map<std::string, std::optional<double>> probes;
  std::string status, message;
  double eps = 0.0;
};

/// Finished runs of a study, one small JSON file per run in <study folder>/cache/, keyed by a hash of
/// the resolved case (the case file's content after the overrides), the overrides, the run folder
/// and the code identity. A killed study reuses them; `--fresh` ignores them.
struct RunCache {
  fs::path dir;  // empty: no cache
  std::atomic<int> reused{0}, ran{0};
};

RunCache* g_cache = nullptr;  // the cache of the study being run (run_study sets it)

/// A run to do: the overrides of the base case and its run folder (empty: no files).
struct Planned {
  std::vector<std::string> sets;
  fs::path out;
};

/// Runs a batch of the base case with overrides: reuses cached runs, hands the others to run_all
/// (threads here, or the ranks of an MPI job: run_dispatch.hpp), caches each as it finishes. The k-th
/// result belongs to the k-th plan, whatever order the runs finish in.
std::vector<RunOut> run_many(const Study& s, const std::vector<Planned>& plan, int jobs) {
  std::vector<RunOut> outs(plan.size());
  std::vector<RunRequest> reqs;
  std::vector<std::size_t> slot;
  std::vector<fs::path> entries;
  std::vector<std::string> case_paths;
  const fs::path case_file = fs::absolute(s.case_file);
  for (std::size_t k = 0; k < plan.size(); ++k) {
    const dem::Case c = dem::read_case(s.case_file, plan[k].sets);
    fs::path entry;
    if (g_cache && !g_cache->dir.empty()) {
      entry = cache_entry(g_cache->dir, c.resolved, plan[k].sets, plan[k].out);
      const fs::path& out = plan[k].out;
      const bool files_ok = out.empty() || (fs::exists(out / "series.csv") && fs::exists(out / "summary.json"));
      if (files_ok)
        if (const auto cached = read_cached(entry)) {
          ++g_cache->reused;
          outs[k] = {cached->probes, cached->status, cached->message, cached->eps};
          continue;
        }
    }
    reqs.push_back({case_file, plan[k].sets, plan[k].out, run_cost(c)});
    slot.push_back(k);
    entries.push_back(entry);
    case_paths.push_back(c.path.string());
  }
  run_all(reqs, jobs, [&](std::size_t i, RunReply& r) {
    const std::size_t k = slot[i];
    const bool finished = r.status != "interrupted" && r.status != "case-error" && r.status != "error";
    if (finished && !entries[i].empty()) {  // at once: a killed study keeps every finished run
      write_cached(entries[i], {r.status, r.message, r.eps, r.probes}, case_paths[i], plan[k].sets);
      ++g_cache->ran;
    }
    outs[k] = {std::move(r.probes), r.status, r.message, r.eps};
  });
  for (const RunOut& r : outs) {  // the first failure in plan order, whatever finished first
    if (r.status == "interrupted") throw StudyInterrupted(fmt::format("study {}: {}", s.name, r.message));
    if (r.status == "case-error") throw dem::CaseError(r.message);
    if (r.status == "error") throw std::runtime_error(r.message);
  }
  return outs;
}

RunOut run_one(const Study& s, const std::vector<std::string>& sets, const fs::path& out = {}) {
  return run_many(s, {Planned{sets, out}}, 1).front();
}

std::string fmt_value(std::optional<double> v) { return v ? fmt::format("{:.6g}", *v) : std::string("—"); }

}  // namespace

StudyResult run_study(const fs::path& file, const StudyOptions& opt) {
  const auto started = std::chrono::steady_clock::now();
  const Study s = read_study(file);
  const fs::path out = opt.out_dir.empty() ? fs::path("build/studies") / s.name : opt.out_dir;
  fs::create_directories(out);
  // Never a stale result: the old result.json goes first; running.json marks a study under way (or
  // killed) until the new result.json is renamed into place.
  fs::remove(out / "result.json");
  dem::write_file_atomic(out / "running.json", nlohmann::json{{"study", s.name}, {"status", "running"},
                                                              {"provenance", dem::provenance()}}.dump(2) + "\n");
  RunCache cache;
  cache.dir = out / "cache";
  if (!opt.use_cache) fs::remove_all(cache.dir);  // --fresh: forget earlier runs, record the new ones
  fs::create_directories(cache.dir);
  g_cache = &cache;
  struct Reset {
    ~Reset() { g_cache = nullptr; }
  } reset;

  nlohmann::json checks = nlohmann::json::array(), series_json = nlohmann::json::array();
  bool passed = true;
  // The reference of a check for a variant: the solver at the variant's arguments, over them a
  // refinement level's (if given), over those the check's own.
  auto reference_of = [&](const Check& c, const Variant& v, double param,
                          const RefinementLevel* level = nullptr) -> std::optional<double> {
    if (c.value) return c.value;
    if (c.solver.empty()) return std::nullopt;
    std::map<std::string, double> args = v.args;
    if (level)
      for (const auto& [k, x] : level->args) args[k] = x;
    for (const auto& [k, x] : c.args) args[k] = x;
    // Only the arguments the solver takes: variant args may serve several solvers.
    std::map<std::string, double> use;
    for (const auto& info : ref::solvers())
      if (info.name == c.solver)
        for (const auto& a : info.arguments) {
          if (a.name == "param") use[a.name] = param;
          else if (args.count(a.name)) use[a.name] = args[a.name];
        }
    return c.offset + c.scale * ref::evaluate(c.solver, use);
  };
  auto add_check = [&](const std::string& quantity, std::optional<double> reference, std::optional<double> dem,
                       const Check& c, std::optional<double> order, const std::string& note) {
    std::optional<double> err;
    bool ok = dem.has_value();
    if (dem && reference) {
      const double e = std::abs(*dem - *reference);
      err = c.relative ? e / std::abs(*reference) : e;
      if (c.expect == Expect::within) ok = *err <= c.tolerance;
      else if (c.expect == Expect::above) ok = *dem > *reference + c.tolerance;
      else ok = *dem < *reference - c.tolerance;
    }
    bool order_ok = true;
    if (c.expected_order) order_ok = order && std::abs(*order - *c.expected_order) <= c.order_band;
    ok = ok && order_ok;
    passed = passed && ok;
    auto j = [](std::optional<double> x) { return x ? nlohmann::json(*x) : nlohmann::json(nullptr); };
    checks.push_back({{"quantity", quantity}, {"reference", j(reference)}, {"dem", j(dem)}, {"error", j(err)},
                      {"error_kind", c.relative ? "rel" : "abs"}, {"tolerance", c.tolerance},
                      {"tolerance_reason", c.reason}, {"observed_order", j(order)},
                      {"expected_order", j(c.expected_order)},
                      {"order_band", c.expected_order ? nlohmann::json(c.order_band) : nlohmann::json(nullptr)},
                      {"expect", c.expect == Expect::within ? "within" : c.expect == Expect::above ? "above" : "below"},
                      {"passed", ok}, {"note", note}});
  };
  auto label = [](const Check& c, const Variant& v) { return v.label.empty() ? c.label : fmt::format("{}, {}", c.label, v.label); };
  const std::vector<RefinementLevel>& levels = s.refinement.levels;
  // [[level]] form: a check compared at the finest level (or by Richardson) needs ONE reference for
  // the whole sequence; a reference that moves with the level's arguments is refused before anything
  // runs (compare = "each" checks every level against its own).
  if (s.kind == Kind::refinement && s.refinement.declared_levels)
    for (const Check& c : s.checks) {
      if (c.compare_each || c.solver.empty()) continue;
      for (const Variant& v : s.variants) {
        if (!applies(c, v)) continue;
        const std::optional<double> finest = reference_of(c, v, levels.back().value, &levels.back());
        for (const RefinementLevel& l : levels) {
          const std::optional<double> r = reference_of(c, v, l.value, &l);
          if (r && finest && std::abs(*r - *finest) > 1e-12 * std::max(1.0, std::abs(*finest)))
            throw std::runtime_error(fmt::format("{}:{}: check.compare: {}", s.file.string(), c.line,
                 fmt::format("check \"{}\": the reference {} is {:.10g} at level \"{}\" but {:.10g} at the finest level: "
                             "a convergence series needs one reference (compare = \"each\" checks every level "
                             "against its own)", c.label, c.solver, *r, l.label, *finest)));
        }
      }
    }

  double speed_sum = 0.0;
  std::size_t speed_n = 0;
  std::vector<RunOut> finest_runs;  // single / refinement: the finest run of each variant
  auto probe_of = [](const RunOut& r, const std::string& probe) -> std::optional<double> {
    if (probe == "element_steps_per_second") return r.eps > 0.0 ? std::optional<double>(r.eps) : std::nullopt;
    return r.probes.count(probe) ? r.probes.at(probe) : std::nullopt;
  };
  nlohmann::json s_tables = nlohmann::json::array(), s_setup_extra = nlohmann::json::object();
  nlohmann::json mode_chart;  // mode_map: the coloured chart (first figure)
  if (s.kind == Kind::single || s.kind == Kind::refinement) {
    const std::size_t nl = s.kind == Kind::single ? 1 : levels.size();
    std::vector<Planned> plan(s.variants.size() * nl);
    for (std::size_t k = 0; k < plan.size(); ++k) {
      const Variant& v = s.variants[k / nl];
      std::vector<std::string> sets = s.set;
      sets.insert(sets.end(), v.set.begin(), v.set.end());
      if (s.kind == Kind::refinement) sets.insert(sets.end(), levels[k % nl].set.begin(), levels[k % nl].set.end());
      fs::path run_dir;
      if (k % nl == nl - 1) {  // the finest level feeds the figures
        std::vector<std::string> q;
        std::int64_t every = 0;
        for (const Figure& f : s.figures)
          if (f.probe.empty() && (f.variants.empty() || std::find(f.variants.begin(), f.variants.end(), v.label) != f.variants.end())) {
            q.push_back(f.x);
            q.push_back(f.y);
            every = every ? std::min(every, f.every) : f.every;
          }
        if (!q.empty()) {
          run_dir = out / "runs" / fmt::format("variant{}", k / nl);
          std::string list;
          for (const auto& name : q) list += (list.empty() ? "" : ", ") + fmt::format("\"{}\"", name);
          sets.push_back(fmt::format("output.series=[{}]", list));
          sets.push_back(fmt::format("output.every={}", every));
          sets.push_back("output.vtk=false");
        }
      }
      plan[k] = {sets, run_dir};
    }
    const std::vector<RunOut> runs = run_many(s, plan, opt.jobs);
    for (const auto& r : runs) {
      speed_sum += r.eps;
      ++speed_n;
    }
    std::ostringstream csv;
    csv << "variant,level,parameter,status";
    for (const auto& c : s.checks) csv << "," << c.probe;
    csv << "\n";
    for (std::size_t k = 0; k < runs.size(); ++k) {
      csv << '"' << s.variants[k / nl].label << "\"," << k % nl << ","
          << (s.kind == Kind::refinement ? fmt::format("{:.17g}", levels[k % nl].value) : "") << "," << runs[k].status;
      for (const auto& c : s.checks) csv << "," << fmt_value(runs[k].probes.count(c.probe) ? runs[k].probes.at(c.probe) : std::nullopt);
      csv << "\n";
    }
    dem::write_file_atomic(out / "levels.csv", csv.str(), false);
    for (std::size_t vi = 0; vi < s.variants.size(); ++vi) finest_runs.push_back(runs[vi * nl + nl - 1]);
    for (const Check& c : s.checks) {
      if (c.trend != Trend::none) {
        // A trend across the variants, in their order: every step moves the asserted way by more
        // than the tolerance. The error column holds the smallest step (negative: a wrong step).
        std::vector<std::string> shown;
        std::optional<double> smallest, last, last_ref;
        bool complete = true;
        std::optional<double> prev_value, prev_dist;
        for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
          const Variant& v = s.variants[vi];
          if (!applies(c, v)) continue;
          if (!finest_runs[vi].probes.count(c.probe)) fail(s, "check.probe", fmt::format("the case has no probe \"{}\"", c.probe));
          const std::optional<double> x = finest_runs[vi].probes.at(c.probe);
          shown.push_back(fmt::format("{}: {}", v.label, fmt_value(x)));
          if (!x) {
            complete = false;
            continue;
          }
          std::optional<double> dist;
          if (c.trend == Trend::toward_reference) {
            last_ref = s.kind == Kind::refinement ? reference_of(c, v, levels.back().value, &levels.back()) : reference_of(c, v, 0.0);
            if (!last_ref) fail(s, "check.reference", fmt::format("check \"{}\": toward_reference needs a reference", c.label));
            dist = std::abs(*x - *last_ref);
            if (c.relative) *dist /= std::abs(*last_ref);
          }
          if (prev_value) {
            const double step = c.trend == Trend::decreasing ? *prev_value - *x
                                : c.trend == Trend::increasing ? *x - *prev_value
                                                               : *prev_dist - *dist;
            smallest = smallest ? std::min(*smallest, step) : step;
          }
          prev_value = x;
          prev_dist = dist;
          last = x;
        }
        std::string values;
        for (const auto& t : shown) values += (values.empty() ? "" : " → ") + t;
        const bool ok = complete && smallest && *smallest > c.tolerance;
        passed = passed && ok;
        auto j = [](std::optional<double> x) { return x ? nlohmann::json(*x) : nlohmann::json(nullptr); };
        const char* word = c.trend == Trend::decreasing ? "decreasing" : c.trend == Trend::increasing ? "increasing" : "toward_reference";
        checks.push_back({{"quantity", c.label}, {"reference", j(last_ref)}, {"dem", j(last)}, {"error", j(smallest)},
                          {"error_kind", c.relative ? "rel" : "abs"}, {"tolerance", c.tolerance},
                          {"tolerance_reason", c.reason}, {"observed_order", nullptr}, {"expected_order", nullptr},
                          {"order_band", nullptr}, {"expect", word}, {"passed", ok},
                          {"note", (complete ? "" : "a variant gave no value; ") + std::string("values: ") + values}});
        continue;
      }
      for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
        const Variant& v = s.variants[vi];
        if (!applies(c, v)) continue;
        const RunOut& finest = runs[vi * nl + nl - 1];
        if (!finest.probes.count(c.probe))
          fail(s, "check.probe", fmt::format("the case has no probe \"{}\"", c.probe));
        const std::optional<double> ref =
            s.kind == Kind::refinement ? reference_of(c, v, levels.back().value, &levels.back()) : reference_of(c, v, 0.0);
        std::string note = finest.status == "blow-up" ? "blow-up: " + finest.message : "";
        if (s.kind == Kind::single) {
          add_check(label(c, v), ref, finest.probes.at(c.probe), c, std::nullopt, note);
          continue;
        }
        if (c.compare_each) {  // every level against its own reference (the level's arguments)
          for (std::size_t l = 0; l < nl; ++l) {
            const RunOut& run = runs[vi * nl + l];
            const std::string where = levels[l].label.empty() ? fmt::format("level {}", l) : levels[l].label;
            add_check(fmt::format("{} [{}]", label(c, v), where), reference_of(c, v, levels[l].value, &levels[l]),
                      run.probes.at(c.probe), c, std::nullopt, run.status == "blow-up" ? "blow-up: " + run.message : "");
          }
          continue;
        }
        std::vector<std::optional<double>> q;
        for (std::size_t l = 0; l < nl; ++l) q.push_back(runs[vi * nl + l].probes.at(c.probe));
        const std::size_t given = static_cast<std::size_t>(std::count_if(q.begin(), q.end(), [](const auto& x) { return x.has_value(); }));
        std::optional<double> order;
        if (given >= 2) {
          ConvergenceOptions co;
          if (!c.compare_richardson) co.reference = ref;
          co.expected_order = c.expected_order;
          co.assumed_order = c.assumed_order;
          co.fit_levels = c.fit_levels;
          std::vector<std::string> level_labels;
          Series ser = analyse_levels(s.refinement, q, co, label(c, v), &level_labels);
          order = c.compare_richardson && given >= 3 ? ser.three_level_order : ser.fitted_order;
          nlohmann::json sj = to_json(ser);
          if (s.refinement.declared_levels) sj["level_labels"] = level_labels;  // the report names the levels
          series_json.push_back(sj);
          if (c.compare_richardson) {
            note += fmt::format(" Richardson extrapolation compared (GCI of the finest level {})", fmt_value(ser.gci_fine));
            if (c.assumed_order) note += fmt::format(" with the assumed order {:g}", *c.assumed_order);
            add_check(label(c, v) + " (Richardson)", ref, ser.richardson, c, order, note);
            continue;
          }
          if (given < nl) note += fmt::format(" {} of {} levels gave no value", nl - given, nl);
        } else {
          note += " fewer than two levels gave a value";
        }
        add_check(label(c, v), ref, finest.probes.at(c.probe), c, order, note);
      }
    }
  } else if (s.kind == Kind::mode_map) {
    // Sagaseta's dynamic classification (refs §2.3) against the DEM's motion, per grid point.
    struct Point {
      std::size_t block, phi, alpha;
      int ref = 0, gb = 0, dem = -1;
      bool near_boundary = false;
      double slide = 0.0, rotation = 0.0;
    };
    std::vector<Point> pts;
    for (std::size_t b = 0; b < s.blocks.size(); ++b)
      for (std::size_t f = 0; f < s.phis.size(); ++f)
        for (std::size_t a = 0; a < s.alphas.size(); ++a) pts.push_back({b, f, a});
    auto mode_at = [&](const char* solver, double alpha, double phi, double bw, double bh) {
      return static_cast<int>(std::lround(ref::evaluate(solver, {{"alpha", alpha}, {"phi", phi}, {"b", bw}, {"h", bh}})));
    };
    std::vector<Planned> plan(pts.size());
    parallel_for(pts.size(), opt.jobs, [&](std::size_t k) {
      Point& p = pts[k];
      const auto [cols, rows] = s.blocks[p.block];
      const double bw = 2.0 * s.radius * cols, bh = 2.0 * s.radius * rows;
      const double phi = s.phis[p.phi], alpha = s.alphas[p.alpha];
      p.ref = mode_at("incline.mode", alpha, phi, bw, bh);
      p.gb = mode_at("incline.mode_gb", alpha, phi, bw, bh);
      // Near a boundary in α or in φ (e.g. b/h = tan φ exactly is the slide / slide + topple boundary).
      p.near_boundary = mode_at("incline.mode", alpha - s.margin, phi, bw, bh) != p.ref ||
                        mode_at("incline.mode", alpha + s.margin, phi, bw, bh) != p.ref ||
                        mode_at("incline.mode", alpha, phi - s.margin, bw, bh) != p.ref ||
                        mode_at("incline.mode", alpha, phi + s.margin, bw, bh) != p.ref;
      std::vector<std::string> sets = s.set;
      sets.push_back(fmt::format("lattice.0.columns={}", cols));
      sets.push_back(fmt::format("lattice.0.rows={}", rows));
      sets.push_back(fmt::format("physics.gravity.direction={:.17g} deg", alpha * 180.0 / std::numbers::pi - 90.0));
      sets.push_back(fmt::format("contact.{}.friction_angle={:.17g} deg", s.wall_contact, phi * 180.0 / std::numbers::pi));
      sets.push_back(fmt::format("probe.0.quantity=e{}.px(1,-1)", cols - 1));
      sets.push_back(fmt::format("probe.2.quantity=e{}.px(1,-1)", cols - 1));
      plan[k].sets = sets;
    });
    const std::vector<RunOut> mode_runs = run_many(s, plan, opt.jobs);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      Point& p = pts[k];
      const RunOut& r = mode_runs[k];
      auto get = [&](const char* name) { return r.probes.count(name) ? r.probes.at(name) : std::nullopt; };
      if (r.status == "blow-up" || !get("pivot_x") || !get("rotation") || !get("pivot_x_start") || !get("rotation_start")) continue;
      // The motion after the start-up transient: from `pivot_x_start` / `rotation_start` to the end.
      p.slide = *get("pivot_x") - *get("pivot_x_start");
      p.rotation = std::abs(*get("rotation") - *get("rotation_start"));
      const bool slides = p.slide > s.slide_threshold, rotates = p.rotation > s.rotation_threshold;
      p.dem = slides ? (rotates ? 3 : 1) : (rotates ? 2 : 0);
    }
    const char code[] = {'.', 'S', 'T', 'X'};
    std::ostringstream map;
    map << "alpha (deg):          ";
    for (double a : s.alphas) map << fmt::format("{:>3.0f}", a * 180.0 / std::numbers::pi);
    map << "\n";
    nlohmann::json rows = nlohmann::json::array();
    int total_checked = 0, total_agree = 0, total_excluded = 0;
    for (std::size_t b = 0; b < s.blocks.size(); ++b)
      for (std::size_t f = 0; f < s.phis.size(); ++f) {
        std::string ref_row, dem_row, gb_row, marks;
        int checked = 0, agree = 0, excluded = 0;
        for (const Point& p : pts) {
          if (p.block != b || p.phi != f) continue;
          ref_row += fmt::format("{:>3}", code[p.ref]);
          gb_row += code[p.gb];
          dem_row += fmt::format("{:>3}", p.dem < 0 ? '?' : code[p.dem]);
          if (p.near_boundary) {
            ++excluded;
            marks += "  ~";
          } else {
            ++checked;
            const bool ok = p.dem == p.ref;
            agree += ok;
            marks += ok ? "   " : "  !";
          }
        }
        const auto [cols, rows_n] = s.blocks[b];
        const std::string shape = fmt::format("{}x{} (b/h={:.3g})", cols, rows_n, double(cols) / rows_n);
        const double phi_deg = s.phis[f] * 180.0 / std::numbers::pi;
        map << fmt::format("{:<17} phi={:<3.0f} ref {}\n", shape, phi_deg, ref_row);
        map << fmt::format("{:<17}         DEM {}\n", "", dem_row);
        map << fmt::format("{:<17}             {}   [G&B: {}]\n", "", marks, gb_row);
        rows.push_back({shape, fmt::format("{:.0f}", phi_deg), fmt::format("{}/{}", agree, checked), excluded});
        total_checked += checked;
        total_agree += agree;
        total_excluded += excluded;
        Check c = s.checks.front();
        add_check(fmt::format("{}, φ = {:.0f}°: grid points where DEM ≠ Sagaseta", shape, phi_deg), 0.0,
                  static_cast<double>(checked - agree), c, std::nullopt,
                  fmt::format("{} points checked, {} within {:.1f}° (in α or φ) of a boundary not checked", checked, excluded,
                              s.margin * 180.0 / std::numbers::pi));
      }
    map << "(. stable, S slide, T topple, X slide + topple; ~ within the margin of a mode boundary, not checked; ! disagrees)\n";
    {  // the same map as a coloured chart: rows = block and φ, x = α; ring = Sagaseta, dot = DEM
      const char* names[] = {"stable", "slide", "topple", "slide + topple"};
      const char* colours[] = {"#2ca02c", "#1f77b4", "#d62728", "#9467bd"};
      nlohmann::json curves = nlohmann::json::array(), yticks = nlohmann::json::array();
      std::vector<std::vector<double>> rx(4), ry(4), dx(4), dy(4);
      std::vector<double> ex, ey, fx, fy;
      for (const Point& p : pts) {
        const double row = static_cast<double>(p.block * s.phis.size() + p.phi);
        const double a = s.alphas[p.alpha] * 180.0 / std::numbers::pi;
        rx[p.ref].push_back(a);
        ry[p.ref].push_back(row);
        if (p.dem >= 0) {
          dx[p.dem].push_back(a);
          dy[p.dem].push_back(row);
        } else {
          fx.push_back(a);
          fy.push_back(row);
        }
        if (p.near_boundary) {
          ex.push_back(a);
          ey.push_back(row);
        }
      }
      for (int m = 0; m < 4; ++m)
        curves.push_back({{"label", fmt::format("Sagaseta: {}", names[m])}, {"x", rx[m]}, {"y", ry[m]},
                          {"style", "points"}, {"colour", colours[m]}, {"point", 6}, {"size", 1.5}});
      for (int m = 0; m < 4; ++m)
        curves.push_back({{"label", fmt::format("DEM: {}", names[m])}, {"x", dx[m]}, {"y", dy[m]},
                          {"style", "points"}, {"colour", colours[m]}, {"point", 7}, {"size", 0.75}});
      curves.push_back({{"label", "near a boundary: not checked"}, {"x", ex}, {"y", ey}, {"style", "points"},
                        {"colour", "#000000"}, {"point", 2}, {"size", 1.2}});
      curves.push_back({{"label", "DEM run failed"}, {"x", fx}, {"y", fy}, {"style", "points"},
                        {"colour", "#000000"}, {"point", 3}, {"size", 1.8}});
      for (std::size_t b = 0; b < s.blocks.size(); ++b)
        for (std::size_t f = 0; f < s.phis.size(); ++f)
          yticks.push_back({static_cast<double>(b * s.phis.size() + f),
                            fmt::format("{}×{}, φ={:.0f}°", s.blocks[b].first, s.blocks[b].second,
                                        s.phis[f] * 180.0 / std::numbers::pi)});
      const double rows_n = static_cast<double>(s.blocks.size() * s.phis.size());
      mode_chart = {{"id", "mode_map"}, {"title", "Mode map: Sagaseta (ring) against the DEM (dot), same colour = agreement"},
                    {"xlabel", "slope angle α [deg]"}, {"ylabel", "block (columns × rows) and friction angle φ"},
                    {"logx", false}, {"logy", false}, {"curves", curves}, {"yticks", yticks},
                    {"yrange", {-0.7, rows_n - 0.3}}};
    }
    s_tables.push_back({{"title", "Mode map: Sagaseta (ref) against the DEM"}, {"preformatted", map.str()}});
    s_tables.push_back({{"title", "Agreement per block and friction angle"},
                        {"columns", {"block", "phi [deg]", "agree / checked", "excluded (near a boundary)"}},
                        {"rows", rows}});
    s_setup_extra["points checked"] = total_checked;
    s_setup_extra["points agreeing"] = total_agree;
    s_setup_extra["points excluded"] = total_excluded;
    if (opt.print) fmt::print("{}", map.str());
  } else {  // stability: bisection on the parameter, per variant
    std::vector<std::optional<double>> limits(s.variants.size());
    std::vector<std::string> notes(s.variants.size());
    // Under MPI every variant's bisection runs at once (each waits for one run at a time).
    const int threads = run_distributor() ? std::max<int>(opt.jobs, static_cast<int>(s.variants.size())) : opt.jobs;
    parallel_for(s.variants.size(), threads, [&](std::size_t vi) {
      const Variant& v = s.variants[vi];
      auto stable = [&](double x) {
        std::vector<std::string> sets = s.set;
        sets.insert(sets.end(), v.set.begin(), v.set.end());
        sets.push_back(fmt::format("{}={:.17g}", s.parameter, x));
        sets.push_back("numerics.allow_unstable=true");
        return run_one(s, sets).status != "blow-up";
      };
      double lo = s.low, hi = s.high;
      if (!stable(lo)) {
        limits[vi] = 0.0;
        notes[vi] = fmt::format("unstable already at the lower bound {:.6g}", lo);
        return;
      }
      if (stable(hi)) {
        notes[vi] = fmt::format("stable up to the upper bound {:.6g}", hi);
        return;
      }
      while ((hi - lo) > s.rel_tol * lo) {
        const double mid = 0.5 * (lo + hi);
        (stable(mid) ? lo : hi) = mid;
      }
      limits[vi] = 0.5 * (lo + hi);
    });
    for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {  // probe "limit" for figures and tables
      RunOut r;
      r.probes["limit"] = limits[vi];
      finest_runs.push_back(r);
    }
    for (const Check& c : s.checks)
      for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
        if (!applies(c, s.variants[vi])) continue;
        add_check(label(c, s.variants[vi]), reference_of(c, s.variants[vi], 0.0), limits[vi], c, std::nullopt, notes[vi]);
      }
  }

  // A registry solver with only the arguments it takes (variant arguments may serve several solvers).
  auto evaluate = [](const std::string& solver, const std::map<std::string, double>& args) {
    std::map<std::string, double> use;
    for (const auto& info : ref::solvers())
      if (info.name == solver)
        for (const auto& a : info.arguments)
          if (args.count(a.name)) use[a.name] = args.at(a.name);
    return ref::evaluate(solver, use);
  };
  auto words = [](const Figure& f, const std::string& key, const std::string& fallback) {
    const auto it = f.curve_labels.find(key);
    return it == f.curve_labels.end() ? fallback : it->second;
  };
  auto listed = [](const std::vector<std::string>& only, const std::string& label) {
    return only.empty() || std::find(only.begin(), only.end(), label) != only.end();
  };
  nlohmann::json figures = nlohmann::json::array();
  if (!mode_chart.is_null()) figures.push_back(mode_chart);
  for (const Figure& f : s.figures) {
    nlohmann::json curves = nlohmann::json::array();
    if (!f.probe.empty()) {
      // Probe values across variants against a variant argument, one curve per group.
      std::vector<double> groups;
      for (std::size_t vi = 0; vi < s.variants.size() && vi < finest_runs.size(); ++vi) {
        const Variant& v = s.variants[vi];
        if (!listed(f.variants, v.label)) continue;
        const double g = v.args.count(f.group_arg) ? v.args.at(f.group_arg) : 0.0;
        if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
      }
      for (double g : groups) {
        std::vector<double> px, py, rx, ry;
        std::map<std::string, double> ref_args;
        for (std::size_t vi = 0; vi < s.variants.size() && vi < finest_runs.size(); ++vi) {
          const Variant& v = s.variants[vi];
          if (!listed(f.variants, v.label) || !v.args.count(f.x_arg)) continue;
          if ((v.args.count(f.group_arg) ? v.args.at(f.group_arg) : 0.0) != g) continue;
          const std::optional<double> y = probe_of(finest_runs[vi], f.probe);
          px.push_back(v.args.at(f.x_arg) * f.x_scale);
          py.push_back(y ? (*y - f.y_offset) * f.y_scale : std::nan(""));
          if (!f.solver.empty()) {
            std::map<std::string, double> args = v.args;
            for (const auto& [k, x] : f.args) args[k] = x;
            if (ref_args.empty()) ref_args = args;
            rx.push_back(px.back());
            ry.push_back(evaluate(f.solver, args) * f.ref_scale * f.y_scale);
          }
        }
        if (f.reference_points > 1 && !rx.empty()) {  // a smooth curve over the group's span of x_arg
          const auto [lo, hi] = std::minmax_element(rx.begin(), rx.end());
          const double a = *lo / f.x_scale, b = *hi / f.x_scale;
          rx.clear();
          ry.clear();
          for (std::int64_t k = 0; k < f.reference_points; ++k) {
            std::map<std::string, double> args = ref_args;
            args[f.x_arg] = a + (b - a) * static_cast<double>(k) / static_cast<double>(f.reference_points - 1);
            rx.push_back(args[f.x_arg] * f.x_scale);
            ry.push_back(evaluate(f.solver, args) * f.ref_scale * f.y_scale);
          }
        }
        const std::string gname = f.group_arg.empty() ? "DEM" : fmt::format("{} = {:g}", f.group_label, g);
        const std::string gkey = f.group_arg.empty() ? "DEM" : fmt::format("{:g}", g);
        // Against a smooth reference curve the DEM values are points (no line between them to mislead).
        curves.push_back({{"label", words(f, gkey, gname)}, {"x", px}, {"y", py},
                          {"style", f.reference_points > 1 ? "points" : "linespoints"}});
        if (!rx.empty())
          curves.push_back({{"label", words(f, f.solver, "reference") + (f.group_arg.empty() ? "" : ", " + gname)},
                            {"x", rx}, {"y", ry}, {"style", "reference"}});
      }
    } else {
      std::vector<double> ref_x;
      std::map<std::string, double> ref_args = f.args;
      std::map<std::string, std::vector<std::map<std::string, double>>> drawn_references;  // per solver: its arguments
      for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
        const Variant& v = s.variants[vi];
        if (!listed(f.variants, v.label)) continue;
        const fs::path csv = out / "runs" / fmt::format("variant{}", vi) / "series.csv";
        std::ifstream in(csv);
        std::string line;
        std::vector<std::string> header;
        std::vector<double> xs, ys;
        while (std::getline(in, line)) {
          if (line.empty()) continue;
          const std::vector<std::string> cells = dem::split_csv(line);
          if (header.empty()) {  // "e0.y [m]": the quantity and its unit
            for (const std::string& h : cells) header.push_back(dem::series_column_name(h));
            continue;
          }
          auto col = [&](const std::string& name) {
            for (std::size_t k = 0; k < header.size(); ++k)
              if (header[k] == name) return std::stod(cells[k]);
            return std::nan("");
          };
          xs.push_back(col(f.x));
          ys.push_back(col(f.y));
        }
        if (xs.empty()) continue;
        std::map<std::string, double> vargs = v.args;
        for (const auto& [k, x] : f.args) vargs[k] = x;
        const double y0 = ys.front();
        std::vector<double> px, py;
        for (std::size_t k = 0; k < xs.size(); ++k) {
          double y = f.y_from_start ? ys[k] - y0 : ys[k] - f.y_offset;
          if (f.y_minus_reference) {
            std::map<std::string, double> a = vargs;
            a[f.x_arg] = xs[k];
            y -= evaluate(f.solver, a) * f.ref_scale;
          }
          px.push_back(xs[k] * f.x_scale);
          py.push_back(y * f.y_scale);
        }
        if (ref_x.empty()) {
          ref_x = xs;
          ref_args = vargs;
        }
        const std::string name = v.label.empty() ? std::string("DEM") : "DEM " + v.label;
        curves.push_back({{"label", words(f, v.label, name)}, {"x", px}, {"y", py}, {"style", "lines"}});
        if (f.reference_per_variant && !f.y_minus_reference)
          for (const std::string& solver : f.solvers) {
            std::vector<double> rx, ry, grid = xs;
            if (f.reference_points > 1 && !xs.empty()) {  // a uniform grid over the variant's span (a costly solver)
              const auto [lo, hi] = std::minmax_element(xs.begin(), xs.end());
              grid.clear();
              for (std::int64_t k = 0; k < f.reference_points; ++k)
                grid.push_back(*lo + (*hi - *lo) * static_cast<double>(k) / static_cast<double>(f.reference_points - 1));
            }
            for (double x : grid) {
              std::map<std::string, double> a = vargs;
              a[f.x_arg] = x;
              rx.push_back(x * f.x_scale);
              ry.push_back(evaluate(solver, a) * f.ref_scale * f.y_scale);
            }
            // A reference that does not depend on what differs between the variants (e.g. Bray & Goodman
            // for 3 and 75 PREs at one α: the same arguments of the solver apart from x) is drawn once.
            std::map<std::string, double> taken;
            for (const auto& info : ref::solvers())
              if (info.name == solver)
                for (const auto& arg : info.arguments)
                  if (arg.name != f.x_arg && vargs.count(arg.name)) taken[arg.name] = vargs.at(arg.name);
            auto& drawn = drawn_references[solver];
            if (std::find(drawn.begin(), drawn.end(), taken) != drawn.end()) continue;
            drawn.push_back(taken);
            curves.push_back({{"label", words(f, solver + "|" + v.label, words(f, solver, "reference") + ", " + v.label)},
                              {"x", rx}, {"y", ry}, {"style", "reference"}});
          }
      }
      if (f.reference_per_variant) ref_x.clear();
      if (!ref_x.empty() && !f.y_minus_reference)
        for (const std::string& solver : f.solvers) {
          std::vector<double> px, py;
          for (double x : ref_x) {
            std::map<std::string, double> a = ref_args;
            a[f.x_arg] = x;
            px.push_back(x * f.x_scale);
            py.push_back(evaluate(solver, a) * f.ref_scale * f.y_scale);
          }
          curves.push_back({{"label", words(f, solver, "reference: " + solver)}, {"x", px}, {"y", py}, {"style", "reference"}});
        }
    }
    nlohmann::json fig = {{"id", f.id}, {"title", f.title}, {"xlabel", f.xlabel}, {"ylabel", f.ylabel},
                          {"logx", f.logx}, {"logy", f.logy}, {"curves", curves}};
    if (!f.x_range.empty()) fig["xrange"] = f.x_range;
    if (!f.y_range.empty()) fig["yrange"] = f.y_range;
    figures.push_back(fig);
  }
  for (const TableDecl& d : s.tables) {
    nlohmann::json rows = nlohmann::json::array(), columns = nlohmann::json::array();
    auto cell = [&](std::size_t vi, const std::string& probe) -> nlohmann::json {
      const auto x = probe_of(finest_runs[vi], probe);
      return x ? nlohmann::json(fmt::format("{:.4g}", *x * d.scale)) : nlohmann::json("—");
    };
    if (d.row_arg.empty()) {
      columns.push_back("variant");
      for (const auto& p : d.probes) columns.push_back(p);
      for (std::size_t vi = 0; vi < finest_runs.size(); ++vi) {
        if (!listed(d.variants, s.variants[vi].label)) continue;
        nlohmann::json row = {s.variants[vi].label};
        for (const auto& p : d.probes) row.push_back(cell(vi, p));
        rows.push_back(row);
      }
    } else {
      std::vector<double> rv, cv;
      for (std::size_t vi = 0; vi < finest_runs.size(); ++vi) {
        const Variant& v = s.variants[vi];
        if (!listed(d.variants, v.label) || !v.args.count(d.row_arg) || !v.args.count(d.column_arg)) continue;
        if (std::find(rv.begin(), rv.end(), v.args.at(d.row_arg)) == rv.end()) rv.push_back(v.args.at(d.row_arg));
        if (std::find(cv.begin(), cv.end(), v.args.at(d.column_arg)) == cv.end()) cv.push_back(v.args.at(d.column_arg));
      }
      std::sort(cv.begin(), cv.end());
      columns.push_back(fmt::format("{} \\ {}", d.row_label, d.column_label));
      for (double c : cv) columns.push_back(fmt::format("{} = {:g}", d.column_label, c));
      for (double r : rv) {
        nlohmann::json row = {fmt::format("{} = {:g}", d.row_label, r)};
        for (double c : cv) {
          nlohmann::json value = "";
          for (std::size_t vi = 0; vi < finest_runs.size(); ++vi) {
            const Variant& v = s.variants[vi];
            if (listed(d.variants, v.label) && v.args.count(d.row_arg) && v.args.count(d.column_arg) &&
                v.args.at(d.row_arg) == r && v.args.at(d.column_arg) == c)
              value = cell(vi, d.probes.front());
          }
          row.push_back(value);
        }
        rows.push_back(row);
      }
    }
    s_tables.push_back({{"title", d.title}, {"columns", columns}, {"rows", rows}});
  }

  nlohmann::json setup = s.setup;
  for (const auto& [k, v] : s_setup_extra.items()) setup[k] = v;
  setup["variants"] = s.variants.size();
  if (s.kind == Kind::refinement) {
    if (!s.refinement.declared_levels) {
      std::vector<double> values;
      for (const RefinementLevel& l : levels) values.push_back(l.value);
      setup["levels"] = values;
    } else {
      std::vector<std::string> words;  // "1x3 (h = 0.0125)"
      for (const RefinementLevel& l : levels) words.push_back(fmt::format("{} ({} = {:g})", l.label, s.refinement.inverse ? "n" : "h", l.value));
      setup["levels"] = words;
    }
  }
  if (speed_n) setup["mean element-steps per second"] = speed_sum / static_cast<double>(speed_n);
  nlohmann::json prov = dem::provenance();
  prov["overrides"] = s.set;
  nlohmann::json result = {
      {"study", s.name}, {"title", s.title}, {"requirement", s.requirement},
      {"kind", kind_word(s.kind)},
      {"case", s.case_path}, {"parameter", s.parameter}, {"reference", s.reference_text}, {"setup", setup},
      {"provenance", prov}, {"passed", passed}, {"checks", checks}, {"series", series_json},
      {"figures", figures}, {"tables", s_tables}};
  result["provenance"]["wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  result["provenance"]["command"] = fmt::format("dem2d study {} --out {} --jobs {}{}", file.string(), out.string(),
                                                opt.jobs, opt.use_cache ? "" : " --fresh");
  // The study's README (purpose, findings, known limits) travels with the result: the report shows it.
  if (const fs::path readme = fs::absolute(file).parent_path() / "README.md"; fs::exists(readme))
    result["readme"] = dem::read_file(readme);
  result["provenance"]["runs_reused"] = cache.reused.load();
  result["provenance"]["runs_run"] = cache.ran.load();
  dem::write_file_atomic(out / "result.json", result.dump(2) + "\n");
  fs::remove(out / "running.json");

  if (opt.print) {
    fmt::print("study {}: {}\n", s.name, s.title);
    fmt::print("  {:<40} {:>13} {:>13} {:>10} {:>9} {:>15} {}\n", "quantity", "reference", "DEM", "error", "tol", "order (exp)", "");
    for (const auto& c : checks) {
      auto num = [](const nlohmann::json& x) { return x.is_null() ? std::string("—") : fmt::format("{:.6g}", x.get<double>()); };
      const std::string order = c["observed_order"].is_null() && c["expected_order"].is_null()
                                    ? ""
                                    : fmt::format("{} ({}±{})", num(c["observed_order"]), num(c["expected_order"]), num(c["order_band"]));
      fmt::print("  {:<40} {:>13} {:>13} {:>10} {:>9} {:>15} {}{}\n", c["quantity"].get<std::string>(), num(c["reference"]),
                 num(c["dem"]), num(c["error"]), num(c["tolerance"]), order, c["passed"].get<bool>() ? "pass" : "FAIL",
                 c["note"].get<std::string>().empty() ? "" : "  [" + c["note"].get<std::string>() + "]");
    }
    fmt::print("  => {}  ({})\n", passed ? "PASSED" : "FAILED", (out / "result.json").string());
  }
  return {passed, result};
}

}  // namespace ver
