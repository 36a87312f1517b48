#include "engine/sensitivity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

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
#include "engine/sensitivity_names.hpp"
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
  if (s.function && r.has("replicates")) {  // a test function: how many evaluations per sample (each its own noise)
    const std::size_t count = static_cast<std::size_t>(r.integer("replicates", 2, 1000, 2));
    s.replicates.assign(count, {});
    if (!r.has("noise_sd")) r.fail("replicates", "a test function has no noise unless noise_sd is given");
  } else if (const toml::node* rn = r.node("replicates")) {
    const toml::array* ra = rn->as_array();
    if (!ra || ra->size() < 2)
      r.fail("replicates", "expected at least 2 lists of overrides, e.g. [[\"numerics.dt=5e-5 s\"], [\"numerics.dt=4.9e-5 s\"]]");
    for (const auto& e : *ra) s.replicates.push_back(overrides_of(r, e, "replicates"));
  }
  if (r.has("noise_sd") || r.has("noise_seed")) {
    if (!s.function) r.fail(r.has("noise_sd") ? "noise_sd" : "noise_seed", "only for a test function (a case has its own noise)");
    s.noise_sd = r.number_in("noise_sd", 0.0, 1e300, 0.0, false);
    s.noise_seed = static_cast<std::uint64_t>(r.integer("noise_seed", 1, std::numeric_limits<std::int64_t>::max(), 1));
  }
  s.setup = read_setup(r);
  r.finish();
}

/// The value of a parameter bound as written, checked against the case key it sets: the case reader
/// reads the case with `path = <value as written>` and refuses a wrong unit ("1 m" for a damping ratio).
void check_against_case(const Sens& s, const TableReader& r, const Parameter& p, const char* key, const toml::node* at = nullptr) {
  if (s.function || p.path.empty()) return;
  const toml::node& n = at ? *at : *r.node(key);
  const std::string written = n.is_string() ? *n.value<std::string>() : fmt::format("{:.17g}", *n.value<double>());
  std::vector<std::string> sets = s.set;
  sets.push_back(p.path + "=" + written);
  try {
    (void)dem::read_case(s.case_file, sets);
  } catch (const dem::CaseError& e) {
    r.fail(key, fmt::format("\"{}\" cannot set {}: {}", written, p.path, e.what()));
  }
}

/// The distribution of a parameter and the keys it takes, each a quantity in one kind of unit:
///   uniform, log-uniform: low, high;  normal: mean, sd;  truncated-normal: mean, sd, low, high;
///   triangular: low, mode, high;  log-normal: median, sigma_ln (the sd of ln x, a plain number);
///   levels: levels = [x_1, …, x_k] (k >= 2, increasing).
void read_distribution(const Sens& s, const TableReader& r, const toml::node& n, Parameter& p) {
  using sens::Distribution;
  const std::vector<std::string> names = {"uniform", "log-uniform", "normal", "truncated-normal", "triangular", "log-normal", "levels"};
  const std::string name = r.choice("distribution", names, "uniform");
  p.distribution = static_cast<Distribution>(std::find(names.begin(), names.end(), name) - names.begin());
  p.log_uniform = p.distribution == Distribution::log_uniform;
  const std::vector<const char*> keys =
      p.distribution == Distribution::normal ? std::vector<const char*>{"mean", "sd"}
      : p.distribution == Distribution::truncated_normal ? std::vector<const char*>{"mean", "sd", "low", "high"}
      : p.distribution == Distribution::triangular ? std::vector<const char*>{"low", "mode", "high"}
      : p.distribution == Distribution::log_normal ? std::vector<const char*>{"median"}
      : p.distribution == Distribution::levels ? std::vector<const char*>{}
      : std::vector<const char*>{"low", "high"};
  for (const char* k : {"low", "high", "mean", "sd", "mode", "median", "sigma_ln", "levels"})  // a key of another distribution
    if (r.has(k) && std::find_if(keys.begin(), keys.end(), [&](const char* x) { return std::string(x) == k; }) == keys.end() &&
        !(p.distribution == Distribution::log_normal && std::string(k) == "sigma_ln") && !(p.distribution == Distribution::levels && std::string(k) == "levels"))
      r.fail(k, fmt::format("a {} distribution does not take {}", name, k));
  std::optional<dem::Quantity> first;
  std::string first_key;
  std::map<std::string, double> v;
  std::vector<std::pair<const char*, const toml::node*>> on_case;  // tried on the case key once all units agree
  auto quantity = [&](const char* key, const toml::node& at) {
    r.mark(key);
    const dem::Quantity q = r.any_quantity_of(at, key);
    if (first && !(q.dim == first->dim))
      r.fail_at(at, key, fmt::format("{} is {}, {} is {}: give all in one kind of unit", first_key, dem::to_string(first->dim), key,
                                     dem::to_string(q.dim)));
    if (!first) first = q, first_key = key;
    if (std::string(key) != "sd") on_case.emplace_back(key, &at);
    return q.value;
  };
  for (const char* k : keys) {
    if (!r.has(k)) r.fail_at(n, k, fmt::format("missing: a {} distribution takes {}", name, fmt::join(keys, ", ")));
    v[k] = quantity(k, *r.node(k));
  }
  if (p.distribution == Distribution::levels) {
    r.mark("levels");
    const toml::node* ln = r.node("levels");
    if (!ln || !ln->as_array() || ln->as_array()->size() < 2) r.fail_at(ln ? *ln : n, "levels", "expected an array of at least 2 values, e.g. [\"1 mm\", \"2 mm\"]");
    for (const auto& x : *ln->as_array()) p.levels.push_back(quantity("levels", x));
    for (std::size_t k = 1; k < p.levels.size(); ++k)
      if (!(p.levels[k] > p.levels[k - 1])) r.fail_at(*ln, "levels", "expected increasing values");
  }
  for (const auto& [key, at] : on_case) check_against_case(s, r, p, key, at);
  p.angle = first && first->dim == dem::dims::angle;
  if (first) p.unit = sens::ascii_unit(dem::to_string(first->dim));
  p.mean = v.count("mean") ? v["mean"] : 0.0;
  p.sd = v.count("sd") ? v["sd"] : 1.0;
  p.mode = v.count("mode") ? v["mode"] : 0.0;
  if (v.count("low")) p.low = v["low"];
  if (v.count("high")) p.high = v["high"];
  if ((p.distribution == Distribution::normal || p.distribution == Distribution::truncated_normal) && !(p.sd > 0.0))
    r.fail("sd", "expected sd > 0");
  if (p.distribution == Distribution::log_normal) {
    if (!(v["median"] > 0.0)) r.fail("median", "expected median > 0");
    p.mean = std::log(v["median"]);
    p.sd = r.number_in("sigma_ln", 0.0, 10.0, 0.0, true);
    if (!r.has("sigma_ln")) r.fail_at(n, "sigma_ln", "missing: a log-normal distribution takes median and sigma_ln (the sd of ln x)");
  }
  if (p.distribution == Distribution::triangular && !(p.mode >= p.low && p.mode <= p.high)) r.fail("mode", "expected low <= mode <= high");
  if (!keys.empty() && std::find(keys.begin(), keys.end(), std::string("low")) != keys.end() &&
      (!(p.high > p.low) || (p.log_uniform && !(p.low > 0.0))))
    r.fail_at(n, "low", fmt::format("\"{}\": need low < high (and low > 0 for log-uniform)", p.label));
  if (p.distribution == Distribution::normal || p.distribution == Distribution::log_normal || p.distribution == Distribution::levels) {
    p.low = sens::value_at(p, 0.0);  // the support's ends as the designs reach them
    p.high = sens::value_at(p, 1.0);
  }
}

Parameter read_parameter(const Sens& s, const TableReader& r, const toml::node& n) {
  Parameter p;
  p.path = r.string("path", "");
  if (p.path.empty() && !s.function) r.fail_at(n, "path", "missing: the --set path, e.g. contact.0.kn");
  if (!p.path.empty() && s.function) r.fail("path", "a test function's inputs have no case path: remove path");
  p.label = r.string("label", p.path.empty() ? fmt::format("x{}", s.params.size() + 1) : p.path);
  p.name = r.string("name", sens::ascii_name(p.label));
  if (p.name.empty() || p.name != sens::ascii_name(p.name))
    r.fail("name", fmt::format("expected an ASCII identifier (letters, digits, _), e.g. \"{}\"", sens::ascii_name(p.name)));
  for (const Parameter& q : s.params)
    if (q.name == p.name) r.fail_at(n, "name", fmt::format("\"{}\" names two parameters; give one of them name = \"...\"", p.name));
  read_distribution(s, r, n, p);
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
  if (p.integer && (p.distribution != sens::Distribution::uniform || p.low != std::floor(p.low) || p.high != std::floor(p.high)))
    r.fail("integer", fmt::format("\"{}\": integer parameters need integer low and high, uniform", p.label));
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
    s.morris_resamples = static_cast<std::size_t>(r.integer("bootstrap", 1, 1'000'000, 1000));
    s.morris_confidence = r.number_in("confidence", 0.0, 1.0, 0.95, true, true);
    r.finish();
  }
  if (const toml::table* t = top.table("sobol")) {
    TableReader r(*t, "sobol", file, kHelp);
    s.samples = static_cast<std::size_t>(r.integer("samples", 1, kMaxSize, 256));
    s.resamples = static_cast<std::size_t>(r.integer("bootstrap", 1, 1'000'000, 1000));
    s.confidence = r.number_in("confidence", 0.0, 1.0, 0.95, true, true);
    s.sobol_seed = static_cast<std::uint64_t>(r.integer("seed", 1, std::numeric_limits<std::int64_t>::max(), 1));
    s.second_order = r.boolean("second_order", false);
    if (r.has("second_order_tolerance")) {
      if (!s.second_order) r.fail("second_order_tolerance", "needs second_order = true");
      if (!s.function) r.fail("second_order_tolerance", "only for a test function (its exact S_ij are the reference)");
      s.second_order_tolerance = r.number_in("second_order_tolerance", 0.0, 1.0, 0.05, false, true);
      s.second_order_reason = r.string("second_order_reason");
    } else if (r.has("second_order_reason")) {
      r.fail("second_order_reason", "belongs to second_order_tolerance");
    }
    s.delta = r.boolean("delta", false);
    if (r.has("delta_bootstrap")) {
      if (!s.delta) r.fail("delta_bootstrap", "needs delta = true");
      s.delta_resamples = static_cast<std::size_t>(r.integer("delta_bootstrap", 1, 100000, 100));
    }
    if (r.has("delta_tolerance")) {
      if (!s.delta || !s.function || s.function->name != "ishigami")
        r.fail("delta_tolerance", "only with delta = true for the Ishigami function (its reference δ is computed)");
      s.delta_tolerance = r.number_in("delta_tolerance", 0.0, 1.0, 0.05, false, true);
      s.delta_reason = r.string("delta_reason");
      if (s.delta_reason.empty()) r.fail("delta_reason", "missing: one line saying why this tolerance");
    } else if (r.has("delta_reason")) {
      r.fail("delta_reason", "belongs to delta_tolerance");
    }
    if (r.has("tolerance")) {
      if (!s.function) r.fail("tolerance", "only for a test function (its exact indices are the reference)");
      s.index_tolerance = r.number_in("tolerance", 0.0, 1.0, 0.05, false, true);
      s.index_tolerance_reason = r.string("tolerance_reason");
      if (s.index_tolerance_reason.empty()) r.fail("tolerance_reason", "missing: one line saying why this tolerance");
    } else if (r.has("tolerance_reason")) {
      r.fail("tolerance_reason", "belongs to tolerance");
    }
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
  if (s.function && s.function->name != "linear")  // exact indices known for uniform inputs only
    for (const Parameter& p : s.params)
      if (p.distribution != sens::Distribution::uniform)
        fail_at(s, pn, "parameter", fmt::format("\"{}\": the exact indices of {} are for uniform inputs; other distributions with the linear function only",
                                                p.label, s.function->name));
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
    // Inputs not uniform (linear only, cross_check): Var x_i = ∫₀¹ (Q(u) − mean)² du by the midpoint
    // rule on 2^18 cells (the quantile functions are tested against closed forms in the unit tests).
    std::vector<double> variances;
    std::vector<bool> linear_inputs;  // x = low + u (high − low): Morris effects exact (sensitivity_functions.hpp)
    for (const auto& p : s.params) linear_inputs.push_back(p.distribution == sens::Distribution::uniform && !p.integer);
    const bool uniform = std::all_of(linear_inputs.begin(), linear_inputs.end(), [](bool b) { return b; });
    if (!uniform)
      for (const auto& p : s.params) {
        constexpr std::size_t cells = std::size_t{1} << 18;
        double m = 0.0, m2 = 0.0;
        for (std::size_t k = 0; k < cells; ++k) {
          const double x = sens::value_at(p, (static_cast<double>(k) + 0.5) / static_cast<double>(cells));
          m += x / cells;
          m2 += x * x / cells;
        }
        variances.push_back(m2 - m * m);
      }
    exact = sens::exact_indices(*s.function, lo, hi, variances, linear_inputs);
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
                                               p.integer ? "integers, uniform" : sens::distribution_name(p.distribution));
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

namespace {

/// How the study's runs came about (result.json's provenance).
struct RunStats {
  int reused = 0, ran = 0, duplicates = 0;
  double dt_fraction = 0.0;
  std::string command;
};

/// indices.csv with the ASCII `name` column beside `parameter` (a pair "a:b" → "a_name:b_name").
std::string with_names(const Sens& s, const std::string& csv) {
  std::map<std::string, std::string> name;
  for (const auto& p : s.params) name["\"" + p.label + "\""] = p.name;
  name["\"dummy\""] = "dummy";  // the Sobol' noise floor (sensitivity_sobol.cpp)
  name["\"run-to-run noise\""] = "noise";  // the replicates' noise split (sensitivity_noise.cpp)
  name["\"ranking\""] = "ranking";  // the ranking's stability against N (sensitivity_sobol_subsets.cpp)
  for (const auto& p : s.params)
    for (const auto& q : s.params) name["\"" + p.label + ":" + q.label + "\""] = p.name + ":" + q.name;
  std::istringstream in(csv);
  std::string line, out;
  std::getline(in, line);
  out += "method,output,parameter,name,index,estimate,low,high,exact\n";
  while (std::getline(in, line)) {
    const std::size_t q0 = line.find('"'), q1 = q0 == std::string::npos ? q0 : line.find('"', q0 + 1);
    const std::string label = q1 == std::string::npos ? std::string() : line.substr(q0, q1 - q0 + 1);
    const auto it = name.find(label);
    if (it == name.end()) throw std::logic_error("indices.csv: no ASCII name for " + label);
    out += line.substr(0, q1 + 1) + "," + it->second + line.substr(q1 + 1) + "\n";
  }
  return out;
}

/// The analysis of a planned design whose runs carry their outputs: indices.csv, runs.csv, result.json.
StudyResult analyse_and_write(const Sens& s, const sens::Plan& plan, const fs::path& file, const fs::path& out, const StudyOptions& opt,
                              std::chrono::steady_clock::time_point started, const RunStats& stats) {
  const bool derived_dt = stats.dt_fraction > 0.0;
  const sens::RunTable run_table = sens::write_runs_csv(s, plan.runs, derived_dt, out / "runs.csv");

  sens::Analysis an{s};
  an.idx_csv << "method,output,parameter,index,estimate,low,high,exact\n";
  const sens::ExactIndices exact = exact_of(s);
  if (s.oat) sens::analyse_oat(plan, an);
  if (s.morris) sens::analyse_morris(plan, exact, an);
  if (s.sobol) sens::analyse_sobol(plan, exact, an);
  if (s.sobol && s.delta) sens::analyse_delta(plan, an);
  sens::analyse_noise(plan, exact, an);
  dem::write_file_atomic(out / "indices.csv", with_names(s, an.idx_csv.str()), false);
  sens::report_runs(run_table, derived_dt, an);

  nlohmann::json prov = dem::provenance();
  prov["overrides"] = s.set;
  prov["runs_reused"] = stats.reused;
  prov["runs_run"] = stats.ran;
  prov["runs_duplicate"] = stats.duplicates;  // same overrides as another run of the study: its result shared
  std::string params;
  for (const auto& p : s.params) params += (params.empty() ? "" : ", ") + p.label;
  nlohmann::json result = {
      {"study", s.name}, {"title", s.title}, {"requirement", s.requirement}, {"kind", "sensitivity"},
      {"case", s.function ? "test function " + s.function->name : s.case_path}, {"parameter", params},
      {"reference", s.function ? "exact indices of the test function (sensitivity_functions.hpp)" : "none: a sensitivity study"},
      {"setup", setup_of(s, plan.runs.size(), run_table.failed, stats.dt_fraction)}, {"provenance", prov}, {"passed", an.passed},
      {"checks", an.checks}, {"series", an.series}, {"figures", an.figures}, {"tables", an.tables}};
  result["provenance"]["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  result["provenance"]["command"] = stats.command;
  // The study's README (purpose, findings, known limits) travels with the result: the report shows it.
  if (const fs::path readme = fs::absolute(file).parent_path() / "README.md"; fs::exists(readme))
    result["readme"] = dem::read_file(readme);
  dem::write_file_atomic(out / "result.json", result.dump(2) + "\n");

  if (opt.print) print_summary(s, an, plan.runs.size(), run_table.failed, stats.reused, out / "result.json");
  return {an.passed, result};
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
  const RunStats stats{runner.reused.load(), runner.ran.load(), runner.duplicates, runner.dt_fraction,
                       fmt::format("dem2d sweep {} --out {} --jobs {}{}", file.string(), out.string(), opt.jobs, opt.use_cache ? "" : " --fresh")};
  return analyse_and_write(s, plan, file, out, opt, started, stats);
}

StudyResult analyse_sensitivity(const fs::path& file, const fs::path& outputs_csv, const StudyOptions& opt) {
  const auto started = std::chrono::steady_clock::now();
  const Sens s = read_sens(file);
  if (!s.replicates.empty()) throw dem::CaseError(fmt::format("{}: replicates: analyse reads one output per run; give the replicates' means", file.string()));
  sens::Plan plan = sens::plan_runs(s);
  sens::read_outputs_csv(s, outputs_csv, plan.runs);
  const fs::path out = opt.out_dir.empty() ? fs::path("build/studies") / s.name : opt.out_dir;
  fs::create_directories(out);
  const RunStats stats{0, 0, 0, 0.0, fmt::format("dem2d analyse {} --outputs {} --out {}", file.string(), outputs_csv.string(), out.string())};
  return analyse_and_write(s, plan, file, out, opt, started, stats);
}

void write_sensitivity_design(const fs::path& file, const StudyOptions& opt) {
  const Sens s = read_sens(file);
  if (!s.replicates.empty()) throw dem::CaseError(fmt::format("{}: replicates: --design-only writes one row per run, without replicates", file.string()));
  if (s.dt_fraction || s.dt_fraction_base)
    throw dem::CaseError(fmt::format("{}: dt_fraction: --design-only cannot derive each run's Δt from the guard; give numerics.dt instead", file.string()));
  sens::check_ranges(s);
  const sens::Plan plan = sens::plan_runs(s);
  const fs::path out = opt.out_dir.empty() ? fs::path("build/studies") / s.name : opt.out_dir;
  fs::create_directories(out);
  sens::write_design_csv(s, plan.runs, out / "design.csv");
  if (opt.print)
    fmt::print("sensitivity {}: design of {} runs written to {}\n  run them anywhere, then: dem2d analyse {} --outputs OUTPUTS.csv\n", s.name,
               plan.runs.size(), (out / "design.csv").string(), file.string());
}

}  // namespace ver
