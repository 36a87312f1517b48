// The case format's key table (case_keys.hpp), from which `dem2d schema` is made, against what the reader
// itself reads (key_log.hpp): every case file of the project (cases/, tests/lib/fixtures/, python/examples/)
// is read with a KeyLog recording; every key the reader accepted must be in the table with a compatible
// type, dimension, word list and default, and every key of the table must have been read.
// tests/lib/fixtures/schema/ holds small cases that reach the keys no shipped case uses.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/cases/case_keys.hpp"
#include "dem/cases/case_schema.hpp"
#include "dem/cases/key_log.hpp"
#include "../test_support.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> case_files() {
  std::vector<fs::path> out;
  for (const char* dir : {"cases", "tests/lib/fixtures", "python/examples"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(DEM2D_SOURCE_DIR) / dir))
      if (e.is_regular_file() && e.path().extension() == ".toml") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

bool subset(const std::vector<dem::Dimension>& a, const std::vector<dem::Dimension>& b) {
  return std::all_of(a.begin(), a.end(), [&](const dem::Dimension& x) { return std::find(b.begin(), b.end(), x) != b.end(); });
}

/// The spec's default in SI (a quantity string converted), to compare with the reader's fallback.
nlohmann::json si_default(const dem::KeySpec& k) {
  const auto si = [&](const nlohmann::json& v) -> nlohmann::json {
    if (!v.is_string() || k.dims.empty()) return v;
    return dem::to_si(v.get<std::string>(), k.dims.front());
  };
  if (!k.fallback.is_array()) return si(k.fallback);
  nlohmann::json a = nlohmann::json::array();
  for (const auto& v : k.fallback) a.push_back(si(v));
  return a;
}

bool kind_fits(const dem::KeyUse& u, const dem::KeySpec& k) {
  using dem::KeyKind;
  using dem::SpecKind;
  switch (u.kind) {
    case KeyKind::quantity:
      return (k.kind == SpecKind::quantity && subset(u.dims, k.dims) && (u.dims.empty() == k.dims.empty())) ||
             (k.kind == SpecKind::interval && u.dims == std::vector<dem::Dimension>{dem::dims::time});
    case KeyKind::element:
      return (k.kind == SpecKind::quantities || k.kind == SpecKind::vectors) && subset(u.dims, k.dims);
    case KeyKind::number: return k.kind == SpecKind::number;
    case KeyKind::integer: return k.kind == SpecKind::integer || k.kind == SpecKind::interval;
    case KeyKind::boolean: return k.kind == SpecKind::boolean;
    case KeyKind::string: return k.kind == SpecKind::string || k.kind == SpecKind::choice;
    case KeyKind::choice: return k.kind == SpecKind::choice && u.choices == k.choices;
    case KeyKind::strings: return k.kind == SpecKind::strings;
    case KeyKind::vector: return (k.kind == SpecKind::vector || k.kind == SpecKind::vector_or_table) && subset(u.dims, k.dims);
    case KeyKind::table: return k.kind == SpecKind::table || k.kind == SpecKind::vector_or_table;
    case KeyKind::other: return true;
  }
  return false;
}

/// What differs between one recorded read and the table's entry ("" if nothing).
std::string mismatch(const dem::KeyUse& u, const dem::KeySpec& k) {
  if (!kind_fits(u, k)) return fmt::format("the reader reads a {} here, the table says otherwise", dem::to_string(u.kind));
  const bool may_miss = u.kind == dem::KeyKind::table || u.kind == dem::KeyKind::strings ||  // the reader checks by hand
                        u.kind == dem::KeyKind::other || u.kind == dem::KeyKind::element;
  if (k.required && !u.required && !may_miss)
    return "the table says required, the reader has a default for it";
  // an integer's range (the table states no maximum where it depends on the case: an element index)
  if (u.kind == dem::KeyKind::integer && u.max && k.kind == dem::SpecKind::integer && (u.min != k.min || (k.max && u.max != k.max)))
    return fmt::format("range: the table says {} to {}, the reader accepts {} to {}", k.min.value_or(-1), k.max.value_or(-1), *u.min,
                       *u.max);
  if (!k.fallback.is_null() && !u.fallback.is_null() && si_default(k) != u.fallback)
    return fmt::format("default: the table says {}, the reader applies {}", k.fallback.dump(), u.fallback.dump());
  return "";
}

/// The problems of the key table against what the reader read.
std::vector<std::string> table_problems(const dem::KeyUses& uses) {
  std::set<std::string> out;  // each problem once, however many cases show it
  for (const auto& [path, keys] : uses) {
    const dem::TableSpec* t = dem::find_case_table(path);
    if (!t) {
      out.insert(fmt::format("table '{}': read by the reader, not in the key table", path));
      continue;
    }
    for (const auto& [key, reads] : keys) {
      const dem::KeySpec* k = t->find(key);
      if (!k) {
        out.insert(fmt::format("{}{}{}: accepted by the reader, not in the key table", path, path.empty() ? "" : ".", key));
        continue;
      }
      for (const dem::KeyUse& u : reads)
        if (const std::string m = mismatch(u, *k); !m.empty()) out.insert(fmt::format("{}.{}: {}", path, key, m));
    }
  }
  for (const dem::TableSpec& t : dem::case_key_tables())
    for (const dem::KeySpec& k : t.keys)
      if (!uses.count(t.path) || !uses.at(t.path).count(k.key))
        out.insert(fmt::format("{}.{}: in the key table, never read by the reader", t.path, k.key));
  return {out.begin(), out.end()};
}

dem::KeyUses read_every_case() {
  dem::KeyLog log;
  for (const fs::path& f : case_files()) {
    INFO(f.string());
    (void)dem::read_case(f);
  }
  return log.uses();
}

}  // namespace

TEST_CASE("key table: every key the reader accepts is in it and every key in it is read alike") {
  const dem::KeyUses uses = read_every_case();
  const std::vector<std::string> problems = table_problems(uses);
  INFO(fmt::format("{} problems:\n  {}", problems.size(), fmt::join(problems, "\n  ")));
  CHECK(problems.empty());
}

TEST_CASE("key table: a key the reader accepts but the table lacks is found") {
  dem::KeyUses uses = read_every_case();
  uses["numerics"]["dt_typo"].push_back({dem::KeyKind::quantity, {dem::dims::time}, {}, nullptr, true});
  uses["output"]["every"].push_back({dem::KeyKind::boolean, {}, {}, false, false});
  uses["numerics"]["max_step_fraction"].push_back({dem::KeyKind::number, {}, {}, 0.5, false});
  uses["contact"].erase("cohesion");
  const std::vector<std::string> p = table_problems(uses);
  const auto has = [&](const std::string& text) {
    return std::any_of(p.begin(), p.end(), [&](const std::string& s) { return s.find(text) != std::string::npos; });
  };
  CHECK(has("numerics.dt_typo: accepted by the reader, not in the key table"));
  CHECK(has("output.every: the reader reads a boolean"));
  CHECK(has("numerics.max_step_fraction: default: the table says 0.25, the reader applies 0.5"));
  CHECK(has("contact.cohesion: in the key table, never read by the reader"));
  CHECK(p.size() == 4);
}

TEST_CASE("key table: table_kind drops array indices") {
  CHECK(dem::table_kind("contact.3.kn_from_elastic") == "contact.kn_from_elastic");
  CHECK(dem::table_kind("") == "");
  CHECK(dem::table_kind("element.12.preload") == "element.preload");
}

TEST_CASE("case schema: every table and key of the key table is in it") {
  const nlohmann::ordered_json s = dem::case_schema();
  CHECK(s["$schema"] == "http://json-schema.org/draft-07/schema#");
  CHECK(s["additionalProperties"] == false);
  CHECK(s["properties"]["numerics"]["properties"]["dt"]["x-unit-si"] == "s");
  CHECK(s["properties"]["contact"]["items"]["properties"]["law"]["enum"] == nlohmann::ordered_json({"linear", "face"}));
  CHECK(s["properties"]["numerics"]["required"] == nlohmann::ordered_json({"dt", "duration"}));
  std::size_t keys = 0;
  for (const dem::TableSpec& t : dem::case_key_tables()) keys += t.keys.size();
  CHECK(s.dump().find("\"kn_from_elastic\"") != std::string::npos);
  CHECK(keys > 150);
}
