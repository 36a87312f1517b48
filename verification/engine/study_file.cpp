#include "engine/study_file.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "dem/cases/case_file.hpp"
#include "dem/cases/case_reader.hpp"
#include "dem/cases/units.hpp"
#include "dem/run/resolved_case.hpp"
#include "engine/study_wall_profile.hpp"
#include "ref/registry.hpp"

namespace fs = std::filesystem;

namespace ver {

namespace {

constexpr const char* kHelp = "verification/README.md, \"The study file\"";

using dem::TableReader;

/// Every [[name]] table of the file, each through its own reader (finished after `f`).
template <class F>
void each_table(const TableReader& top, const std::string& name, const std::string& file, F&& f) {
  top.mark(name);
  const toml::node* n = top.node(name);
  if (!n) return;
  const toml::array* arr = n->as_array();
  if (!arr) top.fail(name, fmt::format("expected [[{}]] tables", name));
  for (const auto& x : *arr) {
    const toml::table* t = x.as_table();
    if (!t) top.fail_at(x, name, fmt::format("expected [[{}]] tables (a table each), got a value", name));
    TableReader r(*t, name, file, kHelp);
    f(r, x);
    r.finish();
  }
}

/// A plain folder name: the study's results go to build/studies/<name>.
void check_folder_name(const TableReader& r, const std::string& key, const std::string& name) {
  if (name.empty() || name == "." || name == ".." ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") != std::string::npos)
    r.fail(key, fmt::format("expected a plain folder name (letters, digits, '_', '-', '.'), got \"{}\"", name));
}

const ref::SolverInfo* find_solver(const std::string& name) {
  static const std::vector<ref::SolverInfo> all = ref::solvers();
  for (const auto& s : all)
    if (s.name == name) return &s;
  return nullptr;
}

/// Refuses a reference solver name the registry does not know, with the nearest known name.
void check_solver(const TableReader& r, const std::string& key, const std::string& name) {
  if (find_solver(name)) return;
  std::vector<std::string> names;
  for (const auto& s : ref::solvers()) names.push_back(s.name);
  const std::string near = dem::nearest_word(name, names);
  r.fail(key, fmt::format("unknown reference solver \"{}\"{} (`dem2d study --help` does not list them; see "
                          "reference/README.md)", name, near.empty() ? "" : fmt::format("; did you mean \"{}\"?", near)));
}

void read_header(Study& s, const TableReader& top, const std::string& file) {
  const toml::table* st = top.table("study");
  if (!st) top.fail("study", "missing [study] table");
  TableReader r(*st, "study", file, kHelp);
  s.name = r.string("name", fs::absolute(s.file).parent_path().filename().string());
  check_folder_name(r, "name", s.name);
  s.title = r.string("title", s.name);
  s.requirement = r.string("requirement", "");
  s.reference_text = r.string("reference", "");
  s.case_path = r.string("case");
  s.case_file = (fs::absolute(s.file).parent_path() / s.case_path).lexically_normal();
  if (std::error_code ec; !fs::is_regular_file(s.case_file, ec)) {
    const toml::node& n = *st->get("case");
    throw dem::CaseError(fmt::format("file not found: {} (from {})", s.case_file.string(), dem::where(n, file)));
  }
  const std::string kind = r.choice("kind", {"refinement", "single", "stability", "mode_map"}, "single");
  s.kind = kind == "refinement" ? Kind::refinement : kind == "stability" ? Kind::stability
           : kind == "mode_map" ? Kind::mode_map : Kind::single;
  s.set = r.strings("set");
  s.setup = read_setup(r);
  r.finish();
}

void read_variants(Study& s, const TableReader& top, const std::string& file) {
  std::set<std::string> labels;
  each_table(top, "variant", file, [&](const TableReader& r, const toml::node&) {
    Variant v;
    v.label = r.string("label", "");
    if (!labels.insert(v.label).second)
      r.fail("label", fmt::format("\"{}\" is the label of an earlier variant: every variant needs its own", v.label));
    v.set = r.strings("set");
    v.args = r.quantity_table("args");
    s.variants.push_back(v);
  });
  if (s.variants.empty()) s.variants.push_back({});
}

void read_stability(Study& s, const TableReader& top, const std::string& file) {
  const toml::table* t = top.table("stability");
  if (s.kind != Kind::stability) {
    if (t) top.fail("stability", "a [stability] table needs kind = \"stability\"");
    return;
  }
  if (!t) top.fail("stability", "missing [stability] table for kind = \"stability\"");
  TableReader r(*t, "stability", file, kHelp);
  s.parameter = r.string("parameter", "numerics.dt");
  s.parameter_label = r.string("label", s.parameter);
  s.low = r.any_quantity("low").value;
  s.high = r.any_quantity("high").value;
  s.rel_tol = r.number_in("rel_tol", 1e-12, 0.5, 1e-4);
  if (!(s.low > 0.0 && s.high > s.low)) r.fail("low", fmt::format("need 0 < low < high, got low = {:g}, high = {:g}", s.low, s.high));
  r.finish();
}

void read_mode_map(Study& s, const TableReader& top, const std::string& file) {
  const toml::table* t = top.table("mode_map");
  if (s.kind != Kind::mode_map) {
    if (t) top.fail("mode_map", "a [mode_map] table needs kind = \"mode_map\"");
    return;
  }
  if (!t) top.fail("mode_map", "missing [mode_map] table for kind = \"mode_map\"");
  TableReader r(*t, "mode_map", file, kHelp);
  r.mark("blocks");
  const toml::array* b = r.node("blocks") ? r.node("blocks")->as_array() : nullptr;
  if (!b || b->empty()) r.fail("blocks", "expected [[columns, rows], ...] (whole numbers ≥ 1)");
  for (const auto& x : *b) {
    const toml::array* pair = x.as_array();
    std::optional<std::int64_t> c, w;
    if (pair && pair->size() == 2) {
      c = pair->get(0)->value_exact<std::int64_t>();
      w = pair->get(1)->value_exact<std::int64_t>();
    }
    if (!c || !w || *c < 1 || *w < 1 || *c > 1000 || *w > 1000)
      r.fail_at(x, "blocks", "expected [columns, rows]: two whole numbers from 1 to 1000");
    s.blocks.emplace_back(static_cast<int>(*c), static_cast<int>(*w));
  }
  auto angles = [&](const char* key, std::vector<double>& out) {
    r.mark(key);
    const toml::array* a = r.node(key) ? r.node(key)->as_array() : nullptr;
    if (!a || a->empty()) r.fail(key, "expected a list of angles in degrees");
    for (const auto& x : *a) {
      const auto d = x.value<double>();
      if (!d || !std::isfinite(*d) || *d < 0.0 || *d > 90.0) r.fail_at(x, key, "expected an angle in degrees from 0 to 90");
      out.push_back(*d * std::numbers::pi / 180.0);
    }
  };
  angles("phis_deg", s.phis);
  angles("alphas_deg", s.alphas);
  s.radius = r.quantity("radius", dem::dims::length);
  if (!(s.radius > 0.0)) r.fail("radius", "expected a positive length");
  s.margin = r.number_in("margin_deg", 0.0, 45.0, 1.0) * std::numbers::pi / 180.0;
  s.rotation_threshold = r.number_in("rotation_threshold", 0.0, 1e300, 2e-3, true);
  s.slide_threshold = r.quantity("slide_threshold", dem::dims::length, 1e-4);
  if (!(s.slide_threshold > 0.0)) r.fail("slide_threshold", "expected a positive length");
  s.wall_contact = static_cast<int>(r.integer("wall_contact", 0, 1000, 1));
  const std::string block = r.choice("block", {"lattice", "polygon", "rolling_disk"}, "lattice");
  s.mode_block = block == "polygon" ? Study::ModeBlock::polygon
                 : block == "rolling_disk" ? Study::ModeBlock::rolling_disk : Study::ModeBlock::lattice;
  r.finish();
}

Check read_check(const Study& s, const TableReader& r, const toml::node& n) {
  Check c;
  c.line = n.source().begin.line;
  c.probe = r.string("probe", s.kind == Kind::stability ? "limit" : s.kind == Kind::mode_map ? "mismatches" : "");
  if (c.probe.empty()) r.fail("probe", "missing: the probe of the case to check");
  c.label = r.string("label", c.probe);
  c.solver = r.string("reference", "");
  if (!c.solver.empty()) check_solver(r, "reference", c.solver);
  if (auto v = r.optional_any_quantity("value")) c.value = v->value;
  const std::string trend = r.choice("trend", {"none", "decreasing", "increasing", "toward_reference"}, "none");
  c.trend = trend == "decreasing" ? Trend::decreasing : trend == "increasing" ? Trend::increasing
            : trend == "toward_reference" ? Trend::toward_reference : Trend::none;
  if (c.trend != Trend::none && s.kind != Kind::single && s.kind != Kind::refinement)
    r.fail("trend", "a trend check needs kind = \"single\" or \"refinement\"");
  c.against_variant = r.string("against_variant", "");
  if (!c.against_variant.empty()) {
    if (s.kind != Kind::single) r.fail("against_variant", "needs kind = \"single\"");
    if (!c.solver.empty() || c.value || c.trend != Trend::none)
      r.fail("against_variant", "give a reference solver, a value, a trend or against_variant: one of them");
    const bool known = std::any_of(s.variants.begin(), s.variants.end(), [&](const Variant& v) { return v.label == c.against_variant; });
    if (!known) r.fail("against_variant", fmt::format("no variant \"{}\" in the study", c.against_variant));
  }
  if (c.solver.empty() && !c.value && c.against_variant.empty() && s.kind != Kind::refinement &&
      (c.trend == Trend::none || c.trend == Trend::toward_reference))
    r.fail_at(n, "reference", fmt::format("check \"{}\": give a reference solver or a value", c.label));
  c.args = r.quantity_table("args");
  c.offset = r.optional_any_quantity("reference_offset").value_or(dem::Quantity{0.0, dem::dims::dimensionless}).value;
  c.scale = r.number("reference_scale", 1.0);
  if ((r.has("reference_offset") || r.has("reference_scale")) && c.solver.empty())
    r.fail(r.has("reference_offset") ? "reference_offset" : "reference_scale", "needs a reference solver");
  if (!r.has("tolerance")) r.fail("tolerance", fmt::format("check \"{}\": missing tolerance", c.label));
  c.tolerance = r.any_quantity("tolerance").value;
  c.relative = r.choice("error", {"abs", "rel"}, "abs") == "rel";
  c.reason = r.string("reason", "");
  if (c.reason.empty()) r.fail("reason", fmt::format("check \"{}\": every tolerance needs a one-line reason", c.label));
  if (r.has("expected_order")) {
    c.expected_order = r.number_in("expected_order", 0.0, 20.0, 0.0, true);
    c.order_band = r.number_in("order_band", 0.0, 10.0, 0.2, true);
    if (s.kind != Kind::refinement) r.fail("expected_order", "an observed order needs kind = \"refinement\"");
  } else if (r.has("order_band")) {
    r.fail("order_band", "needs expected_order (the band is around it)");
  }
  if (r.has("fit_levels")) {
    r.mark("fit_levels");
    const toml::array* fl = r.node("fit_levels")->as_array();
    if (!fl) r.fail("fit_levels", "expected an array of level indices (0 = the coarsest)");
    for (const auto& x : *fl) {
      const auto k = x.value_exact<std::int64_t>();
      if (!k || *k < 0 || static_cast<std::size_t>(*k) >= s.refinement.levels.size())
        r.fail_at(x, "fit_levels", fmt::format("expected level indices from 0 to {}", s.refinement.levels.size() - 1));
      c.fit_levels.push_back(static_cast<std::size_t>(*k));
    }
    if (s.kind != Kind::refinement) r.fail("fit_levels", "needs kind = \"refinement\"");
  }
  c.only = r.strings("variants");
  if (!c.against_variant.empty() &&
      (c.only.empty() || std::find(c.only.begin(), c.only.end(), c.against_variant) != c.only.end()))
    r.fail("against_variant", fmt::format("the check's variants must not include \"{}\" (a variant against itself "
                                          "cannot fail): list the variants it compares", c.against_variant));
  const std::string ex = r.choice("expect", {"within", "above", "below"}, "within");
  c.expect = ex == "above" ? Expect::above : ex == "below" ? Expect::below : Expect::within;
  if (c.expect != Expect::within && c.trend != Trend::none) r.fail("expect", "a trend check asserts its own direction: remove expect");
  // |error| ≤ tolerance can never hold below 0; a trend, above or below takes a margin of either sign
  // (a margin of −1e-9 lets a trend step back by round-off).
  if (c.expect == Expect::within && c.trend == Trend::none && !(c.tolerance >= 0.0))
    r.fail("tolerance", fmt::format("expected a finite tolerance ≥ 0 for |error| ≤ tolerance (0: exact), got {:g}: it "
                                    "could never pass", c.tolerance));
  const std::string cmp = r.choice("compare", {"finest", "richardson", "each"}, "finest");
  c.compare_richardson = cmp == "richardson";
  c.compare_each = cmp == "each";
  if ((c.compare_richardson || c.compare_each) && s.kind != Kind::refinement)
    r.fail("compare", fmt::format("compare = \"{}\" needs kind = \"refinement\"", cmp));
  if (c.compare_each && (c.expected_order || c.trend != Trend::none))
    r.fail("compare", "compare = \"each\" checks values, not an order or a trend: remove expected_order / trend");
  if (c.compare_each && c.solver.empty() && !c.value)
    r.fail("compare", "compare = \"each\" needs a reference solver or a value");
  if (r.has("assumed_order")) {
    c.assumed_order = r.number_in("assumed_order", 0.0, 20.0, 1.0, true);
    if (s.kind != Kind::refinement) r.fail("assumed_order", "needs kind = \"refinement\"");
  }
  return c;
}

Figure read_figure(const Study& s, const TableReader& r, const toml::node& n) {
  Figure f;
  f.id = r.string("id", fmt::format("figure{}", s.figures.size()));
  f.title = r.string("title", f.id);
  f.x = r.string("x", "t");
  f.y = r.string("y", "");
  f.probe = r.string("probe", "");
  f.walls = r.strings("walls");  // a wall-contact profile (study_wall_profile.hpp)
  if (f.y.empty() && f.probe.empty() && f.walls.empty()) r.fail_at(n, "y", "missing: the series quantity to plot (or probe = a probe across variants)");
  if (!f.y.empty() && !f.probe.empty()) r.fail("probe", "give y (a series quantity over time) or probe (a probe across variants), not both");
  f.xlabel = r.string("xlabel", f.x);
  f.ylabel = r.string("ylabel", f.y);
  f.x_scale = r.number("x_scale", 1.0);
  f.y_scale = r.number("y_scale", 1.0);
  f.ref_scale = r.number("reference_scale", 1.0);
  f.y_from_start = r.boolean("y_from_start", false);
  f.every = r.integer("every", 1, std::int64_t{1} << 40, 100);
  r.mark("reference");
  if (const toml::node* rn = r.node("reference")) {  // "solver" or, for a time-series figure, ["solver", ...]
    if (auto one = rn->value_exact<std::string>()) {
      f.solvers.push_back(*one);
    } else if (const toml::array* ra = rn->as_array(); ra && !ra->empty()) {
      for (const auto& x : *ra) {
        auto name = x.value_exact<std::string>();
        if (!name || name->empty()) r.fail_at(x, "reference", "expected a solver name or an array of solver names");
        f.solvers.push_back(*name);
      }
    } else {
      r.fail("reference", "expected a solver name or an array of solver names");
    }
    for (const auto& name : f.solvers) check_solver(r, "reference", name);
    f.solver = f.solvers.front();
  }
  f.x_arg = r.string("x_arg", "t");
  f.args = r.quantity_table("args");
  f.variants = r.strings("variants");
  f.logx = r.boolean("logx", false);
  f.logy = r.boolean("logy", false);
  f.y_offset = r.number("y_offset", 0.0);
  f.y_minus_reference = r.boolean("y_minus_reference", false);
  if (f.solvers.size() > 1 && (!f.probe.empty() || f.y_minus_reference))
    r.fail("reference", "several references need a time-series figure without y_minus_reference");
  if (f.y_minus_reference && f.solver.empty()) r.fail("y_minus_reference", "needs a reference solver");
  f.group_arg = r.string("group_arg", "");
  f.group_label = r.string("group_label", f.group_arg);
  f.reference_points = r.integer("reference_points", 0, 100000, 0);
  f.reference_per_variant = r.boolean("reference_per_variant", false);
  f.y_relative_to = r.string("y_relative_to", "");
  if (!f.y_relative_to.empty()) {
    if (f.probe.empty()) r.fail("y_relative_to", "needs a probe figure (probe = ...)");
    if (!f.solver.empty()) r.fail("y_relative_to", "a figure of ratios has no reference solver");
    const bool known = std::any_of(s.variants.begin(), s.variants.end(), [&](const Variant& v) { return v.label == f.y_relative_to; });
    if (!known) r.fail("y_relative_to", fmt::format("no variant \"{}\" in the study", f.y_relative_to));
  }
  if (!f.probe.empty() && f.x_arg == "t") r.fail_at(n, "x_arg", "a probe figure needs x_arg: the variant argument on x");
  for (const char* key : {"x_range", "y_range"}) {
    r.mark(key);
    const toml::node* rn = r.node(key);
    if (!rn) continue;
    const toml::array* a = rn->as_array();
    if (!a || a->size() != 2) r.fail(key, "expected [lo, hi]");
    std::vector<double>& out = std::string(key) == "x_range" ? f.x_range : f.y_range;
    for (const auto& x : *a) out.push_back(r.any_quantity_of(x, key).value);
    if (!(out[0] < out[1])) r.fail(key, "expected lo < hi");
  }
  if (const toml::table* cl = r.table("labels"))
    for (const auto& [k, v] : *cl) {
      auto word = v.value_exact<std::string>();
      if (!word) r.fail_at(v, "labels." + std::string(k.str()), "expected a string (the legend's words)");
      f.curve_labels[std::string(k.str())] = *word;
    }
  if (!f.walls.empty()) read_wall_profile(f, s, r, n);
  else if (r.node("component")) r.fail("component", "needs walls = [...] (a wall-contact profile)");
  return f;
}

TableDecl read_table(const Study& s, const TableReader& r, const toml::node& n) {
  if (s.kind == Kind::mode_map) r.fail_at(n, "table", "declared tables need kind = single, refinement or stability");
  TableDecl d;
  d.title = r.string("title", "");
  d.probes = r.strings("probes");
  if (r.has("probe")) d.probes.insert(d.probes.begin(), r.string("probe"));
  if (d.probes.empty()) r.fail_at(n, "probe", "missing: the probe(s) to tabulate (or element_steps_per_second)");
  d.row_arg = r.string("row_arg", "");
  d.column_arg = r.string("column_arg", "");
  d.row_label = r.string("row_label", d.row_arg);
  d.column_label = r.string("column_label", d.column_arg);
  if (d.row_arg.empty() != d.column_arg.empty()) r.fail_at(n, "row_arg", "give both row_arg and column_arg (a pivot) or neither");
  if (!d.row_arg.empty() && d.probes.size() != 1) r.fail_at(n, "probe", "a pivot table shows one probe");
  d.scale = r.number("scale", 1.0);
  d.variants = r.strings("variants");
  if (d.title.empty()) d.title = d.probes.front();
  return d;
}

/// Every name of `names` is the label of a variant; returns how many variants the list selects
/// (an empty list selects all).
std::size_t selected(const Study& s, const std::vector<std::string>& names, const std::string& file, std::uint32_t line,
                     const std::string& key) {
  std::vector<std::string> labels;
  for (const Variant& v : s.variants) labels.push_back(v.label);
  for (const std::string& name : names)
    if (std::find(labels.begin(), labels.end(), name) == labels.end()) {
      const std::string near = dem::nearest_word(name, labels);
      throw dem::CaseError(fmt::format("{}:{}: {}: \"{}\" names no variant{} (the labels are \"{}\")", file, line, key, name,
                                       near.empty() ? "" : fmt::format("; did you mean \"{}\"?", near),
                                       fmt::join(labels, "\", \"")));
    }
  return names.empty() ? s.variants.size() : names.size();
}

/// The arguments of `solver` missing from `given` ("param" is the refined or bisected value, always given).
std::vector<std::string> missing_arguments(const std::string& solver, const std::map<std::string, double>& given) {
  std::vector<std::string> out;
  if (const ref::SolverInfo* info = find_solver(solver))
    for (const auto& a : info->arguments)
      if (a.name != "param" && !given.count(a.name)) out.push_back(a.name);
  return out;
}

/// What can be checked across the tables before anything runs: the variants each check and figure
/// names, the reference arguments every check gets, the probes of the case.
void cross_check(const Study& s, const std::string& file) {
  for (const Check& c : s.checks) {
    const std::size_t n = selected(s, c.only, file, c.line, "check.variants");
    if (c.trend != Trend::none && n < 2)
      throw dem::CaseError(fmt::format("{}:{}: check.variants: check \"{}\": a trend needs at least two variants", file, c.line, c.label));
    if (c.solver.empty()) continue;
    std::vector<const RefinementLevel*> levels{nullptr};
    if (s.kind == Kind::refinement) {
      levels.clear();
      for (const RefinementLevel& l : s.refinement.levels) levels.push_back(&l);
    }
    for (const Variant& v : s.variants) {
      if (!applies(c, v)) continue;
      for (const RefinementLevel* l : levels) {
        std::map<std::string, double> args = v.args;
        if (l) args.insert(l->args.begin(), l->args.end());
        for (const auto& [k, x] : c.args) args[k] = x;
        const auto miss = missing_arguments(c.solver, args);
        if (!miss.empty())
          throw dem::CaseError(fmt::format("{}:{}: check.args: check \"{}\"{}: the reference {} needs {} (give them in the "
                                           "check's args, the variant's or the level's)", file, c.line, c.label,
                                           v.label.empty() ? "" : " for variant \"" + v.label + "\"", c.solver,
                                           fmt::join(miss, ", ")));
      }
    }
  }
}

/// "file:line" of the override `kv` in the study file: in [study] set, the variant's set or a [[level]]'s set;
/// else the variant's table (or [study]).
std::string override_location(const toml::table& root, const std::string& file, std::size_t variant, const std::string& kv) {
  std::vector<const toml::node*> lists{root["study"]["set"].node()};
  if (const toml::array* vs = root["variant"].as_array(); vs && variant < vs->size())
    if (const toml::table* vt = vs->get(variant)->as_table()) lists.push_back(vt->get("set"));
  if (const toml::array* ls = root["level"].as_array())
    for (const toml::node& l : *ls) lists.push_back(l.as_table() ? l.as_table()->get("set") : nullptr);
  for (const toml::node* list : lists)
    if (const toml::array* a = list ? list->as_array() : nullptr)
      for (const toml::node& item : *a)
        if (item.value_exact<std::string>() == kv) return dem::where(item, file);
  if (const toml::array* vs = root["variant"].as_array(); vs && variant < vs->size()) return dem::where(*vs->get(variant), file);
  return dem::where(*root["study"].node(), file);
}

/// The base case with the overrides of a variant; an error names the study file's line of the override
/// that caused it (or the variant) before the case's own message.
dem::Case read_variant_case(const Study& s, const Variant& v, const std::vector<std::string>& sets, const toml::table& root,
                            const std::string& file) {
  try {
    return dem::read_case(s.case_file, sets);
  } catch (const dem::CaseError& e) {
    const std::string what = e.what();
    std::string culprit;  // the override the case names ("--set key=value: key: …")
    for (const std::string& kv : sets)
      if (what.rfind("--set " + kv + ":", 0) == 0) culprit = kv;
    const auto variant = static_cast<std::size_t>(&v - s.variants.data());
    const std::string label = v.label.empty() ? "" : fmt::format("variant \"{}\": ", v.label);
    throw dem::CaseError(fmt::format("{}: set: {}{}", override_location(root, file, variant, culprit), label, what));
  }
}

/// A mode map runs its grid, not variants: [[variant]] is refused; the case is read with every block's
/// overrides (mode_map_sets, the first φ and α) before anything runs. An error names the line of the
/// study's override at fault, or of the [mode_map] key whose overrides the case does not take.
void check_mode_map_sets(const Study& s, const toml::table& root, const std::string& file) {
  if (const toml::array* vs = root["variant"].as_array(); vs && !vs->empty())
    throw dem::CaseError(fmt::format("{}: variant: a mode map runs its grid of blocks and angles, not variants "
                                     "(give the overrides in [study] set)", dem::where(*vs->get(0), file)));
  const toml::table& mm = *root["mode_map"].as_table();
  for (std::size_t b = 0; b < s.blocks.size(); ++b) {
    const std::vector<std::string> sets = mode_map_sets(s, b, s.phis.front(), s.alphas.front());
    try {
      (void)dem::read_case(s.case_file, sets);
    } catch (const dem::CaseError& e) {
      const std::string what = e.what();
      std::string culprit;  // the override the case names ("--set key=value: key: …")
      for (const std::string& kv : sets)
        if (what.rfind("--set " + kv + ":", 0) == 0) culprit = kv;
      if (culprit.empty() || std::find(s.set.begin(), s.set.end(), culprit) != s.set.end())
        throw dem::CaseError(fmt::format("{}: set: {}", override_location(root, file, 0, culprit), what));
      const char* key = culprit.rfind("contact.", 0) == 0           ? "wall_contact"  // φ of that contact
                        : culprit.rfind("physics.gravity", 0) == 0 ? "alphas_deg"    // α as gravity's direction
                                                                   : "blocks";       // lattice and pivot probes
      const toml::node* at = mm.get(key) ? mm.get(key) : root.get("mode_map");
      throw dem::CaseError(fmt::format("{}: mode_map.{}: the case {} does not take the mode map's overrides "
                                       "(block {}x{}): {}", dem::where(*at, file), key, s.case_path, s.blocks[b].first,
                                       s.blocks[b].second, what));
    }
  }
}

/// Reads the base case once per variant (with the study's and the variant's overrides, and the
/// finest level's; a stability study's without its bisected parameter) and refuses a check of a probe the case does not have, or a check value given in
/// another unit than the probe's.
void check_probes(const Study& s, const toml::table& root, const std::string& file) {
  if (s.kind == Kind::mode_map) check_mode_map_sets(s, root, file);
  if (s.kind == Kind::stability)  // no probes to check, but every variant's overrides must read
    for (const Variant& v : s.variants) {
      std::vector<std::string> sets = s.set;
      sets.insert(sets.end(), v.set.begin(), v.set.end());
      (void)read_variant_case(s, v, sets, root, file);
    }
  if (s.kind != Kind::single && s.kind != Kind::refinement) return;
  for (const Variant& v : s.variants) {
    std::vector<std::string> sets = s.set;
    sets.insert(sets.end(), v.set.begin(), v.set.end());
    if (s.kind == Kind::refinement)
      sets.insert(sets.end(), s.refinement.levels.back().set.begin(), s.refinement.levels.back().set.end());
    if (s.ensemble) {  // the last member's overrides must read (the seed key, the shared overrides)
      const std::vector<std::string> m = member_sets(*s.ensemble, s.ensemble->members);
      sets.insert(sets.end(), m.begin(), m.end());
      try {
        (void)dem::read_case(s.case_file, sets);
      } catch (const dem::CaseError& e) {
        throw dem::CaseError(fmt::format("{}:{}: ensemble: variant \"{}\": {}", file, s.ensemble->line, v.label, e.what()));
      }
    }
    const dem::Case c = read_variant_case(s, v, sets, root, file);
    std::size_t k = 0;
    for (const Check& ch : s.checks) {
      const toml::node& node = *root["check"].as_array()->get(k++);
      if (!applies(ch, v) || ch.probe == "element_steps_per_second") continue;
      const auto p = std::find_if(c.probes.begin(), c.probes.end(), [&](const dem::ProbeSpec& x) { return x.name == ch.probe; });
      if (p == c.probes.end()) {
        std::vector<std::string> names;
        for (const auto& x : c.probes) names.push_back(x.name);
        const std::string near = dem::nearest_word(ch.probe, names);
        throw dem::CaseError(fmt::format("{}: check.probe: the case {} has no probe \"{}\"{}", dem::where(*node.as_table()->get("probe"), file),
                                         s.case_path, ch.probe, near.empty() ? "" : fmt::format("; did you mean \"{}\"?", near)));
      }
      const toml::node* vn = node.as_table()->get("value");
      if (!vn || !vn->is_string()) continue;
      const std::string unit = dem::probe_unit(*p);
      const dem::Dimension want = unit == "1" ? dem::dims::dimensionless : dem::parse_quantity("1 " + unit).dim;
      const dem::Quantity got = dem::parse_quantity(*vn->value<std::string>());
      if (got.dim != want)
        throw dem::CaseError(fmt::format("{}: check.value: the probe \"{}\" is in {}, the value is {}", dem::where(*vn, file),
                                         ch.probe, unit, dem::to_string(got.dim)));
    }
  }
}

}  // namespace

nlohmann::json read_setup(const dem::TableReader& r) {
  nlohmann::json setup = nlohmann::json::object();
  if (const toml::table* su = r.table("setup"))
    for (const auto& [k, v] : *su) {
      if (auto x = v.value<double>()) setup[std::string(k.str())] = *x;
      else if (auto y = v.value_exact<std::string>()) setup[std::string(k.str())] = *y;
      else r.fail_at(v, "setup." + std::string(k.str()), "expected a number or a string (shown in the report)");
    }
  return setup;
}

bool applies(const Check& c, const Variant& v) {
  return c.only.empty() || std::find(c.only.begin(), c.only.end(), v.label) != c.only.end();
}

const char* kind_word(Kind k) {
  return k == Kind::refinement ? "refinement" : k == Kind::single ? "single" : k == Kind::stability ? "stability" : "mode_map";
}

Study read_study(const fs::path& file_path) {
  Study s;
  s.file = file_path;
  const std::string file = file_path.string();
  const toml::table root = dem::parse_toml_file(file_path);
  TableReader top(root, "", file, kHelp);
  read_header(s, top, file);
  read_variants(s, top, file);
  top.mark("refinement");
  top.mark("level");
  if (s.kind == Kind::refinement) {
    if (!root.get("refinement") && !root.get("level"))  // named at the line that asks for a refinement
      throw dem::CaseError(fmt::format("{}: study.kind: kind = \"refinement\" needs a [refinement] table (or [[level]] "
                                       "tables); none is given", dem::where(*root["study"]["kind"].node(), file)));
    s.refinement = read_refinement(root, file);
    s.parameter = s.refinement.parameter;
    s.parameter_label = s.refinement.label;
  } else {
    if (root.get("refinement")) top.fail("refinement", "a [refinement] table needs kind = \"refinement\"");
    refuse_levels(root, file);
  }
  read_stability(s, top, file);
  read_mode_map(s, top, file);
  s.ensemble = read_ensemble(top, s.kind == Kind::single);
  each_table(top, "check", file, [&](const TableReader& r, const toml::node& n) { s.checks.push_back(read_check(s, r, n)); });
  if (s.checks.empty()) top.fail("check", "missing: at least one [[check]] (a study without checks proves nothing)");
  each_table(top, "figure", file, [&](const TableReader& r, const toml::node& n) {
    s.figures.push_back(read_figure(s, r, n));
    if (selected(s, s.figures.back().variants, file, n.source().begin.line, "figure.variants") == 0)
      r.fail_at(n, "variants", "the figure selects no variant");
  });
  each_table(top, "table", file, [&](const TableReader& r, const toml::node& n) {
    s.tables.push_back(read_table(s, r, n));
    selected(s, s.tables.back().variants, file, n.source().begin.line, "table.variants");
  });
  read_snapshots(s, top, file);
  top.finish();
  cross_check(s, file);
  check_probes(s, root, file);
  return s;
}

}  // namespace ver
