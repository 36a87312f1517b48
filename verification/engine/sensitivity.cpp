#include "engine/sensitivity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include <unistd.h>
#include <toml++/toml.h>

#include "dem/cases/case_file.hpp"
#include "dem/cases/case_reader.hpp"
#include "dem/cases/units.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"
#include "dem/run/owned_files.hpp"
#include "engine/progress.hpp"
#include "engine/run_cache.hpp"
#include "engine/sensitivity_study.hpp"
#include "engine/study_file.hpp"

namespace fs = std::filesystem;

namespace ver {

namespace {

using sens::Parameter;
using sens::Sens;

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
  s.setup = read_setup(r);
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


}  // namespace

namespace sens {

std::string num(double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : std::string("—"); }
nlohmann::json jnum(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

void Analysis::add_check(const std::string& q, double ref, double val, double err, double tol, const std::string& reason,
                         bool ok, const std::string& note, std::optional<double> order) {
  passed = passed && ok;
  checks.push_back({{"quantity", q}, {"reference", jnum(ref)}, {"dem", jnum(val)}, {"error", jnum(err)},
                    {"error_kind", "abs"}, {"tolerance", jnum(tol)}, {"tolerance_reason", reason},
                    {"observed_order", order ? nlohmann::json(*order) : nlohmann::json(nullptr)},
                    {"expected_order", order && s.expected_order ? nlohmann::json(*s.expected_order) : nlohmann::json(nullptr)},
                    {"order_band", order && s.expected_order ? nlohmann::json(s.order_band) : nlohmann::json(nullptr)},
                    {"passed", ok}, {"note", note}});
}

}  // namespace sens

namespace {

using sens::num;

/// The exact indices of a test function (none for a case).
sens::ExactIndices exact_of(const Sens& s) {
  sens::ExactIndices exact;
  if (s.function) {
    std::vector<double> lo, hi;
    for (const auto& p : s.params) {
      lo.push_back(p.low);
      hi.push_back(p.high);
    }
    exact = sens::exact_indices(*s.function, lo, hi);
  }
  return exact;
}

/// result.json's setup: the study's own entries, the methods, the runs, each range, replicates and Δt.
nlohmann::json setup_of(const Sens& s, std::size_t runs, int failed, double dt_fraction) {
  nlohmann::json setup = s.setup;
  std::string methods;
  for (const auto& [on, m] : {std::pair{s.oat, "one-at-a-time"}, std::pair{s.morris, "Morris"}, std::pair{s.sobol, "Sobol'"}})
    if (on) methods += (methods.empty() ? "" : ", ") + std::string(m);
  setup["methods"] = methods;
  setup["runs"] = runs;
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
                                      runs * s.replicates.size(), list);
  }
  if (dt_fraction > 0.0)
    setup["time step"] = fmt::format("Δt = {:.4g} × the time-step guard's limit of each run{}", dt_fraction,
                                     s.dt_fraction_base ? " (the base case's own ratio)" : "");
  return setup;
}

/// The tables of indices and the failed checks on the terminal.
void print_summary(const Sens& s, const sens::Analysis& an, std::size_t runs, int failed, int reused, const fs::path& result_file) {
  fmt::print("sensitivity {}: {} ({} runs, {} failed, {} reused)\n", s.name, s.title, runs, failed, reused);
  for (const auto& t : an.tables) {
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
  for (const auto& c : an.checks)
    if (!c["passed"].get<bool>()) fmt::print("  FAIL: {} (value {}, reference {})\n", c["quantity"].get<std::string>(), c["dem"].dump(), c["reference"].dump());
  fmt::print("  => {}  ({})\n", an.passed ? "PASSED" : "FAILED", result_file.string());
}

}  // namespace

void check_sensitivity_file(const fs::path& file) { sens::check_ranges(read_sens(file)); }

StudyResult run_sensitivity(const fs::path& file, const StudyOptions& opt) {
  const auto started = std::chrono::steady_clock::now();
  const Sens s = read_sens(file);
  const fs::path out = open_study_folder(s.name, opt);  // running.json until the runs are done (run_cache.hpp)
  Progress progress("sweep " + s.name, stderr, opt.print && ::isatty(::fileno(stderr)), opt.verbose);
  const ProgressScope shown(&progress);
  sens::Runner runner{s, out / "cache"};
  const sens::Plan plan = marking_failure(out, s.name, [&] {
    if (!opt.use_cache) dem::remove_owned_folder(runner.cache_dir, dem::OwnedFolder::study_cache, "--fresh");
    fs::create_directories(runner.cache_dir);
    sens::check_ranges(s);
    runner.dt_fraction = sens::dt_fraction_of(s);
    sens::Plan p = sens::plan_runs(s);
    runner.run_samples(p.runs, opt.jobs);
    return p;
  });
  progress.close();
  fs::remove(out / "running.json");
  const bool derived_dt = runner.dt_fraction > 0.0;
  const sens::RunTable run_table = sens::write_runs_csv(s, plan.runs, derived_dt, out / "runs.csv");

  sens::Analysis an{s};
  an.idx_csv << "method,output,parameter,index,estimate,low,high,exact\n";
  const sens::ExactIndices exact = exact_of(s);
  if (s.oat) sens::analyse_oat(plan, an);
  if (s.morris) sens::analyse_morris(plan, exact, an);
  if (s.sobol) sens::analyse_sobol(plan, exact, an);
  dem::write_file_atomic(out / "indices.csv", an.idx_csv.str(), false);
  sens::report_runs(run_table, derived_dt, an);

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
      {"setup", setup_of(s, plan.runs.size(), run_table.failed, runner.dt_fraction)}, {"provenance", prov}, {"passed", an.passed},
      {"checks", an.checks}, {"series", an.series}, {"figures", an.figures}, {"tables", an.tables}};
  result["provenance"]["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  result["provenance"]["command"] = fmt::format("dem2d sweep {} --out {} --jobs {}{}", file.string(), out.string(), opt.jobs,
                                                opt.use_cache ? "" : " --fresh");
  // The study's README (purpose, findings, known limits) travels with the result: the report shows it.
  if (const fs::path readme = fs::absolute(file).parent_path() / "README.md"; fs::exists(readme))
    result["readme"] = dem::read_file(readme);
  dem::write_file_atomic(out / "result.json", result.dump(2) + "\n");

  if (opt.print) print_summary(s, an, plan.runs.size(), run_table.failed, runner.reused.load(), out / "result.json");
  return {an.passed, result};
}

}  // namespace ver
