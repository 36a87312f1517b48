#include "engine/sensitivity.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <limits>
#include <optional>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "dem/cases/case_file.hpp"
#include "dem/cases/case_reader.hpp"
#include "dem/cases/units.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"
#include "engine/convergence.hpp"
#include "engine/run_cache.hpp"
#include "engine/run_dispatch.hpp"
#include "engine/sensitivity_estimators.hpp"
#include "engine/sensitivity_functions.hpp"
#include "engine/sensitivity_sampling.hpp"
#include "engine/sensitivity_transform.hpp"

namespace fs = std::filesystem;

namespace ver {

namespace {

using sens::Parameter;

struct Sens {
  fs::path file, case_file;  // case_file: the base case, resolved relative to the sensitivity file's folder
  std::string name, title, requirement, case_path;
  std::optional<sens::TestFunction> function;
  std::vector<std::string> set, outputs;
  std::vector<Parameter> params;
  bool oat = false, morris = false, sobol = false;
  std::size_t oat_points = 5;
  std::size_t trajectories = 10;
  int levels = 4;
  std::uint64_t seed = 1;
  std::size_t samples = 256, resamples = 1000;
  double confidence = 0.95;
  std::vector<std::size_t> convergence;     // function studies: Sobol' sample sizes for the error rate
  std::optional<double> expected_order;
  double order_band = 0.3;
  // [sobol] transforms: the indices of each listed monotone transform of the output, IN ADDITION to
  // those of the output itself (sensitivity_transform.hpp).
  std::vector<sens::Transform> transforms;
  int max_failed = 0;
  // Δt tied to the time-step guard: each run's Δt = dt_fraction × the guard's limit for that run's
  // parameters (stiffness, mass, damping move the limit). dt_fraction_base: the fraction is the base
  // case's own Δt / limit (so the base run keeps the case's Δt).
  std::optional<double> dt_fraction;
  bool dt_fraction_base = false;
  // Replicates: every sample runs once per entry (that entry's overrides after the sample's) and its
  // outputs are the mean over the entries — for outputs with run-to-run noise (a silo's discharge rate
  // set by which arches form): the noise of the mean falls as 1/√(entries).
  std::vector<std::vector<std::string>> replicates;
  nlohmann::json setup = nlohmann::json::object();
};

constexpr const char* kHelp = "verification/README.md, \"Sensitivity studies\"";
using dem::TableReader;

[[noreturn]] void fail_at(const Sens& s, const toml::node* n, const std::string& key, const std::string& what) {
  throw dem::CaseError(n ? fmt::format("{}: {}: {}", dem::where(*n, s.file.string()), key, what)
                         : fmt::format("{}: {}: {}", s.file.string(), key, what));
}

/// A list of "path=value" overrides.
std::vector<std::string> overrides_of(const TableReader& r, const toml::node& n, const std::string& key) {
  const toml::array* a = n.as_array();
  if (!a) r.fail_at(n, key, "expected a list of \"path=value\" overrides");
  std::vector<std::string> sets;
  for (const auto& x : *a) {
    auto v = x.value_exact<std::string>();
    if (!v || v->find('=') == std::string::npos) r.fail_at(x, key, "expected \"path=value\"");
    sets.push_back(*v);
  }
  return sets;
}

void read_header(Sens& s, const TableReader& top) {
  const std::string file = s.file.string();
  const toml::table* st = top.table("sensitivity");
  if (!st) top.fail("sensitivity", "missing [sensitivity] table");
  TableReader r(*st, "sensitivity", file, kHelp);
  s.name = r.string("name", fs::absolute(s.file).parent_path().filename().string());
  if (s.name.empty() || s.name == "." || s.name == ".." ||
      s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") != std::string::npos)
    r.fail("name", fmt::format("expected a plain folder name, got \"{}\"", s.name));
  s.title = r.string("title", s.name);
  s.requirement = r.string("requirement", "");
  s.case_path = r.string("case", "");
  if (!s.case_path.empty()) {
    s.case_file = (fs::absolute(s.file).parent_path() / s.case_path).lexically_normal();
    if (std::error_code ec; !fs::is_regular_file(s.case_file, ec))
      throw dem::CaseError(fmt::format("file not found: {} (from {})", s.case_file.string(), dem::where(*st->get("case"), file)));
  }
  if (r.has("function")) {
    sens::TestFunction f{r.choice("function", {"ishigami", "g", "linear"}, ""), {}};
    r.mark("coefficients");
    if (const toml::node* cn = r.node("coefficients")) {
      const toml::array* c = cn->as_array();
      if (!c) r.fail("coefficients", "expected an array of numbers");
      for (const auto& x : *c) f.coefficients.push_back(r.any_quantity_of(x, "coefficients").value);
    }
    if (f.name == "ishigami" && f.coefficients.size() != 2) r.fail("coefficients", "ishigami takes [a, b]");
    if (f.name != "ishigami" && f.coefficients.empty()) r.fail("coefficients", "expected one coefficient per parameter");
    s.function = f;
  } else if (r.has("coefficients")) {
    r.fail("coefficients", "coefficients belong to a test function (function = ...)");
  }
  if (s.case_path.empty() == !s.function.has_value())
    r.fail_here("give either a case file or a test function (function = \"ishigami\" | \"g\" | \"linear\")");
  s.set = r.strings("set");
  s.outputs = r.strings("outputs");
  if (s.function) {
    if (!s.outputs.empty()) r.fail("outputs", "a test function has one output, f: remove outputs");
    s.outputs = {"f"};
  }
  if (s.outputs.empty()) r.fail_here("missing outputs: the probes of the case to analyse");
  for (const std::string& m : r.strings("methods")) {
    if (m == "oat") s.oat = true;
    else if (m == "morris") s.morris = true;
    else if (m == "sobol") s.sobol = true;
    else {
      const std::string near = dem::nearest_word(m, {"oat", "morris", "sobol"});
      r.fail("methods", fmt::format("expected oat, morris or sobol, got \"{}\"{}", m, near.empty() ? "" : "; did you mean \"" + near + "\"?"));
    }
  }
  if (!s.oat && !s.morris && !s.sobol) r.fail_here("missing methods: any of [\"oat\", \"morris\", \"sobol\"]");
  s.max_failed = static_cast<int>(r.integer("max_failed_runs", 0, 1'000'000'000, 0));
  r.mark("dt_fraction");
  if (const toml::node* n = r.node("dt_fraction")) {
    if (auto str = n->value_exact<std::string>(); str && *str == "base") s.dt_fraction_base = true;
    else if (auto x = n->value<double>(); x && *x > 0.0 && std::isfinite(*x)) s.dt_fraction = *x;
    else r.fail("dt_fraction", "expected a number > 0 (Δt = that × the guard's limit) or \"base\"");
    if (s.function) r.fail("dt_fraction", "only for a case (a test function has no time step)");
  }
  r.mark("replicates");
  if (const toml::node* rn = r.node("replicates")) {
    const toml::array* ra = rn->as_array();
    if (!ra || ra->size() < 2)
      r.fail("replicates", "expected at least 2 lists of overrides, e.g. [[\"numerics.dt=5e-5 s\"], [\"numerics.dt=4.9e-5 s\"]]");
    if (s.function) r.fail("replicates", "only for a case (a test function has no noise)");
    for (const auto& e : *ra) s.replicates.push_back(overrides_of(r, e, "replicates"));
  }
  if (const toml::table* su = r.table("setup"))
    for (const auto& [k, v] : *su) {
      if (auto x = v.value<double>()) s.setup[std::string(k.str())] = *x;
      else if (auto y = v.value_exact<std::string>()) s.setup[std::string(k.str())] = *y;
      else r.fail_at(v, "setup." + std::string(k.str()), "expected a number or a string (shown in the report)");
    }
  r.finish();
}

/// The value of a parameter bound as written, checked against the case key it sets: the case reader
/// reads the case with `path = <value as written>` and refuses a wrong unit ("1 m" for a damping ratio).
void check_against_case(const Sens& s, const TableReader& r, const Parameter& p, const char* key) {
  if (s.function || p.path.empty()) return;
  const toml::node& n = *r.node(key);
  const std::string written = n.is_string() ? *n.value<std::string>() : fmt::format("{:.17g}", *n.value<double>());
  std::vector<std::string> sets = s.set;
  sets.push_back(p.path + "=" + written);
  try {
    (void)dem::read_case(s.case_file, sets);
  } catch (const dem::CaseError& e) {
    r.fail(key, fmt::format("\"{}\" cannot set {}: {}", written, p.path, e.what()));
  }
}

Parameter read_parameter(const Sens& s, const TableReader& r, const toml::node& n) {
  Parameter p;
  p.path = r.string("path", "");
  if (p.path.empty() && !s.function) r.fail_at(n, "path", "missing: the --set path, e.g. contact.0.kn");
  if (!p.path.empty() && s.function) r.fail("path", "a test function's inputs have no case path: remove path");
  p.label = r.string("label", p.path.empty() ? fmt::format("x{}", s.params.size() + 1) : p.path);
  const dem::Quantity low = r.any_quantity("low"), high = r.any_quantity("high");
  if (!(low.dim == high.dim)) r.fail("high", fmt::format("low is {}, high is {}: give both in one kind of unit",
                                                         dem::to_string(low.dim), dem::to_string(high.dim)));
  p.low = low.value;
  p.high = high.value;
  p.angle = low.dim == dem::dims::angle;
  check_against_case(s, r, p, "low");
  check_against_case(s, r, p, "high");
  p.log_uniform = r.choice("distribution", {"uniform", "log-uniform"}, "uniform") == "log-uniform";
  p.integer = r.boolean("integer", false);
  r.mark("also");
  if (const toml::node* an = r.node("also")) {
    const toml::array* aa = an->as_array();
    if (!aa) r.fail("also", "expected an array of { path, scale, exponent } tables");
    for (const auto& x : *aa) {
      const toml::table* ft = x.as_table();
      if (!ft) r.fail_at(x, "also", "expected { path = \"...\", scale = 1, exponent = 1 }");
      TableReader f(*ft, "parameter.also", s.file.string(), kHelp);
      Parameter::Follower fo;
      fo.path = f.string("path");
      fo.scale = f.optional_any_quantity("scale").value_or(dem::Quantity{1.0, dem::dims::dimensionless}).value;
      fo.exponent = f.number("exponent", 1.0);
      f.finish();
      p.also.push_back(fo);
    }
  }
  if (p.integer && (p.log_uniform || p.low != std::floor(p.low) || p.high != std::floor(p.high)))
    r.fail("integer", fmt::format("\"{}\": integer parameters need integer low and high, uniform", p.label));
  if (!(p.high > p.low) || (p.log_uniform && !(p.low > 0.0)))
    r.fail_at(n, "low", fmt::format("\"{}\": need low < high (and low > 0 for log-uniform)", p.label));
  return p;
}

void read_methods(Sens& s, const TableReader& top) {
  const std::string file = s.file.string();
  constexpr std::int64_t kMaxSize = std::int64_t{1} << 24;  // runs and samples: beyond any machine's budget
  if (const toml::table* t = top.table("oat")) {
    TableReader r(*t, "oat", file, kHelp);
    s.oat_points = static_cast<std::size_t>(r.integer("points", 2, 100000, 5));
    r.finish();
  }
  if (const toml::table* t = top.table("morris")) {
    TableReader r(*t, "morris", file, kHelp);
    s.trajectories = static_cast<std::size_t>(r.integer("trajectories", 1, kMaxSize, 10));
    s.levels = static_cast<int>(r.integer("levels", 2, 1000, 4));
    s.seed = static_cast<std::uint64_t>(r.integer("seed", 1, std::numeric_limits<std::int64_t>::max(), 1));
    if (s.levels % 2 != 0) r.fail("levels", "expected an even number of levels (4, 6, 8)");
    r.finish();
  }
  if (const toml::table* t = top.table("sobol")) {
    TableReader r(*t, "sobol", file, kHelp);
    s.samples = static_cast<std::size_t>(r.integer("samples", 1, kMaxSize, 256));
    s.resamples = static_cast<std::size_t>(r.integer("bootstrap", 1, 1'000'000, 1000));
    s.confidence = r.number_in("confidence", 0.0, 1.0, 0.95, true, true);
    r.mark("convergence");
    if (const toml::node* cn = r.node("convergence")) {
      const toml::array* c = cn->as_array();
      if (!c) r.fail("convergence", "expected an array of sample sizes");
      for (const auto& x : *c) {
        auto v = x.value_exact<int64_t>();
        if (!v || *v < 4 || *v > kMaxSize) r.fail_at(x, "convergence", "expected sample sizes from 4 to 2^24, increasing");
        s.convergence.push_back(static_cast<std::size_t>(*v));
      }
      for (std::size_t k = 1; k < s.convergence.size(); ++k)
        if (s.convergence[k] <= s.convergence[k - 1]) r.fail("convergence", "expected increasing sample sizes");
    }
    if (r.has("expected_order")) {
      s.expected_order = r.number_in("expected_order", 0.0, 20.0, 0.0, true);
      if (s.convergence.empty()) r.fail("expected_order", "needs convergence = [sample sizes] (the order is their error rate)");
    } else if (r.has("order_band")) {
      r.fail("order_band", "needs expected_order (the band is around it)");
    }
    s.order_band = r.number_in("order_band", 0.0, 10.0, 0.3, true);
    r.mark("transforms");
    if (const toml::node* tn = r.node("transforms")) {
      const toml::array* ta = tn->as_array();
      if (!ta) r.fail("transforms", "expected an array such as [\"rank\"] or [\"log\", \"rank\"]");
      for (const auto& x : *ta) {
        try {
          const auto word = x.value_exact<std::string>();
          if (!word) throw std::invalid_argument("expected a string: \"log\" or \"rank\"");
          const sens::Transform tf = sens::parse_transform(*word);
          if (tf == sens::Transform::none) throw std::invalid_argument("\"none\" is always analysed; list \"log\" or \"rank\"");
          if (std::find(s.transforms.begin(), s.transforms.end(), tf) != s.transforms.end()) throw std::invalid_argument("listed twice");
          s.transforms.push_back(tf);
        } catch (const std::invalid_argument& e) {
          r.fail_at(x, "transforms", e.what());
        }
      }
    }
    r.finish();
  }
  // A method's table without the method listed is a mistake (its settings would be ignored).
  for (const auto& [name, on] : {std::pair{"oat", s.oat}, std::pair{"morris", s.morris}, std::pair{"sobol", s.sobol}})
    if (!on && top.node(name)) top.fail(name, fmt::format("[{}] is given but methods does not list \"{}\"", name, name));
}

/// What holds across the tables: Δt and replicates against the parameters, the function's inputs.
void cross_check(const Sens& s, const toml::table& st, const toml::node* pn) {
  if (s.dt_fraction || s.dt_fraction_base)
    for (const Parameter& p : s.params)
      if (p.path == "numerics.dt")
        fail_at(s, st.get("dt_fraction"), "sensitivity.dt_fraction", "Δt follows the guard's limit, so numerics.dt cannot also be a parameter");
  for (const auto& sets : s.replicates)  // a replicate's override would silently undo a parameter's value
    for (const std::string& x : sets) {
      const std::string path = x.substr(0, x.find('='));
      for (const Parameter& p : s.params) {
        bool clash = p.path == path;
        for (const auto& f : p.also) clash = clash || f.path == path;
        if (clash)
          fail_at(s, st.get("replicates"), "sensitivity.replicates",
                  fmt::format("\"{}\" is set by the parameter \"{}\"; a replicate may not override it", path, p.label));
      }
      if (path == "numerics.dt" && (s.dt_fraction || s.dt_fraction_base))
        fail_at(s, st.get("replicates"), "sensitivity.replicates", "Δt follows the guard's limit (dt_fraction): a replicate may not set it");
    }
  if (s.function && sens::dimension(*s.function) != s.params.size())
    fail_at(s, pn, "parameter", fmt::format("the function {} takes {} inputs, {} parameters given", s.function->name,
                                            sens::dimension(*s.function), s.params.size()));
  if (s.sobol && 2 * s.params.size() > 40) fail_at(s, pn, "parameter", "Sobol': at most 20 parameters (GSL's sequence has 40 dimensions)");
  if (!s.function) {  // every output is a probe of the case
    const dem::Case base = dem::read_case(s.case_file, s.set);
    std::vector<std::string> names;
    for (const auto& p : base.probes) names.push_back(p.name);
    for (const std::string& o : s.outputs)
      if (std::find(names.begin(), names.end(), o) == names.end()) {
        const std::string near = dem::nearest_word(o, names);
        fail_at(s, st.get("outputs"), "sensitivity.outputs", fmt::format("the case has no probe \"{}\"{}", o,
                near.empty() ? "" : fmt::format("; did you mean \"{}\"?", near)));
      }
  }
  if (!s.function)  // every replicate's overrides apply to the case
    for (const auto& sets : s.replicates) {
      std::vector<std::string> all = s.set;
      all.insert(all.end(), sets.begin(), sets.end());
      try {
        (void)dem::read_case(s.case_file, all);
      } catch (const dem::CaseError& e) {
        fail_at(s, st.get("replicates"), "sensitivity.replicates", e.what());
      }
    }
}

Sens read_sens(const fs::path& file) {
  Sens s;
  s.file = file;
  const toml::table root = dem::parse_toml_file(file);
  TableReader top(root, "", file.string(), kHelp);
  read_header(s, top);
  top.mark("parameter");
  const toml::node* pn = root.get("parameter");
  if (!pn || !pn->as_array() || pn->as_array()->empty()) fail_at(s, pn, "parameter", "expected [[parameter]] tables (path, low, high)");
  for (const auto& n : *pn->as_array()) {
    const toml::table* t = n.as_table();
    if (!t) fail_at(s, &n, "parameter", "expected [[parameter]] tables");
    TableReader r(*t, "parameter", file.string(), kHelp);
    s.params.push_back(read_parameter(s, r, n));
    r.finish();
  }
  read_methods(s, top);
  top.finish();
  cross_check(s, *root["sensitivity"].as_table(), pn);
  return s;
}

// ---- runs: the study engine's cache and pool (engine/run_cache.hpp) ----

struct Run {
  std::vector<double> u;                      // unit coordinates (OAT: NaN for parameters left at base)
  std::vector<std::string> sets;
  std::string method, status, message;
  std::vector<double> outputs;                // NaN: missing
  double dt = std::nan("");                   // dt_fraction: the Δt this run used
};

/// The time-step guard's limit for a case with these overrides (the guard's refusal off while it is asked).
double guard_limit(const fs::path& case_file, std::vector<std::string> sets) {
  sets.push_back("numerics.allow_unstable=true");
  return dem::check_case(dem::read_case(case_file, sets));
}

struct Runner {
  const Sens& s;
  fs::path cache_dir;
  double dt_fraction = 0.0;  // > 0: Δt = dt_fraction × the guard's limit of each run
  std::atomic<int> reused{0}, ran{0};
  int duplicates = 0;  // runs with the same overrides as an earlier run of the study: run once, result shared

  void run_function(Run& r) const {
    std::vector<double> x;
    for (std::size_t i = 0; i < s.params.size(); ++i)  // the base point of a function: mid-range
      x.push_back(sens::value_at(s.params[i], std::isfinite(r.u[i]) ? r.u[i] : 0.5));
    r.outputs = {sens::evaluate(*s.function, x)};
    r.status = std::isfinite(r.outputs[0]) ? "completed" : "non-finite";
  }

  void set_outputs(Run& r, const std::map<std::string, std::optional<double>>& probes) const {
    for (const auto& o : s.outputs) {
      if (r.status != "refused" && r.status != "blow-up" && !probes.count(o))
        throw std::runtime_error(fmt::format("{}: sensitivity.outputs: the case has no probe \"{}\"", s.file.string(), o));
      const auto it = probes.find(o);
      r.outputs.push_back(it != probes.end() && it->second && r.status != "blow-up" ? *it->second : std::nan(""));
    }
  }

  /// Every run: a test function here; DEM runs from the cache, the others through run_all (threads
  /// here or the ranks of an MPI job, run_dispatch.hpp), each cached as it finishes. Results go to
  /// the run's own slot, whatever order the runs finish in.
  void run_all_runs(std::vector<Run>& runs, int jobs) {
    if (s.function) {
      for (Run& r : runs) run_function(r);
      return;
    }
    std::vector<std::map<std::string, std::optional<double>>> probes(runs.size());
    std::vector<RunRequest> reqs;
    std::vector<std::size_t> slot;
    std::vector<fs::path> entries;
    std::vector<std::string> case_paths;
    const fs::path case_file = fs::absolute(s.case_file);
    // Δt tied to the guard: each run's limit first (in parallel; a refusal is the run's result).
    std::vector<char> settled(runs.size(), 0);
    // A design may hold the same point more than once (Saltelli's row 0 is the origin in A, B and
    // every AB_i; integer parameters repeat values): the same overrides are the same cache entry, so
    // each is run once and its reply goes to every run that shares the entry.
    std::map<fs::path, std::size_t> request_of;        // cache entry → index into reqs
    std::vector<std::vector<std::size_t>> shared_by;   // per request: the further runs that use its reply
    if (dt_fraction > 0.0)
      parallel_for(runs.size(), jobs, [&](std::size_t k) {
        Run& r = runs[k];
        try {
          r.dt = dt_fraction * guard_limit(s.case_file, r.sets);
          r.sets.push_back(fmt::format("numerics.dt={:.17g}", r.dt));
        } catch (const dem::CaseError& e) {
          r.status = "refused";
          r.message = e.what();
          r.outputs.assign(s.outputs.size(), std::nan(""));
          settled[k] = 1;
        }
      });
    for (std::size_t k = 0; k < runs.size(); ++k) {
      if (settled[k]) continue;
      Run& r = runs[k];
      const dem::Case c = dem::read_case(s.case_file, r.sets);  // a bad path or value: the study fails
      const fs::path entry = cache_entry(cache_dir, c.resolved, r.sets);
      if (const auto cached = read_cached(entry)) {
        r.status = cached->status;
        r.message = cached->message;
        probes[k] = cached->probes;
        ++reused;
        continue;
      }
      if (const auto it = request_of.find(entry); it != request_of.end()) {
        shared_by[it->second].push_back(k);
        ++duplicates;
        continue;
      }
      request_of.emplace(entry, reqs.size());
      shared_by.emplace_back();
      reqs.push_back({case_file, r.sets, {}, run_cost(c)});
      slot.push_back(k);
      entries.push_back(entry);
      case_paths.push_back(c.path.string());
    }
    run_all(reqs, jobs, [&](std::size_t i, RunReply& rep) {
      Run& r = runs[slot[i]];
      r.status = rep.status;
      r.message = rep.message;
      if (rep.status == "interrupted" || rep.status == "error") return;
      if (rep.status == "case-error") {  // the time-step guard (or another check before the run) refused it
        r.status = "refused";
        rep.probes.clear();
      }
      probes[slot[i]] = rep.probes;
      write_cached(entries[i], {r.status, r.message, 0.0, rep.probes}, case_paths[i], r.sets);  // at once
      ++ran;
    });
    for (std::size_t i = 0; i < reqs.size(); ++i)
      for (std::size_t k : shared_by[i]) {
        runs[k].status = runs[slot[i]].status;
        runs[k].message = runs[slot[i]].message;
        probes[k] = probes[slot[i]];
      }
    for (std::size_t k = 0; k < runs.size(); ++k) {  // the first failure in run order
      if (runs[k].status == "interrupted") throw StudyInterrupted(fmt::format("sensitivity {}: {}", s.name, runs[k].message));
      if (runs[k].status == "error") throw std::runtime_error(runs[k].message);
    }
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (!settled[k]) set_outputs(runs[k], probes[k]);
  }
};


bool run_ok(const Run& r) { return r.status != "refused" && r.status != "blow-up" && r.status != "non-finite"; }

/// One sample from its replicates: the mean of every output (missing if any replicate's is), the status
/// and message of the first replicate that failed (else the first's), the mean Δt.
Run replicate_mean(const Run* reps, std::size_t count) {
  Run r = reps[0];
  for (std::size_t j = 1; j < count; ++j) {
    const Run& x = reps[j];
    if (run_ok(r) && !run_ok(x)) {
      r.status = x.status;
      r.message = fmt::format("replicate {}: {}", j + 1, x.message);
    }
    for (std::size_t o = 0; o < r.outputs.size(); ++o) r.outputs[o] += x.outputs[o];  // NaN stays NaN
    r.dt += x.dt;
  }
  for (double& y : r.outputs) y /= static_cast<double>(count);
  r.dt /= static_cast<double>(count);
  return r;
}

/// The overrides that put parameter p at value v: its path and every path that follows it.
void push_sets(std::vector<std::string>& sets, const Parameter& p, double v) {
  sets.push_back(fmt::format("{}={:.17g}{}", p.path, v, p.angle ? " rad" : ""));
  for (const auto& f : p.also) sets.push_back(fmt::format("{}={:.17g}", f.path, f.scale * std::pow(v, f.exponent)));
}

std::string num(double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : std::string("—"); }
nlohmann::json jnum(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

StudyResult run_sensitivity(const fs::path& file, const StudyOptions& opt) {
  const auto started = std::chrono::steady_clock::now();
  const Sens s = read_sens(file);
  const std::size_t d = s.params.size(), no = s.outputs.size();
  const fs::path out = opt.out_dir.empty() ? fs::path("build/studies") / s.name : opt.out_dir;
  fs::create_directories(out);
  fs::remove(out / "result.json");
  dem::write_file_atomic(out / "running.json", nlohmann::json{{"study", s.name}, {"status", "running"},
                                                              {"provenance", dem::provenance()}}.dump(2) + "\n");
  Runner runner{s, out / "cache"};
  if (!opt.use_cache) fs::remove_all(runner.cache_dir);
  fs::create_directories(runner.cache_dir);

  // Every path and value is checked before anything runs: each parameter at both ends of its range.
  if (!s.function)
    for (const Parameter& p : s.params)
      for (double v : {p.low, p.high}) {
        std::vector<std::string> sets = s.set;
        push_sets(sets, p, v);
        (void)dem::read_case(s.case_file, sets);
      }

  if (s.dt_fraction) runner.dt_fraction = *s.dt_fraction;
  if (s.dt_fraction_base) {
    const dem::Case base = dem::read_case(s.case_file, s.set);
    runner.dt_fraction = base.model.numerics.dt / guard_limit(s.case_file, s.set);
  }

  auto make_run = [&](const std::string& method, const std::vector<double>& u) {
    Run r;
    r.method = method;
    r.u = u;
    r.sets = s.set;
    for (std::size_t i = 0; i < d; ++i)
      if (std::isfinite(u[i])) push_sets(r.sets, s.params[i], sens::value_at(s.params[i], u[i]));
    return r;
  };

  std::vector<Run> runs;
  // one-at-a-time: the base case, then each parameter over its range with the others at the base case's values
  std::size_t oat_begin = runs.size();
  const std::vector<double> grid = sens::oat_grid(s.oat_points);
  if (s.oat) {
    runs.push_back(make_run("oat base", std::vector<double>(d, std::nan(""))));
    for (std::size_t i = 0; i < d; ++i)
      for (double u : grid) {
        std::vector<double> x(d, std::nan(""));
        x[i] = u;
        runs.push_back(make_run(fmt::format("oat {}", s.params[i].label), x));
      }
  }
  const std::size_t morris_begin = runs.size();
  std::vector<sens::MorrisTrajectory> traj;
  if (s.morris) {
    traj = sens::morris_trajectories(s.trajectories, d, s.levels, s.seed);
    for (std::size_t t = 0; t < traj.size(); ++t)
      for (const auto& p : traj[t].points) runs.push_back(make_run(fmt::format("morris {}", t), p));
  }
  const std::size_t sobol_begin = runs.size();
  const std::size_t n = s.samples;
  if (s.sobol) {
    const sens::SaltelliDesign des = sens::saltelli_design(n, d);
    for (const auto& row : des.a) runs.push_back(make_run("sobol A", row));
    for (const auto& row : des.b) runs.push_back(make_run("sobol B", row));
    for (std::size_t i = 0; i < d; ++i)
      for (const auto& row : des.ab[i]) runs.push_back(make_run(fmt::format("sobol AB{}", i + 1), row));
  }
  if (s.replicates.empty()) {
    runner.run_all_runs(runs, opt.jobs);
  } else {  // every sample once per replicate, then the mean per sample
    const std::size_t nr = s.replicates.size();
    std::vector<Run> reps;
    reps.reserve(runs.size() * nr);
    for (const Run& r : runs)
      for (const auto& extra : s.replicates) {
        Run x = r;
        x.sets.insert(x.sets.end(), extra.begin(), extra.end());
        reps.push_back(std::move(x));
      }
    runner.run_all_runs(reps, opt.jobs);
    for (std::size_t k = 0; k < runs.size(); ++k) runs[k] = replicate_mean(&reps[k * nr], nr);
  }
  fs::remove(out / "running.json");

  // The table of every run: inputs (values; blank = the base case's), outputs, status.
  std::ostringstream csv;
  csv << "run,method";
  for (const auto& p : s.params) csv << ",\"" << p.label << "\"";
  const bool derived_dt = runner.dt_fraction > 0.0;
  if (derived_dt) csv << ",dt";
  for (const auto& o : s.outputs) csv << "," << o;
  csv << ",status,message\n";
  int failed = 0;
  nlohmann::json run_rows = nlohmann::json::array();
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Run& r = runs[k];
    const bool ok = run_ok(r);
    failed += !ok;
    csv << k << "," << r.method;
    nlohmann::json row = {std::to_string(k), r.method};
    for (std::size_t i = 0; i < d; ++i) {
      const std::string v = std::isfinite(r.u[i]) ? fmt::format("{:.6g}", sens::value_at(s.params[i], r.u[i])) : std::string("base");
      csv << "," << (std::isfinite(r.u[i]) ? fmt::format("{:.17g}", sens::value_at(s.params[i], r.u[i])) : std::string());
      row.push_back(v);
    }
    if (derived_dt) {
      csv << "," << (std::isfinite(r.dt) ? fmt::format("{:.17g}", r.dt) : std::string());
      row.push_back(num(r.dt));
    }
    for (double y : r.outputs) {
      csv << "," << (std::isfinite(y) ? fmt::format("{:.17g}", y) : std::string());
      row.push_back(num(y));
    }
    std::string msg = r.message;
    std::replace(msg.begin(), msg.end(), '"', '\'');
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    csv << "," << r.status << ",\"" << msg << "\"\n";
    row.push_back(r.status);
    run_rows.push_back(row);
  }
  dem::write_file_atomic(out / "runs.csv", csv.str(), false);

  nlohmann::json checks = nlohmann::json::array(), tables = nlohmann::json::array(), figures = nlohmann::json::array(),
                 series = nlohmann::json::array();
  bool passed = true;
  auto add_check = [&](const std::string& q, double ref, double val, double err, double tol, const std::string& reason,
                       bool ok, const std::string& note, std::optional<double> order = std::nullopt) {
    passed = passed && ok;
    checks.push_back({{"quantity", q}, {"reference", jnum(ref)}, {"dem", jnum(val)}, {"error", jnum(err)},
                      {"error_kind", "abs"}, {"tolerance", jnum(tol)}, {"tolerance_reason", reason},
                      {"observed_order", order ? nlohmann::json(*order) : nlohmann::json(nullptr)},
                      {"expected_order", order && s.expected_order ? nlohmann::json(*s.expected_order) : nlohmann::json(nullptr)},
                      {"order_band", order && s.expected_order ? nlohmann::json(s.order_band) : nlohmann::json(nullptr)},
                      {"passed", ok}, {"note", note}});
  };
  sens::ExactIndices exact;
  if (s.function) {
    std::vector<double> lo, hi;
    for (const auto& p : s.params) {
      lo.push_back(p.low);
      hi.push_back(p.high);
    }
    exact = sens::exact_indices(*s.function, lo, hi);
  }
  std::ostringstream idx_csv;
  idx_csv << "method,output,parameter,index,estimate,low,high,exact\n";
  auto plain = [](const std::string& x) { return x; };

  if (s.oat) {
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t o = 0; o < no; ++o) {
      nlohmann::json curves = nlohmann::json::array();
      for (std::size_t i = 0; i < d; ++i) {
        std::vector<double> xs, ys;
        double ymin = INFINITY, ymax = -INFINITY;
        for (std::size_t g = 0; g < grid.size(); ++g) {
          const double y = runs[oat_begin + 1 + i * grid.size() + g].outputs[o];
          if (!std::isfinite(y)) continue;
          xs.push_back(grid[g]);
          ys.push_back(y);
          ymin = std::min(ymin, y);
          ymax = std::max(ymax, y);
        }
        curves.push_back({{"label", s.params[i].label}, {"x", xs}, {"y", ys}, {"style", "linespoints"}});
        const double range = ys.empty() ? std::nan("") : ymax - ymin;
        rows.push_back({s.outputs[o], s.params[i].label,
                        fmt::format("{} … {}{}", num(s.params[i].low), num(s.params[i].high), s.params[i].log_uniform ? " (log)" : s.params[i].integer ? " (integer)" : ""),
                        num(ys.empty() ? NAN : ys.front()), num(ys.empty() ? NAN : ys.back()), num(range),
                        num(range / std::abs(runs[oat_begin].outputs[o]))});
        idx_csv << "oat," << s.outputs[o] << ",\"" << plain(s.params[i].label) << "\",range," << fmt::format("{:.17g}", range) << ",,,\n";
      }
      figures.push_back({{"id", fmt::format("oat_{}", o)},
                         {"title", fmt::format("One-at-a-time sweeps of {} (others at the base case; base value {})", s.outputs[o], num(runs[oat_begin].outputs[o]))},
                         {"xlabel", "position in the parameter's range u (0 = low, 1 = high; log scale for log-uniform)"},
                         {"ylabel", s.outputs[o]}, {"logx", false}, {"logy", false}, {"curves", curves}});
    }
    tables.push_back({{"title", "One-at-a-time sweeps: the output at both ends of each range"},
                      {"columns", {"output", "parameter", "range", "at low", "at high", "max − min", "(max − min) / |base|"}},
                      {"rows", rows}});
  }

  if (s.morris) {
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t o = 0; o < no; ++o) {
      std::vector<std::vector<double>> f(traj.size());
      std::size_t k = morris_begin;
      for (std::size_t t = 0; t < traj.size(); ++t)
        for (std::size_t p = 0; p < traj[t].points.size(); ++p) f[t].push_back(runs[k++].outputs[o]);
      const sens::MorrisEffects m = sens::morris_effects(traj, f, d);
      nlohmann::json curves = nlohmann::json::array(), labels = nlohmann::json::array();
      for (std::size_t i = 0; i < d; ++i) {
        if (std::isfinite(m.mu_star[i]) && std::isfinite(m.sigma[i]))
          labels.push_back({{"x", m.mu_star[i]}, {"y", m.sigma[i]}, {"text", s.params[i].label}});
        rows.push_back({s.outputs[o], s.params[i].label, num(m.mu_star[i]), num(m.mu[i]), num(m.sigma[i]),
                        std::to_string(m.effects[i]), exact.morris_mu_star.empty() ? "" : num(exact.morris_mu_star[i])});
        curves.push_back({{"label", s.params[i].label}, {"x", {jnum(m.mu_star[i])}}, {"y", {jnum(m.sigma[i])}}, {"style", "points"}});
        idx_csv << "morris," << s.outputs[o] << ",\"" << s.params[i].label << "\",mu_star," << fmt::format("{:.17g}", m.mu_star[i]) << ",,,"
                << (exact.morris_mu_star.empty() ? std::string() : fmt::format("{:.17g}", exact.morris_mu_star[i])) << "\n";
        idx_csv << "morris," << s.outputs[o] << ",\"" << s.params[i].label << "\",mu," << fmt::format("{:.17g}", m.mu[i]) << ",,,\n";
        idx_csv << "morris," << s.outputs[o] << ",\"" << s.params[i].label << "\",sigma," << fmt::format("{:.17g}", m.sigma[i]) << ",,,\n";
        if (!exact.morris_mu_star.empty()) {
          const double e = std::abs(m.mu_star[i] - exact.morris_mu_star[i]);
          const double tol = 1e-9 * std::max(1.0, exact.morris_mu_star[i]);
          add_check(fmt::format("Morris μ* of {} ({})", s.params[i].label, s.function->name), exact.morris_mu_star[i],
                    m.mu_star[i], e, tol, "linear model: every elementary effect is exactly c_i (high − low); round-off only",
                    e <= tol, "");
          add_check(fmt::format("Morris σ of {} ({})", s.params[i].label, s.function->name), 0.0, m.sigma[i],
                    std::abs(m.sigma[i]), tol, "linear model: all elementary effects equal, σ = 0; round-off only",
                    std::abs(m.sigma[i]) <= tol, "");
        }
      }
      figures.push_back({{"id", fmt::format("morris_{}", o)},
                         {"title", fmt::format("Morris screening of {}: μ* against σ ({} trajectories, {} levels)", s.outputs[o], s.trajectories, s.levels)},
                         {"xlabel", fmt::format("μ* [{} per unit range]", s.outputs[o])}, {"ylabel", fmt::format("σ [{} per unit range]", s.outputs[o])},
                         {"logx", false}, {"logy", false}, {"curves", curves}, {"labels", labels}});
    }
    tables.push_back({{"title", fmt::format("Morris elementary effects (unit coordinates: per full range; {} trajectories, {} levels, Δ = {:.4g})",
                                            s.trajectories, s.levels, sens::morris_delta(s.levels))},
                      {"columns", {"output", "parameter", "μ*", "μ", "σ", "effects", "exact μ*"}},
                      {"rows", rows}});
  }

  std::vector<sens::Transform> sobol_transforms = {sens::Transform::none};
  sobol_transforms.insert(sobol_transforms.end(), s.transforms.begin(), s.transforms.end());
  if (s.sobol) for (const sens::Transform transform : sobol_transforms) {
    // The exact values of the indices of the (transformed) output, where known.
    sens::ExactIndices exact_sobol = exact;
    if (s.function && transform == sens::Transform::log) exact_sobol = sens::exact_indices_of_log(*s.function);
    if (s.function && transform == sens::Transform::rank) exact_sobol = {};
    // What names a check, figure or table of a transform: "" for the output itself.
    const std::string tsuffix = transform == sens::Transform::none ? "" : ", " + sens::transformed_label(transform, "y");
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t o = 0; o < no; ++o) {
      std::vector<double> fa(n), fb(n);
      std::vector<std::vector<double>> fab(d, std::vector<double>(n));
      for (std::size_t j = 0; j < n; ++j) {
        fa[j] = runs[sobol_begin + j].outputs[o];
        fb[j] = runs[sobol_begin + n + j].outputs[o];
        for (std::size_t i = 0; i < d; ++i) fab[i][j] = runs[sobol_begin + (2 + i) * n + j].outputs[o];
      }
      sens::apply_transform(transform, fa, fb, fab);
      const std::string yname = sens::transformed_label(transform, s.outputs[o]);
      const sens::SobolIndices si = sens::sobol_indices(fa, fb, fab, s.resamples, s.confidence);
      // Test functions: the bootstrap interval's width against the central limit theorem for N rows,
      // 2 z σ_∞ / √N, σ_∞ from 2^16 rows of the exact function (sensitivity_estimators.hpp).
      if (s.function && s.resamples >= 100) {
        const std::size_t big = std::size_t{1} << 16;
        const sens::SaltelliDesign des = sens::saltelli_design(big, d);
        auto f = [&](const std::vector<double>& u) {
          std::vector<double> x;
          for (std::size_t i = 0; i < d; ++i) x.push_back(sens::value_at(s.params[i], u[i]));
          return sens::evaluate(*s.function, x);
        };
        std::vector<double> ga(big), gb(big);
        std::vector<std::vector<double>> gab(d, std::vector<double>(big));
        for (std::size_t j = 0; j < big; ++j) {
          ga[j] = f(des.a[j]);
          gb[j] = f(des.b[j]);
          for (std::size_t i = 0; i < d; ++i) gab[i][j] = f(des.ab[i][j]);
        }
        sens::apply_transform(transform, ga, gb, gab);
        const sens::SobolAsymptoticSd sd = sens::sobol_asymptotic_sd(ga, gb, gab);
        const double z = sens::normal_quantile(0.5 * (1.0 + s.confidence));
        // The bootstrap's own noise: a percentile of B resamples has standard error √(p(1−p)/B)/φ(z) in
        // units of the spread (p = (1 − c)/2), so the width 2 z σ has relative error √2 × that / (2 z);
        // 3 of those, plus 10 % for what the CLT leaves out at finite N (the ratio estimator's skew).
        const double p_end = 0.5 * (1.0 - s.confidence);
        const double phi_z = std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi);
        const double quantile_noise = std::sqrt(2.0) * std::sqrt(p_end * (1.0 - p_end) / static_cast<double>(s.resamples)) / phi_z / (2.0 * z);
        const double band = 3.0 * quantile_noise + 0.1;
        for (std::size_t i = 0; i < d; ++i)
          for (const auto& [kind, iv, sig] : {std::tuple{"S", si.first[i], sd.first[i]}, std::tuple{"ST", si.total[i], sd.total[i]},
                                              std::tuple{"S(Janon)", si.first_janon[i], sd.first_janon[i]}}) {
            if (!(sig > 0.0)) continue;  // an exact estimator (σ_∞ = 0): no width to compare
            const double clt = 2.0 * z * sig / std::sqrt(static_cast<double>(si.rows_used));
            const double w = iv.high - iv.low;
            add_check(fmt::format("width of the {}_{} interval of {} ({}, N = {}{})", kind, i + 1, s.params[i].label, s.function->name, n, tsuffix),
                      clt, w, std::abs(w - clt) / clt, band,
                      fmt::format("CLT: a {:.0f} % interval over N i.i.d. rows is 2 z σ_∞/√N wide (z = {:.4f}, σ_∞ from 2^16 rows); the "
                                  "bootstrap width within 3 × {:.1f} % (its {} resamples' quantile noise) + 10 % (finite-N skew) of it",
                                  100.0 * s.confidence, z, 100.0 * quantile_noise, s.resamples),
                      std::abs(w - clt) <= band * clt, fmt::format("σ_∞ = {}, relative difference", num(sig)));
            checks.back()["error_kind"] = "rel";
          }
      }
      nlohmann::json curves = nlohmann::json::array();
      std::vector<double> xi, xt, ys, yt;
      for (std::size_t i = 0; i < d; ++i) {
        const double x = static_cast<double>(i + 1);
        xi.push_back(x - 0.11);
        xt.push_back(x + 0.11);
        ys.push_back(si.first[i].estimate);
        yt.push_back(si.total[i].estimate);
        rows.push_back({yname, s.params[i].label, num(si.first[i].estimate),
                        fmt::format("[{}, {}]", num(si.first[i].low), num(si.first[i].high)), num(si.total[i].estimate),
                        fmt::format("[{}, {}]", num(si.total[i].low), num(si.total[i].high)),
                        exact_sobol.first.empty() ? "" : num(exact_sobol.first[i]), exact_sobol.total.empty() ? "" : num(exact_sobol.total[i]),
                        num(si.first_janon[i].estimate), fmt::format("[{}, {}]", num(si.first_janon[i].low), num(si.first_janon[i].high))});
        for (const auto& [kind, iv, ex] : {std::tuple{"S", si.first[i], exact_sobol.first}, std::tuple{"ST", si.total[i], exact_sobol.total},
                                           std::tuple{"S_janon", si.first_janon[i], exact_sobol.first}}) {
          idx_csv << "sobol," << yname << ",\"" << s.params[i].label << "\"," << kind << ","
                  << fmt::format("{:.17g},{:.17g},{:.17g},", iv.estimate, iv.low, iv.high)
                  << (ex.empty() ? std::string() : fmt::format("{:.17g}", ex[i])) << "\n";
          if (!ex.empty()) {
            const double e = std::abs(iv.estimate - ex[i]);
            const double tol = ex[i] < iv.estimate ? iv.estimate - iv.low : iv.high - iv.estimate;
            add_check(fmt::format("{}_{} of {} ({}, N = {}{})", kind, i + 1, s.params[i].label, s.function->name, n, tsuffix), ex[i],
                      iv.estimate, e, tol,
                      fmt::format("the {:.0f} % bootstrap interval ({} resamples of the N rows) must contain the exact value",
                                  100.0 * s.confidence, s.resamples),
                      ex[i] >= iv.low && ex[i] <= iv.high, fmt::format("interval [{}, {}]", num(iv.low), num(iv.high)));
          }
        }
      }
      // Bars: S and S_T side by side per parameter, each with its bootstrap interval.
      std::vector<double> s_lo, s_hi, t_lo, t_hi;
      nlohmann::json xticks = nlohmann::json::array();
      for (std::size_t i = 0; i < d; ++i) {
        s_lo.push_back(si.first[i].low);
        s_hi.push_back(si.first[i].high);
        t_lo.push_back(si.total[i].low);
        t_hi.push_back(si.total[i].high);
        xticks.push_back({static_cast<double>(i + 1), s.params[i].label});
      }
      auto jv = [](const std::vector<double>& v) {
        nlohmann::json a = nlohmann::json::array();
        for (double x : v) a.push_back(jnum(x));
        return a;
      };
      curves.push_back({{"label", "first order S (Saltelli 2010)"}, {"x", xi}, {"y", jv(ys)}, {"style", "boxes"}, {"width", 0.2}});
      {  // Janon's first order as points with their interval between the bars
        std::vector<double> xj, yj, jlo, jhi;
        for (std::size_t i = 0; i < d; ++i) {
          xj.push_back(static_cast<double>(i + 1));
          yj.push_back(si.first_janon[i].estimate);
          jlo.push_back(si.first_janon[i].low);
          jhi.push_back(si.first_janon[i].high);
        }
        curves.push_back({{"label", fmt::format("first order S (Janon 2014), {:.0f} % bootstrap interval", 100.0 * s.confidence)},
                          {"x", xj}, {"y", jv(yj)}, {"ylow", jv(jlo)}, {"yhigh", jv(jhi)}, {"style", "errorbars"}, {"colour", "#b03000"}});
      }
      curves.push_back({{"label", "total S_T (Jansen)"}, {"x", xt}, {"y", jv(yt)}, {"style", "boxes"}, {"width", 0.2}});
      curves.push_back({{"label", fmt::format("S, {:.0f} % bootstrap interval", 100.0 * s.confidence)}, {"x", xi}, {"y", jv(ys)},
                        {"ylow", jv(s_lo)}, {"yhigh", jv(s_hi)}, {"style", "errorbars"}, {"colour", "#000000"}});
      curves.push_back({{"label", fmt::format("S_T, {:.0f} % bootstrap interval", 100.0 * s.confidence)}, {"x", xt}, {"y", jv(yt)},
                        {"ylow", jv(t_lo)}, {"yhigh", jv(t_hi)}, {"style", "errorbars"}, {"colour", "#555555"}});
      if (!exact_sobol.first.empty()) {
        std::vector<double> xe, ye;
        for (std::size_t i = 0; i < d; ++i) {
          xe.insert(xe.end(), {xi[i], xt[i]});
          ye.insert(ye.end(), {exact_sobol.first[i], exact_sobol.total[i]});
        }
        curves.push_back({{"label", "exact"}, {"x", xe}, {"y", ye}, {"style", "points"}});
      }
      figures.push_back({{"id", transform == sens::Transform::none ? fmt::format("sobol_{}", o)
                                                                    : fmt::format("sobol_{}_{}", sens::transform_name(transform), o)},
                         {"title", fmt::format("Sobol' indices of {} (N = {}, {} rows used)", yname, n, si.rows_used)},
                         {"xlabel", "parameter"}, {"ylabel", "index"}, {"logx", false}, {"logy", false}, {"curves", curves},
                         {"xticks", xticks}, {"xrange", {0.5, static_cast<double>(d) + 0.5}}});
    }
    tables.push_back({{"title", fmt::format("Sobol' indices (Saltelli sampling, N = {}, {} runs; {} % bootstrap intervals){}", n, n * (d + 2),
                                            100.0 * s.confidence,
                                            transform == sens::Transform::none ? "" : fmt::format(
                                                ": indices of the TRANSFORMED output {} (declared transforms = [\"{}\"]), not of the output itself",
                                                sens::transformed_label(transform, "y"), sens::transform_name(transform)))},
                      {"columns", {"output", "parameter", "S", "interval", "S_T", "interval", "exact S", "exact S_T", "S (Janon)", "interval"}},
                      {"rows", rows}});
    // Function studies: the error over doubling sample sizes, at the quasi-random rate.
    if (s.function && !s.convergence.empty() && !exact_sobol.first.empty()) {
      std::vector<double> h, err, err_janon;
      nlohmann::json crow = nlohmann::json::array();
      for (std::size_t nn : s.convergence) {
        const sens::SaltelliDesign des = sens::saltelli_design(nn, d);
        auto f = [&](const std::vector<double>& u) {
          Run r = make_run("", u);
          runner.run_function(r);
          return r.outputs[0];
        };
        std::vector<double> fa, fb;
        std::vector<std::vector<double>> fab(d);
        for (std::size_t j = 0; j < nn; ++j) {
          fa.push_back(f(des.a[j]));
          fb.push_back(f(des.b[j]));
          for (std::size_t i = 0; i < d; ++i) fab[i].push_back(f(des.ab[i][j]));
        }
        sens::apply_transform(transform, fa, fb, fab);
        const sens::SobolIndices si = sens::sobol_indices(fa, fb, fab, 0);
        double e = 0.0, ej = 0.0;
        for (std::size_t i = 0; i < d; ++i) {
          e = std::max({e, std::abs(si.first[i].estimate - exact_sobol.first[i]), std::abs(si.total[i].estimate - exact_sobol.total[i])});
          ej = std::max(ej, std::abs(si.first_janon[i].estimate - exact_sobol.first[i]));
        }
        h.push_back(1.0 / static_cast<double>(nn));
        err.push_back(e);
        err_janon.push_back(ej);
        crow.push_back({std::to_string(nn), num(e), num(ej)});
      }
      ConvergenceOptions co;
      co.reference = 0.0;
      co.expected_order = s.expected_order;
      const Series ser = analyse_convergence(h, err, co, fmt::format("max |index − exact| ({}{})", s.function->name, tsuffix), "1/N");
      series.push_back(to_json(ser));
      const double p = ser.fitted_order.value_or(std::nan(""));
      if (s.expected_order)
        add_check(fmt::format("order of the index error in N ({}, N = {} … {}{})", s.function->name, s.convergence.front(), s.convergence.back(), tsuffix),
                  0.0, err.back(), err.back(), NAN,
                  fmt::format("Sobol' points: error ~ N^-1 up to log factors (Monte Carlo: N^-1/2); least-squares order must be at least {} − {}",
                              *s.expected_order, s.order_band),
                  std::isfinite(p) && p >= *s.expected_order - s.order_band, "one-sided: faster than promised passes", p);
      const Series serj = analyse_convergence(h, err_janon, co, fmt::format("max |S (Janon) − exact| ({}{})", s.function->name, tsuffix), "1/N");
      series.push_back(to_json(serj));
      const double pj = serj.fitted_order.value_or(std::nan(""));
      if (s.expected_order)
        add_check(fmt::format("order of the Janon first-order error in N ({}, N = {} … {}{})", s.function->name, s.convergence.front(), s.convergence.back(), tsuffix),
                  0.0, err_janon.back(), err_janon.back(), NAN,
                  fmt::format("Sobol' points: error ~ N^-1 up to log factors (Monte Carlo: N^-1/2); least-squares order must be at least {} − {}",
                              *s.expected_order, s.order_band),
                  std::isfinite(pj) && pj >= *s.expected_order - s.order_band, "one-sided: faster than promised passes", pj);
      tables.push_back({{"title", "Largest index error over doubling sample sizes" + tsuffix},
                        {"columns", {"N", "max |S − exact|, |S_T − exact|", "max |S (Janon) − exact|"}}, {"rows", crow}});
    }
  }
  dem::write_file_atomic(out / "indices.csv", idx_csv.str(), false);

  if (failed > s.max_failed) passed = false;
  checks.push_back({{"quantity", "failed runs (blow-up, refused by the guard)"}, {"reference", 0}, {"dem", failed},
                    {"error", failed}, {"error_kind", "abs"}, {"tolerance", s.max_failed},
                    {"tolerance_reason", "the ranges are meant to stay inside the stable, accepted region (max_failed_runs)"},
                    {"observed_order", nullptr}, {"expected_order", nullptr}, {"order_band", nullptr},
                    {"passed", failed <= s.max_failed}, {"note", ""}});
  if (run_rows.size() <= 300) {
    nlohmann::json cols = {"run", "method"};
    for (const auto& p : s.params) cols.push_back(p.label);
    if (derived_dt) cols.push_back("Δt (guard × fraction)");
    for (const auto& o : s.outputs) cols.push_back(o);
    cols.push_back("status");
    tables.push_back({{"title", "All runs (runs.csv)"}, {"columns", cols}, {"rows", run_rows}});
  } else {
    tables.push_back({{"title", "All runs"}, {"preformatted", fmt::format("{} runs, {} failed: see runs.csv", run_rows.size(), failed)}});
  }

  nlohmann::json setup = s.setup;
  std::string methods;
  for (const auto& [on, m] : {std::pair{s.oat, "one-at-a-time"}, std::pair{s.morris, "Morris"}, std::pair{s.sobol, "Sobol'"}})
    if (on) methods += (methods.empty() ? "" : ", ") + std::string(m);
  setup["methods"] = methods;
  setup["runs"] = runs.size();
  setup["failed runs"] = failed;
  for (const auto& p : s.params)
    setup["range of " + p.label] = fmt::format("{} = {} … {} ({})", p.path.empty() ? p.label : p.path, num(p.low), num(p.high),
                                               p.log_uniform ? "log-uniform" : p.integer ? "integers, uniform" : "uniform");
  if (s.function) setup["function"] = s.function->name;
  if (!s.replicates.empty()) {
    std::string list;
    for (const auto& sets : s.replicates) {
      std::string one;
      for (const auto& x : sets) one += (one.empty() ? "" : ", ") + x;
      list += (list.empty() ? "" : "; ") + one;
    }
    setup["replicates"] = fmt::format("each run above is the mean of {} replicates ({} DEM runs in all): {}", s.replicates.size(),
                                      runs.size() * s.replicates.size(), list);
  }
  if (derived_dt)
    setup["time step"] = fmt::format("Δt = {:.4g} × the time-step guard's limit of each run{}", runner.dt_fraction,
                                     s.dt_fraction_base ? " (the base case's own ratio)" : "");
  nlohmann::json prov = dem::provenance();
  prov["overrides"] = s.set;
  prov["runs_reused"] = runner.reused.load();
  prov["runs_run"] = runner.ran.load();
  prov["runs_duplicate"] = runner.duplicates;  // same overrides as another run of the study: its result shared
  std::string params;
  for (const auto& p : s.params) params += (params.empty() ? "" : ", ") + p.label;
  nlohmann::json result = {
      {"study", s.name}, {"title", s.title}, {"requirement", s.requirement}, {"kind", "sensitivity"},
      {"case", s.function ? "test function " + s.function->name : s.case_path}, {"parameter", params},
      {"reference", s.function ? "exact indices of the test function (sensitivity_functions.hpp)" : "none: a sensitivity study"},
      {"setup", setup}, {"provenance", prov}, {"passed", passed}, {"checks", checks}, {"series", series},
      {"figures", figures}, {"tables", tables}};
  result["provenance"]["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  result["provenance"]["command"] = fmt::format("dem2d sweep {} --out {} --jobs {}{}", file.string(), out.string(), opt.jobs,
                                                opt.use_cache ? "" : " --fresh");
  // The study's README (purpose, findings, known limits) travels with the result: the report shows it.
  if (const fs::path readme = fs::absolute(file).parent_path() / "README.md"; fs::exists(readme))
    result["readme"] = dem::read_file(readme);
  dem::write_file_atomic(out / "result.json", result.dump(2) + "\n");

  if (opt.print) {
    fmt::print("sensitivity {}: {} ({} runs, {} failed, {} reused)\n", s.name, s.title, runs.size(), failed, runner.reused.load());
    for (const auto& t : tables) {
      if (!t.contains("columns") || t["title"].get<std::string>().rfind("All runs", 0) == 0) continue;
      fmt::print("  {}\n", t["title"].get<std::string>());
      std::string line;
      for (const auto& c : t["columns"]) line += fmt::format("{:>16} ", c.get<std::string>());
      fmt::print("    {}\n", line);
      for (const auto& r : t["rows"]) {
        line.clear();
        for (const auto& c : r) line += fmt::format("{:>16} ", c.is_string() ? c.get<std::string>() : c.dump());
        fmt::print("    {}\n", line);
      }
    }
    for (const auto& c : checks)
      if (!c["passed"].get<bool>()) fmt::print("  FAIL: {} (value {}, reference {})\n", c["quantity"].get<std::string>(), c["dem"].dump(), c["reference"].dump());
    fmt::print("  => {}  ({})\n", passed ? "PASSED" : "FAILED", (out / "result.json").string());
  }
  return {passed, result};
}

}  // namespace ver
