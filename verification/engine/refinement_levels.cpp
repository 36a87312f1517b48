#include "engine/refinement_levels.hpp"

#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "dem/cases/case_reader.hpp"
#include "dem/cases/units.hpp"

namespace ver {

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& key, const std::string& what) {
  throw std::runtime_error(fmt::format("{}: {}: {}", file, key, what));
}

[[noreturn]] void fail_at(const std::string& file, const toml::node& n, const std::string& key, const std::string& what) {
  throw std::runtime_error(fmt::format("{}:{}: {}: {}", file, n.source().begin.line, key, what));
}

/// A number, or a string with a unit ("2.5 mm"), in SI.
double number_or_quantity(const std::string& file, const toml::node& n, const std::string& key) {
  if (auto d = n.value<double>()) return *d;
  if (auto str = n.value_exact<std::string>()) {
    try {
      return dem::parse_quantity(*str).value;
    } catch (const std::exception& e) {
      fail_at(file, n, key, e.what());
    }
  }
  fail_at(file, n, key, "expected a number or a string with a unit");
}

/// The values form: one --set path, one value per level (the format of the override is the one the
/// engine always used, so that the runs and their cache keys do not change).
Refinement read_values(const toml::table& t, const std::string& file) {
  const dem::TableReader r(t, "refinement", file, "verification/README.md, \"The study file\"");
  Refinement out;
  out.parameter = r.string("parameter");
  out.label = r.string("label", out.parameter);
  if (out.parameter.empty()) r.fail("parameter", "missing: the case key to refine, e.g. numerics.dt");
  std::vector<double> values;
  r.mark("values");
  if (const toml::node* vn = r.node("values")) {
    const toml::array* a = vn->as_array();
    if (!a) r.fail("values", "expected an array of the parameter's values, coarse → fine");
    for (const auto& x : *a) values.push_back(r.any_quantity_of(x, "values").value);
    for (const char* key : {"base", "ratio", "levels"})
      if (r.has(key)) r.fail(key, "give values = [...] or base, ratio, levels; not both");
  } else {
    if (!r.has("base")) r.fail_here("give values = [...] or base, ratio, levels (or [[level]] tables)");
    const double base = r.any_quantity("base").value;
    const double ratio = r.number_in("ratio", 1.0, 1e6, 2.0, true);
    const auto levels = r.integer("levels", 2, 64, 4);
    for (int64_t k = 0; k < levels; ++k) values.push_back(base / std::pow(ratio, static_cast<double>(k)));
  }
  if (values.size() < 2) r.fail("values", "need at least two levels");
  const std::string hk = r.choice("h", {"value", "inverse"}, "value");
  out.inverse = hk == "inverse";
  for (double v : values) {
    if (!(v > 0.0)) r.fail(r.has("values") ? "values" : "base", fmt::format("expected positive values, got {:g}", v));
    RefinementLevel l;
    l.value = v;
    l.h = out.inverse ? 1.0 / v : v;
    if (!out.levels.empty() && !(l.h < out.levels.back().h))
      r.fail(r.has("values") ? "values" : "base",
             fmt::format("expected the levels from coarse to fine (h = {} strictly decreasing): {:g} follows {:g}",
                         out.inverse ? "1/value" : "the value", v, out.levels.back().value));
    l.set.push_back(v == std::floor(v) && std::abs(v) < 1e15 ? fmt::format("{}={}", out.parameter, static_cast<long long>(v))
                                                            : fmt::format("{}={:.17g}", out.parameter, v));
    out.levels.push_back(l);
  }
  r.finish();
  return out;
}

/// The [[level]] form.
Refinement read_levels(const toml::table& root, const toml::table* r, const std::string& file) {
  Refinement out;
  out.declared_levels = true;
  const toml::node& lv = *root.get("level");
  const toml::array* la = lv.as_array();
  if (!la) fail_at(file, lv, "level", "expected [[level]] tables, each with label, h (or n), set and args");
  if (r) {
    for (const char* key : {"parameter", "values", "base", "ratio", "levels", "h"})
      if (const toml::node* n = r->get(key))
        fail_at(file, *n, fmt::format("refinement.{}", key),
                "with [[level]] tables each level gives its own h (or n) and overrides: remove this key "
                "(keep label, the name of the h axis)");
    for (const auto& [k, v] : *r)
      if (k.str() != "label")
        fail_at(file, v, fmt::format("refinement.{}", k.str()), "unknown key (with [[level]] tables: label only)");
    out.label = (*r)["label"].value_or(std::string("h"));
  } else {
    out.label = "h";
  }
  std::set<std::string> labels;
  std::optional<bool> by_count;  // all levels give n, or all give h
  for (const auto& n : *la) {
    const toml::table* t = n.as_table();
    if (!t) fail_at(file, n, "level", "expected [[level]] tables, each with label, h (or n), set and args");
    const std::size_t k = out.levels.size();
    for (const auto& [key, v] : *t) {
      const std::string name(key.str());
      if (name == "label" || name == "h" || name == "n" || name == "set" || name == "args") continue;
      const std::string near = dem::nearest_word(name, {"label", "h", "n", "set", "args"});
      fail_at(file, v, "level." + name, fmt::format("unknown key (expected label, h or n, set, args){}",
                                                    near.empty() ? std::string() : fmt::format("; did you mean '{}'?", near)));
    }
    RefinementLevel l;
    if (const toml::node* x = t->get("label")) {
      const auto s = x->value_exact<std::string>();
      if (!s || s->empty()) fail_at(file, *x, "level.label", "expected a non-empty string");
      l.label = *s;
    } else {
      l.label = fmt::format("level {}", k);
    }
    if (!labels.insert(l.label).second) fail_at(file, n, "level.label", fmt::format("\"{}\" is used by two levels", l.label));
    const toml::node* hn = t->get("h");
    const toml::node* nn = t->get("n");
    if (hn && nn) fail_at(file, *nn, "level.n", "give h (a length) or n (a count, h = 1/n), not both");
    if (!hn && !nn)
      fail_at(file, n, "level.h", "missing: the level's length h (a number or a quantity such as \"2.5 mm\") or its count n (h = 1/n)");
    if (by_count && *by_count != (nn != nullptr))
      fail_at(file, hn ? *hn : *nn, hn ? "level.h" : "level.n", "every level gives h, or every level gives n; not a mix");
    by_count = nn != nullptr;
    l.value = number_or_quantity(file, hn ? *hn : *nn, hn ? "level.h" : "level.n");
    if (!std::isfinite(l.value) || !(l.value > 0.0))
      fail_at(file, hn ? *hn : *nn, hn ? "level.h" : "level.n", fmt::format("expected a positive number, got {}", l.value));
    l.h = nn ? 1.0 / l.value : l.value;
    if (!out.levels.empty() && !(l.h < out.levels.back().h))
      fail_at(file, hn ? *hn : *nn, hn ? "level.h" : "level.n",
              fmt::format("expected the levels from coarse to fine (h strictly decreasing): h = {:g} follows h = {:g}", l.h,
                          out.levels.back().h));
    if (const toml::node* sn = t->get("set")) {
      const toml::array* a = sn->as_array();
      if (!a) fail_at(file, *sn, "level.set", "expected an array of overrides, e.g. [\"lattice.0.columns=2\"]");
      for (const auto& x : *a) {
        const auto v = x.value_exact<std::string>();
        if (!v || v->find('=') == std::string::npos)
          fail_at(file, x, "level.set", "expected an array of overrides \"path=value\", e.g. [\"lattice.0.columns=2\"]");
        l.set.push_back(*v);
      }
    }
    if (const toml::node* an = t->get("args")) {
      const toml::table* a = an->as_table();
      if (!a) fail_at(file, *an, "level.args", "expected a table of reference arguments, e.g. { n_w = 2, n_h = 6 }");
      for (const auto& [k2, v] : *a) l.args[std::string(k2.str())] = number_or_quantity(file, v, "level.args." + std::string(k2.str()));
    }
    out.levels.push_back(l);
  }
  out.inverse = by_count.value_or(false);
  if (out.levels.size() < 2) fail_at(file, lv, "level", "need at least two [[level]] tables");
  return out;
}

}  // namespace

Refinement read_refinement(const toml::table& root, const std::string& file) {
  const toml::table* r = root["refinement"].as_table();
  if (root.get("refinement") && !r) fail_at(file, *root.get("refinement"), "refinement", "expected a [refinement] table");
  if (root.get("level")) return read_levels(root, r, file);
  if (!r) fail(file, "refinement", "missing [refinement] table (or [[level]] tables) for kind = \"refinement\"");
  return read_values(*r, file);
}

Series analyse_levels(const Refinement& refinement, const std::vector<std::optional<double>>& values,
                      const ConvergenceOptions& options, const std::string& name, std::vector<std::string>* labels) {
  if (values.size() != refinement.levels.size())
    throw std::invalid_argument(fmt::format("analyse_levels: {} values for {} levels", values.size(), refinement.levels.size()));
  std::vector<double> h, q;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!values[k]) continue;
    h.push_back(refinement.levels[k].h);
    q.push_back(*values[k]);
    if (labels) labels->push_back(refinement.levels[k].label);
  }
  return analyse_convergence(h, q, options, name, refinement.label);
}

void refuse_levels(const toml::table& root, const std::string& file) {
  if (const toml::node* n = root.get("level")) fail_at(file, *n, "level", "[[level]] tables need kind = \"refinement\"");
}

}  // namespace ver
