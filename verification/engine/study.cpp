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
#include "engine/convergence.hpp"
#include "engine/run_cache.hpp"
#include "ref/registry.hpp"

namespace fs = std::filesystem;

namespace ver {

namespace {

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
  std::int64_t reference_points = 0;
  bool reference_per_variant = false;  // series figure: one reference curve per variant (its own args)  // > 1: the reference on a uniform grid of x_arg over the group's span
  std::map<std::string, std::string> curve_labels;  // legend words per series quantity / solver
};

/// A table of probe values across variants: rows = variants (columns = the probes), or a pivot with
/// rows = distinct values of row_arg and columns = distinct values of column_arg (one probe).
struct TableDecl {
  std::string title, row_arg, column_arg, row_label, column_label;
  std::vector<std::string> probes, variants;
  double scale = 1.0;
};

struct Study {
  fs::path file, root;
  std::string name, title, requirement, reference_text, case_path, parameter, parameter_label;
  Kind kind = Kind::single;
  std::vector<std::string> set;
  std::vector<Variant> variants;
  std::vector<double> values;       // refinement levels, coarse → fine
  bool inverse = false;             // h = 1/value (refining by raising N or an element count)
  double low = 0.0, high = 0.0, rel_tol = 1e-4;  // stability bisection
  std::vector<Check> checks;
  std::vector<Figure> figures;
  std::vector<TableDecl> tables;
  nlohmann::json setup = nlohmann::json::object();
  // mode_map: block shapes (columns, rows) × friction angles × slope angles
  std::vector<std::pair<int, int>> blocks;
  std::vector<double> phis, alphas;  // [rad]
  double radius = 0.0, margin = 0.0, rotation_threshold = 0.0, slide_threshold = 0.0;
  int wall_contact = 1;
};

[[noreturn]] void fail(const Study& s, const std::string& key, const std::string& what) {
  throw std::runtime_error(fmt::format("{}: {}: {}", s.file.string(), key, what));
}

/// The same, with the line of the offending node.
[[noreturn]] void fail_at(const Study& s, const toml::node& n, const std::string& key, const std::string& what) {
  throw std::runtime_error(fmt::format("{}:{}: {}: {}", s.file.string(), n.source().begin.line, key, what));
}

double number_or_quantity(const Study& s, const toml::node& n, const std::string& key) {
  if (auto d = n.value<double>()) return *d;
  if (auto str = n.value_exact<std::string>()) {
    try {
      return dem::parse_quantity(*str).value;
    } catch (const std::exception& e) {
      fail(s, key, e.what());
    }
  }
  fail(s, key, "expected a number or a string with a unit");
}

std::vector<std::string> strings(const Study& s, const toml::table& t, const std::string& key) {
  std::vector<std::string> out;
  if (const toml::node* n = t.get(key)) {
    const toml::array* a = n->as_array();
    if (!a) fail(s, key, "expected an array of strings");
    for (const auto& x : *a) {
      auto v = x.value_exact<std::string>();
      if (!v) fail(s, key, "expected an array of strings");
      out.push_back(*v);
    }
  }
  return out;
}

std::map<std::string, double> args_of(const Study& s, const toml::table& t, const std::string& key) {
  std::map<std::string, double> out;
  if (const toml::node* n = t.get(key)) {
    const toml::table* a = n->as_table();
    if (!a) fail(s, key, "expected a table of reference arguments, e.g. { zeta = 0.3 }");
    for (const auto& [k, v] : *a) out[std::string(k.str())] = number_or_quantity(s, v, key + "." + std::string(k.str()));
  }
  return out;
}

Study read_study(const fs::path& file) {
  Study s;
  s.file = file;
  s.root = fs::absolute(file).parent_path().parent_path().parent_path();  // verification/<name>/study.toml
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw std::runtime_error(fmt::format("{}:{}: syntax: {}", file.string(), e.source().begin.line, e.description()));
  }
  const toml::table* st = root["study"].as_table();
  if (!st) fail(s, "study", "missing [study] table");
  s.name = (*st)["name"].value_or(fs::absolute(file).parent_path().filename().string());
  // The name becomes a folder under build/studies: one plain path component, nothing else.
  if (s.name.empty() || s.name == "." || s.name == ".." ||
      s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") != std::string::npos)
    fail_at(s, st->get("name") ? *st->get("name") : static_cast<const toml::node&>(*st), "study.name",
            fmt::format("expected a plain folder name (letters, digits, '_', '-', '.'), got \"{}\"", s.name));
  s.title = (*st)["title"].value_or(s.name);
  s.requirement = (*st)["requirement"].value_or(std::string());
  s.reference_text = (*st)["reference"].value_or(std::string());
  s.case_path = (*st)["case"].value_or(std::string());
  if (s.case_path.empty()) fail(s, "study.case", "missing: the base case file");
  const std::string kind = (*st)["kind"].value_or(std::string("single"));
  if (kind == "refinement") s.kind = Kind::refinement;
  else if (kind == "single") s.kind = Kind::single;
  else if (kind == "stability") s.kind = Kind::stability;
  else if (kind == "mode_map") s.kind = Kind::mode_map;
  else fail(s, "study.kind", fmt::format("expected refinement, single, stability or mode_map, got \"{}\"", kind));
  s.set = strings(s, *st, "set");
  if (const toml::table* su = (*st)["setup"].as_table()) {
    for (const auto& [k, v] : *su) {
      if (auto x = v.value<double>()) s.setup[std::string(k.str())] = *x;
      else if (auto y = v.value_exact<std::string>()) s.setup[std::string(k.str())] = *y;
    }
  }
  if (root.get("variant") && !root["variant"].as_array())
    fail_at(s, *root.get("variant"), "variant", "expected [[variant]] tables");
  if (const toml::array* va = root["variant"].as_array()) {
    for (const auto& n : *va) {
      const toml::table* t = n.as_table();
      if (!t) fail_at(s, n, "variant", "expected [[variant]] tables");
      Variant v;
      v.label = (*t)["label"].value_or(std::string());
      v.set = strings(s, *t, "set");
      v.args = args_of(s, *t, "args");
      s.variants.push_back(v);
    }
  }
  if (s.variants.empty()) s.variants.push_back({});
  if (s.kind == Kind::refinement) {
    const toml::table* r = root["refinement"].as_table();
    if (!r) fail(s, "refinement", "missing [refinement] table for kind = \"refinement\"");
    s.parameter = (*r)["parameter"].value_or(std::string());
    s.parameter_label = (*r)["label"].value_or(s.parameter);
    if (s.parameter.empty()) fail(s, "refinement.parameter", "missing: the case key to refine, e.g. numerics.dt");
    if (const toml::array* a = (*r)["values"].as_array()) {
      for (const auto& x : *a) s.values.push_back(number_or_quantity(s, x, "refinement.values"));
    } else {
      const toml::node* b = r->get("base");
      if (!b) fail(s, "refinement", "give values = [...] or base, ratio, levels");
      const double base = number_or_quantity(s, *b, "refinement.base");
      const double ratio = (*r)["ratio"].value_or(2.0);
      const auto levels = (*r)["levels"].value_or(int64_t{4});
      if (ratio <= 1.0 || levels < 2) fail(s, "refinement", "need ratio > 1 and levels >= 2");
      for (int64_t k = 0; k < levels; ++k) s.values.push_back(base / std::pow(ratio, static_cast<double>(k)));
    }
    if (s.values.size() < 2) fail(s, "refinement.values", "need at least two levels");
    const std::string hk = (*r)["h"].value_or(std::string("value"));
    if (hk != "value" && hk != "inverse") fail(s, "refinement.h", "expected \"value\" (h = the parameter, e.g. Δt) or \"inverse\" (h = 1/parameter, e.g. N)");
    s.inverse = hk == "inverse";
  } else if (s.kind == Kind::stability) {
    const toml::table* r = root["stability"].as_table();
    if (!r) fail(s, "stability", "missing [stability] table for kind = \"stability\"");
    s.parameter = (*r)["parameter"].value_or(std::string("numerics.dt"));
    s.parameter_label = (*r)["label"].value_or(s.parameter);
    if (!r->get("low") || !r->get("high")) fail(s, "stability", "need low (stable) and high (unstable) bounds");
    s.low = number_or_quantity(s, *r->get("low"), "stability.low");
    s.high = number_or_quantity(s, *r->get("high"), "stability.high");
    s.rel_tol = (*r)["rel_tol"].value_or(1e-4);
    if (!(s.low > 0.0 && s.high > s.low)) fail(s, "stability", "need 0 < low < high");
  }
  if (s.kind == Kind::mode_map) {
    const toml::table* r = root["mode_map"].as_table();
    if (!r) fail(s, "mode_map", "missing [mode_map] table for kind = \"mode_map\"");
    if (const toml::array* b = (*r)["blocks"].as_array())
      for (const auto& x : *b) {
        const toml::array* pair = x.as_array();
        if (!pair || pair->size() != 2) fail(s, "mode_map.blocks", "expected [[columns, rows], ...]");
        s.blocks.emplace_back(static_cast<int>(pair->get(0)->value_or(int64_t{1})), static_cast<int>(pair->get(1)->value_or(int64_t{1})));
      }
    auto angles = [&](const char* key, std::vector<double>& out) {
      if (const toml::array* a = (*r)[key].as_array())
        for (const auto& x : *a) out.push_back(x.value_or(0.0) * std::numbers::pi / 180.0);
      if (out.empty()) fail(s, fmt::format("mode_map.{}", key), "expected a list of angles in degrees");
    };
    angles("phis_deg", s.phis);
    angles("alphas_deg", s.alphas);
    s.radius = (*r)["radius"].value_or(0.0);
    s.margin = (*r)["margin_deg"].value_or(1.0) * std::numbers::pi / 180.0;
    s.rotation_threshold = (*r)["rotation_threshold"].value_or(2e-3);
    s.slide_threshold = (*r)["slide_threshold"].value_or(1e-4);
    s.wall_contact = static_cast<int>((*r)["wall_contact"].value_or(int64_t{1}));
    if (s.blocks.empty() || !(s.radius > 0.0)) fail(s, "mode_map", "need blocks and radius");
  }
  if (root.get("check") && !root["check"].as_array())
    fail_at(s, *root.get("check"), "check", "expected [[check]] tables");
  const toml::array* ca = root["check"].as_array();
  if (!ca || ca->empty()) fail(s, "check", "missing: at least one [[check]]");
  for (const auto& n : *ca) {
    const toml::table* t = n.as_table();
    if (!t) fail_at(s, n, "check", "expected [[check]] tables (a table per check), got a value");
    Check c;
    c.probe = (*t)["probe"].value_or(std::string(s.kind == Kind::stability ? "limit" : s.kind == Kind::mode_map ? "mismatches" : ""));
    if (c.probe.empty()) fail(s, "check.probe", "missing: the probe of the case to check");
    c.label = (*t)["label"].value_or(c.probe);
    c.solver = (*t)["reference"].value_or(std::string());
    if (const toml::node* v = t->get("value")) c.value = number_or_quantity(s, *v, "check.value");
    const std::string trend = (*t)["trend"].value_or(std::string());
    if (!trend.empty()) {
      if (trend == "decreasing") c.trend = Trend::decreasing;
      else if (trend == "increasing") c.trend = Trend::increasing;
      else if (trend == "toward_reference") c.trend = Trend::toward_reference;
      else fail_at(s, n, "check.trend", fmt::format("expected decreasing, increasing or toward_reference, got \"{}\"", trend));
      if (s.kind != Kind::single && s.kind != Kind::refinement)
        fail_at(s, n, "check.trend", "a trend check needs kind = \"single\" or \"refinement\"");
    }
    if (c.solver.empty() && !c.value && s.kind != Kind::refinement && (c.trend == Trend::none || c.trend == Trend::toward_reference))
      fail(s, "check.reference", fmt::format("check \"{}\": give a reference solver or a value", c.label));
    c.args = args_of(s, *t, "args");
    if (const toml::node* o = t->get("reference_offset")) c.offset = number_or_quantity(s, *o, "check.reference_offset");
    if (const toml::node* o = t->get("reference_scale")) c.scale = number_or_quantity(s, *o, "check.reference_scale");
    if (!t->get("tolerance")) fail(s, "check.tolerance", fmt::format("check \"{}\": missing tolerance", c.label));
    c.tolerance = number_or_quantity(s, *t->get("tolerance"), "check.tolerance");
    c.relative = (*t)["error"].value_or(std::string("abs")) == "rel";
    c.reason = (*t)["reason"].value_or(std::string());
    if (c.reason.empty()) fail(s, "check.reason", fmt::format("check \"{}\": every tolerance needs a one-line reason", c.label));
    if (auto p = (*t)["expected_order"].value<double>()) {
      c.expected_order = *p;
      c.order_band = (*t)["order_band"].value_or(0.2);
    }
    if (const toml::array* fl = (*t)["fit_levels"].as_array())
      for (const auto& x : *fl) c.fit_levels.push_back(static_cast<std::size_t>(x.value_or(int64_t{0})));
    c.only = strings(s, *t, "variants");
    const std::string ex = (*t)["expect"].value_or(std::string("within"));
    c.expect = ex == "above" ? Expect::above : ex == "below" ? Expect::below : Expect::within;
    const std::string cmp = (*t)["compare"].value_or(std::string("finest"));
    if (cmp != "finest" && cmp != "richardson") fail(s, "check.compare", "expected \"finest\" or \"richardson\"");
    c.compare_richardson = cmp == "richardson";
    s.checks.push_back(c);
  }
  if (root.get("figure") && !root["figure"].as_array())
    fail_at(s, *root.get("figure"), "figure", "expected [[figure]] tables");
  if (const toml::array* fa = root["figure"].as_array()) {
    for (const auto& n : *fa) {
      const toml::table* t = n.as_table();
      if (!t) fail_at(s, n, "figure", "expected [[figure]] tables");
      Figure f;
      f.id = (*t)["id"].value_or(fmt::format("figure{}", s.figures.size()));
      f.title = (*t)["title"].value_or(f.id);
      f.x = (*t)["x"].value_or(std::string("t"));
      f.y = (*t)["y"].value_or(std::string());
      if (f.y.empty() && !t->get("probe")) fail_at(s, n, "figure.y", "missing: the series quantity to plot (or probe = a probe across variants)");
      f.xlabel = (*t)["xlabel"].value_or(f.x);
      f.ylabel = (*t)["ylabel"].value_or(f.y);
      f.x_scale = (*t)["x_scale"].value_or(1.0);
      f.y_scale = (*t)["y_scale"].value_or(1.0);
      f.ref_scale = (*t)["reference_scale"].value_or(1.0);
      f.y_from_start = (*t)["y_from_start"].value_or(false);
      f.every = (*t)["every"].value_or(int64_t{100});
      f.solver = (*t)["reference"].value_or(std::string());
      f.x_arg = (*t)["x_arg"].value_or(std::string("t"));
      f.args = args_of(s, *t, "args");
      f.variants = strings(s, *t, "variants");
      f.logx = (*t)["logx"].value_or(false);
      f.logy = (*t)["logy"].value_or(false);
      f.y_offset = (*t)["y_offset"].value_or(0.0);
      f.y_minus_reference = (*t)["y_minus_reference"].value_or(false);
      if (f.y_minus_reference && f.solver.empty()) fail_at(s, n, "figure.y_minus_reference", "needs a reference solver");
      f.probe = (*t)["probe"].value_or(std::string());
      f.group_arg = (*t)["group_arg"].value_or(std::string());
      f.group_label = (*t)["group_label"].value_or(f.group_arg);
      f.reference_points = (*t)["reference_points"].value_or(int64_t{0});
      f.reference_per_variant = (*t)["reference_per_variant"].value_or(false);
      if (!f.probe.empty() && f.x_arg == "t") fail_at(s, n, "figure.x_arg", "a probe figure needs x_arg: the variant argument on x");
      for (const char* key : {"x_range", "y_range"}) {
        if (const toml::node* r = t->get(key)) {
          const toml::array* a = r->as_array();
          if (!a || a->size() != 2) fail_at(s, *r, fmt::format("figure.{}", key), "expected [lo, hi]");
          std::vector<double>& out = std::string(key) == "x_range" ? f.x_range : f.y_range;
          for (const auto& x : *a) out.push_back(number_or_quantity(s, x, fmt::format("figure.{}", key)));
          if (!(out[0] < out[1])) fail_at(s, *r, fmt::format("figure.{}", key), "expected lo < hi");
        }
      }
      if (const toml::table* cl = (*t)["labels"].as_table())
        for (const auto& [k, v] : *cl) f.curve_labels[std::string(k.str())] = v.value_or(std::string(k.str()));
      s.figures.push_back(f);
    }
  }
  if (root.get("table") && !root["table"].as_array())
    fail_at(s, *root.get("table"), "table", "expected [[table]] tables");
  if (const toml::array* ta = root["table"].as_array()) {
    if (s.kind == Kind::mode_map) fail(s, "table", "declared tables need kind = single, refinement or stability");
    for (const auto& n : *ta) {
      const toml::table* t = n.as_table();
      if (!t) fail_at(s, n, "table", "expected [[table]] tables");
      TableDecl d;
      d.title = (*t)["title"].value_or(std::string());
      d.probes = strings(s, *t, "probes");
      if (auto p = (*t)["probe"].value<std::string>()) d.probes.insert(d.probes.begin(), *p);
      if (d.probes.empty()) fail_at(s, n, "table.probe", "missing: the probe(s) to tabulate (or element_steps_per_second)");
      d.row_arg = (*t)["row_arg"].value_or(std::string());
      d.column_arg = (*t)["column_arg"].value_or(std::string());
      d.row_label = (*t)["row_label"].value_or(d.row_arg);
      d.column_label = (*t)["column_label"].value_or(d.column_arg);
      if (d.row_arg.empty() != d.column_arg.empty()) fail_at(s, n, "table", "give both row_arg and column_arg (a pivot) or neither");
      if (!d.row_arg.empty() && d.probes.size() != 1) fail_at(s, n, "table.probe", "a pivot table shows one probe");
      d.scale = (*t)["scale"].value_or(1.0);
      d.variants = strings(s, *t, "variants");
      if (d.title.empty()) d.title = d.probes.front();
      s.tables.push_back(d);
    }
  }
  return s;
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
  int threads_per_run = 1;  // the cores left to each run by the study's own parallel runs (--jobs)
};

RunCache* g_cache = nullptr;  // the cache of the study being run (run_study sets it)

RunOut run_one(const Study& s, const std::vector<std::string>& sets, const fs::path& out = {}) {
  const dem::Case c = dem::read_case(s.root / s.case_path, sets);
  fs::path entry;
  if (g_cache && !g_cache->dir.empty()) {
    entry = cache_entry(g_cache->dir, c.resolved, sets, out);
    const bool files_ok = out.empty() || (fs::exists(out / "series.csv") && fs::exists(out / "summary.json"));
    if (files_ok)
      if (const auto cached = read_cached(entry)) {
        ++g_cache->reused;
        return {cached->probes, cached->status, cached->message, cached->eps};
      }
  }
  dem::RunOptions o;  // files only for runs that feed a figure
  o.out_dir = out;
  o.threads = g_cache ? g_cache->threads_per_run : 1;  // results do not depend on it
  const dem::RunResult r = dem::run_case(c, o);
  if (r.status == "interrupted") throw StudyInterrupted(fmt::format("study {}: {}", s.name, r.message));
  if (!entry.empty()) {
    write_cached(entry, {r.status, r.message, r.element_steps_per_second, r.probes}, c.path.string(), sets);
    ++g_cache->ran;
  }
  return {r.probes, r.status, r.message, r.element_steps_per_second};
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
  cache.threads_per_run = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / std::max(1, opt.jobs));
  g_cache = &cache;
  struct Reset {
    ~Reset() { g_cache = nullptr; }
  } reset;

  nlohmann::json checks = nlohmann::json::array(), series_json = nlohmann::json::array();
  bool passed = true;
  auto reference_of = [&](const Check& c, const Variant& v, double param) -> std::optional<double> {
    if (c.value) return c.value;
    if (c.solver.empty()) return std::nullopt;
    std::map<std::string, double> args = v.args;
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
  auto applies = [](const Check& c, const Variant& v) {
    if (c.only.empty()) return true;
    for (const auto& o : c.only)
      if (o == v.label) return true;
    return false;
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
    const std::size_t nl = s.kind == Kind::single ? 1 : s.values.size();
    std::vector<RunOut> runs(s.variants.size() * nl);
    parallel_for(runs.size(), opt.jobs, [&](std::size_t k) {
      const Variant& v = s.variants[k / nl];
      std::vector<std::string> sets = s.set;
      sets.insert(sets.end(), v.set.begin(), v.set.end());
      if (s.kind == Kind::refinement) {
        const double v = s.values[k % nl];
        sets.push_back(v == std::floor(v) && std::abs(v) < 1e15 ? fmt::format("{}={}", s.parameter, static_cast<long long>(v))
                                                               : fmt::format("{}={:.17g}", s.parameter, v));
      }
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
      runs[k] = run_one(s, sets, run_dir);
    });
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
          << (s.kind == Kind::refinement ? fmt::format("{:.17g}", s.values[k % nl]) : "") << "," << runs[k].status;
      for (const auto& c : s.checks) csv << "," << fmt_value(runs[k].probes.count(c.probe) ? runs[k].probes[c.probe] : std::nullopt);
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
            last_ref = reference_of(c, v, s.kind == Kind::refinement ? s.values.back() : 0.0);
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
        const std::optional<double> ref = reference_of(c, v, s.kind == Kind::refinement ? s.values.back() : 0.0);
        std::string note = finest.status == "blow-up" ? "blow-up: " + finest.message : "";
        if (s.kind == Kind::single) {
          add_check(label(c, v), ref, finest.probes.at(c.probe), c, std::nullopt, note);
          continue;
        }
        std::vector<double> h, q;
        for (std::size_t l = 0; l < nl; ++l) {
          const auto& p = runs[vi * nl + l].probes.at(c.probe);
          if (!p) continue;
          h.push_back(s.inverse ? 1.0 / s.values[l] : s.values[l]);
          q.push_back(*p);
        }
        std::optional<double> order;
        if (h.size() >= 2) {
          ConvergenceOptions co;
          if (!c.compare_richardson) co.reference = ref;
          co.expected_order = c.expected_order;
          co.fit_levels = c.fit_levels;
          Series ser = analyse_convergence(h, q, co, label(c, v), s.parameter_label);
          order = c.compare_richardson && h.size() >= 3 ? ser.three_level_order : ser.fitted_order;
          series_json.push_back(to_json(ser));
          if (c.compare_richardson) {
            note += fmt::format(" Richardson extrapolation compared (GCI of the finest level {})", fmt_value(ser.gci_fine));
            add_check(label(c, v) + " (Richardson)", ref, ser.richardson, c, order, note);
            continue;
          }
          if (h.size() < nl) note += fmt::format(" {} of {} levels gave no value", nl - h.size(), nl);
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
      const RunOut r = run_one(s, sets);
      auto get = [&](const char* name) { return r.probes.count(name) ? r.probes.at(name) : std::nullopt; };
      if (r.status == "blow-up" || !get("pivot_x") || !get("rotation") || !get("pivot_x_start") || !get("rotation_start")) return;
      // The motion after the start-up transient: from `pivot_x_start` / `rotation_start` to the end.
      p.slide = *get("pivot_x") - *get("pivot_x_start");
      p.rotation = std::abs(*get("rotation") - *get("rotation_start"));
      const bool slides = p.slide > s.slide_threshold, rotates = p.rotation > s.rotation_threshold;
      p.dem = slides ? (rotates ? 3 : 1) : (rotates ? 2 : 0);
    });
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
    parallel_for(s.variants.size(), opt.jobs, [&](std::size_t vi) {
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
      for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
        const Variant& v = s.variants[vi];
        if (!listed(f.variants, v.label)) continue;
        const fs::path csv = out / "runs" / fmt::format("variant{}", vi) / "series.csv";
        std::ifstream in(csv);
        std::string line;
        std::vector<std::string> header;
        std::vector<double> xs, ys;
        while (std::getline(in, line)) {
          if (line.empty() || line[0] == '#') continue;
          const std::vector<std::string> cells = dem::split_csv(line);
          if (header.empty()) {
            header = cells;
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
        if (f.reference_per_variant && !f.solver.empty() && !f.y_minus_reference) {
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
            ry.push_back(evaluate(f.solver, a) * f.ref_scale * f.y_scale);
          }
          curves.push_back({{"label", words(f, f.solver, "reference") + ", " + v.label}, {"x", rx}, {"y", ry},
                            {"style", "reference"}});
        }
      }
      if (f.reference_per_variant) ref_x.clear();
      if (!f.solver.empty() && !ref_x.empty() && !f.y_minus_reference) {
        std::vector<double> px, py;
        for (double x : ref_x) {
          std::map<std::string, double> a = ref_args;
          a[f.x_arg] = x;
          px.push_back(x * f.x_scale);
          py.push_back(evaluate(f.solver, a) * f.ref_scale * f.y_scale);
        }
        curves.push_back({{"label", words(f, f.solver, "reference: " + f.solver)}, {"x", px}, {"y", py}, {"style", "reference"}});
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
  if (s.kind == Kind::refinement) setup["levels"] = s.values;
  if (speed_n) setup["mean element-steps per second"] = speed_sum / static_cast<double>(speed_n);
  nlohmann::json prov = dem::provenance();
  prov["overrides"] = s.set;
  nlohmann::json result = {
      {"study", s.name}, {"title", s.title}, {"requirement", s.requirement},
      {"kind", s.kind == Kind::refinement ? "refinement" : s.kind == Kind::single ? "single" : s.kind == Kind::stability ? "stability" : "mode_map"},
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
