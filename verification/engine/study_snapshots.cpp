// Reading the [[snapshot]] tables of a study file (study_snapshots.hpp), as strictly as the rest of it.
#include "engine/study_snapshots.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/cases/units.hpp"
#include "engine/study_file.hpp"

namespace ver {

namespace {

constexpr const char* kHelp = "verification/README.md, \"The study file\"";

/// Every label of `names` is a variant's ("did you mean" the nearest), as for checks and figures.
void check_variant_labels(const Study& s, const dem::TableReader& r, const std::vector<std::string>& names) {
  std::vector<std::string> labels;
  for (const Variant& v : s.variants) labels.push_back(v.label);
  for (const std::string& name : names)
    if (std::find(labels.begin(), labels.end(), name) == labels.end()) {
      const std::string near = dem::nearest_word(name, labels);
      r.fail("variants", fmt::format("\"{}\" names no variant{} (the labels are \"{}\")", name,
                                     near.empty() ? "" : fmt::format("; did you mean \"{}\"?", near),
                                     fmt::join(labels, "\", \"")));
    }
}

/// `at`: times with a unit ("0.9 s") and/or the word "end", the times strictly increasing.
void read_times(Snapshot& snap, const dem::TableReader& r) {
  r.mark("at");
  const toml::node* n = r.node("at");
  const toml::array* a = n ? n->as_array() : nullptr;
  if (!a || a->empty()) r.fail("at", "expected a non-empty list of times with a unit and/or \"end\", e.g. [\"0.9 s\", \"end\"]");
  if (a->size() > 100) r.fail("at", "at most 100 times");
  for (const auto& x : *a) {
    if (x.value_exact<std::string>() == std::optional<std::string>("end")) {
      if (snap.end) r.fail_at(x, "at", "\"end\" given twice");
      snap.end = true;
      continue;
    }
    if (!x.is_string()) r.fail_at(x, "at", "expected a time with its unit (\"0.9 s\") or \"end\"");
    const double t = r.quantity_of(x, "at", dem::dims::time);
    if (!(t >= 0.0)) r.fail_at(x, "at", fmt::format("expected a time ≥ 0 s, got {:g} s", t));
    if (!snap.times.empty() && t <= snap.times.back())
      r.fail_at(x, "at", fmt::format("the times must increase strictly ({:g} s after {:g} s)", t, snap.times.back()));
    snap.times.push_back(t);
  }
}

/// Every time lies within the run of every listed variant (numerics.duration after the overrides).
void check_within_runs(const Study& s, const Snapshot& snap, const dem::TableReader& r) {
  if (snap.times.empty()) return;
  const toml::array& a = *r.node("at")->as_array();
  for (const Variant& v : s.variants) {
    if (!snap.variants.empty() && std::find(snap.variants.begin(), snap.variants.end(), v.label) == snap.variants.end())
      continue;
    std::vector<std::string> sets = s.set;
    sets.insert(sets.end(), v.set.begin(), v.set.end());
    if (s.kind == Kind::refinement) sets.insert(sets.end(), s.refinement.levels.back().set.begin(), s.refinement.levels.back().set.end());
    const double duration = dem::read_case(s.case_file, sets).model.numerics.duration;
    for (const auto& x : a)
      if (x.is_string() && *x.value<std::string>() != "end" && r.quantity_of(x, "at", dem::dims::time) > duration * (1.0 + 1e-12))
        r.fail_at(x, "at", fmt::format("{} lies past the end of the run{} (numerics.duration = {:g} s)", *x.value<std::string>(),
                                       v.label.empty() ? "" : " of variant \"" + v.label + "\"", duration));
  }
}

Snapshot read_snapshot(const Study& s, const dem::TableReader& r, const toml::node& n, std::set<std::string>& ids) {
  if (s.kind != Kind::single && s.kind != Kind::refinement)
    r.fail_at(n, "snapshot", "snapshots need kind = \"single\" or \"refinement\" (a run to picture)");
  Snapshot snap;
  snap.line = n.source().begin.line;
  snap.id = r.string("id");
  if (snap.id.empty() || snap.id.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") != std::string::npos)
    r.fail("id", fmt::format("expected a plain word (letters, digits, '_', '-'), got \"{}\"", snap.id));
  if (!ids.insert(snap.id).second) r.fail("id", fmt::format("\"{}\" is the id of an earlier snapshot", snap.id));
  snap.title = r.string("title");
  if (snap.title.empty()) r.fail("title", "expected the caption: what the pictures show and which paper figure they answer");
  snap.variants = r.strings("variants");
  check_variant_labels(s, r, snap.variants);
  read_times(snap, r);
  snap.max_force = r.optional_quantity("max_force", dem::dims::force);
  if (snap.max_force && !(*snap.max_force > 0.0 && std::isfinite(*snap.max_force)))
    r.fail("max_force", fmt::format("expected a positive force, got {:g} N", *snap.max_force));
  snap.width = r.integer("width", 64, 4000, 800);
  r.finish();  // a misspelled key first: "max_froce" is not a missing max_force
  const std::size_t n_variants = snap.variants.empty() ? s.variants.size() : snap.variants.size();
  const std::size_t pictures = n_variants * (snap.times.size() + (snap.end ? 1 : 0));
  if (pictures > 1 && !snap.max_force)
    r.fail_at(n, "max_force", fmt::format("snapshot \"{}\" has {} pictures: give max_force (e.g. \"500 N\"), the force drawn at "
                                          "the widest line in all of them, so that they compare", snap.id, pictures));
  check_within_runs(s, snap, r);
  return snap;
}

}  // namespace

void read_snapshots(Study& s, const dem::TableReader& top, const std::string& file) {
  top.mark("snapshot");
  const toml::node* n = top.node("snapshot");
  if (!n) return;
  const toml::array* arr = n->as_array();
  if (!arr) top.fail("snapshot", "expected [[snapshot]] tables");
  std::set<std::string> ids;
  for (const auto& x : *arr) {
    const toml::table* t = x.as_table();
    if (!t) top.fail_at(x, "snapshot", "expected [[snapshot]] tables (a table each), got a value");
    dem::TableReader r(*t, "snapshot", file, kHelp);
    s.snapshots.push_back(read_snapshot(s, r, x, ids));
  }
}

std::string variant_slug(const std::string& label) {
  // the letters and signs of the studies' labels in words ("α=60°" → "alpha_60deg")
  static const std::pair<const char*, const char*> words[] = {
      {"α", "alpha"}, {"β", "beta"}, {"ζ", "zeta"}, {"θ", "theta"}, {"μ", "mu"}, {"φ", "phi"},
      {"Δ", "D"}, {"°", "deg"}, {"×", "x"}};
  std::string text = label;
  for (const auto& [from, to] : words)
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + 1)) text.replace(at, std::string(from).size(), to);
  std::string out;
  for (const char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-';
    if (keep) out += c;
    else if (!out.empty() && out.back() != '_') out += '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() || out == "." || out == ".." ? std::string("run") : out;
}

std::vector<std::string> snapshot_sets(const Snapshot& snap) {
  std::vector<std::string> sets{"output.vtk=false", "output.every=0", "output.picture_every=\"0 s\"",
                                fmt::format("output.pictures={}", snap.end ? "true" : "false"),
                                fmt::format("output.picture_width={}", snap.width)};
  if (!snap.times.empty()) {
    std::vector<std::string> words;
    for (double t : snap.times) words.push_back(fmt::format("\"{} s\"", t));
    sets.push_back(fmt::format("output.picture_times=[{}]", fmt::join(words, ", ")));
  }
  if (snap.max_force) sets.push_back(fmt::format("output.picture_max_force=\"{} N\"", *snap.max_force));
  return sets;
}

}  // namespace ver
