#include "dem/cases/case_schema.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "dem/cases/case_keys.hpp"

namespace dem {

namespace {

using ojson = nlohmann::ordered_json;

/// A regex alternative matching exactly `s` (the unit symbols are letters and µ μ °: nothing to escape).
std::string unit_alternatives() {
  std::vector<std::string> units = unit_symbols();
  std::sort(units.begin(), units.end(), [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
  std::string out;
  for (const auto& u : units) out += (out.empty() ? "" : "|") + u;
  return out;
}

std::string dims_text(const std::vector<Dimension>& ds) {
  if (ds.empty()) return "a number or a string with any unit";
  std::string out;
  for (const Dimension& dim : ds)
    out += fmt::format("{}{} [SI: {}]", out.empty() ? "" : ", or ", describe(dim), to_string(dim));
  return out;
}

/// A quantity: a reference to one of the two definitions (allOf: draft-07 ignores the siblings of a bare $ref,
/// and the key's description sits beside it).
ojson quantity_schema(const std::vector<Dimension>& ds) {
  const bool angle = ds.size() == 1 && ds[0] == dims::angle;
  return {{"allOf", ojson::array({{{"$ref", angle ? "#/definitions/angle" : "#/definitions/quantity"}}})}};
}

ojson definitions() {
  return {{"quantity", {{"description", "a number (SI) or a string \"number unit\" (\"25 mm\", \"750 kgf/cm^2\", \"1e-6 s\")"},
                        {"anyOf", ojson::array({{{"type", "number"}}, {{"type", "string"}, {"pattern", quantity_pattern(false)}}})}}},
          {"angle", {{"description", "an angle with its unit: \"38 deg\", \"0.66 rad\""},
                     {"type", "string"},
                     {"pattern", quantity_pattern(true)}}}};
}

ojson table_schema(const TableSpec& t);

ojson nested_table(const std::string& path) {
  const TableSpec* t = find_case_table(path);
  if (!t) throw std::logic_error("case schema: no key table " + path);
  return table_schema(*t);
}

ojson value_schema(const KeySpec& k) {
  const auto array_of = [&](ojson items, int length) {
    ojson a{{"type", "array"}, {"items", std::move(items)}};
    if (length > 0) a["minItems"] = a["maxItems"] = length;
    return a;
  };
  switch (k.kind) {
    case SpecKind::quantity: return quantity_schema(k.dims);
    case SpecKind::number: return quantity_schema({dims::dimensionless});
    case SpecKind::integer: {
      ojson s{{"type", "integer"}};
      if (k.min) s["minimum"] = *k.min;
      if (k.max) s["maximum"] = *k.max;
      return s;
    }
    case SpecKind::boolean: return {{"type", "boolean"}};
    case SpecKind::string: return {{"type", "string"}};
    case SpecKind::choice: return {{"type", "string"}, {"enum", k.choices}};
    case SpecKind::strings: return array_of({{"type", "string"}}, k.length);
    case SpecKind::vector: return array_of(quantity_schema(k.dims), 2);
    case SpecKind::vector_or_table: return {{"anyOf", ojson::array({array_of(quantity_schema(k.dims), 2), nested_table(k.table)})}};
    case SpecKind::table: return nested_table(k.table);
    case SpecKind::tables: return array_of(nested_table(k.table), 0);
    case SpecKind::interval:
      return {{"anyOf", ojson::array({{{"type", "integer"}, {"minimum", 0}}, {{"$ref", "#/definitions/quantity"}}})}};
    case SpecKind::quantities: return array_of(quantity_schema(k.dims), k.length);
    case SpecKind::vectors: return array_of(array_of(quantity_schema(k.dims), 2), k.length);
    case SpecKind::numbers: return array_of({{"type", "number"}}, k.length);
  }
  return {};
}

std::string key_description(const KeySpec& k) {
  std::string d = k.description;
  const bool quantity = k.kind == SpecKind::quantity || k.kind == SpecKind::vector || k.kind == SpecKind::vector_or_table ||
                        k.kind == SpecKind::quantities || k.kind == SpecKind::vectors;
  if (quantity) d += fmt::format(" — {}", dims_text(k.dims));
  if (k.kind == SpecKind::interval) d += " — steps, or a time [SI: s] that is a whole number of steps";
  if (!k.fallback.is_null()) d += fmt::format(" (default {})", k.fallback.dump());
  return d;
}

ojson table_schema(const TableSpec& t) {
  ojson props = ojson::object();
  ojson required = ojson::array();
  for (const KeySpec& k : t.keys) {
    ojson v = value_schema(k);
    ojson s{{"description", key_description(k)}};
    if (k.kind == SpecKind::table || k.kind == SpecKind::tables) s = {{"description", k.description}};
    for (auto& [name, value] : v.items()) s[name] = value;
    if (!k.fallback.is_null()) s["default"] = k.fallback;
    if (k.kind == SpecKind::quantity && !k.dims.empty()) s["x-unit-si"] = to_string(k.dims.front());
    props[k.key] = std::move(s);
    if (k.required) required.push_back(k.key);
  }
  ojson out{{"type", "object"}};
  if (t.path.find('.') != std::string::npos || !t.path.empty()) out["description"] = t.description;
  out["properties"] = std::move(props);
  if (!required.empty()) out["required"] = std::move(required);
  out["additionalProperties"] = false;
  // a table that takes polygons ([[element]], [[lattice]]): the radius unless shape = "polygon"
  const KeySpec* shape = t.find("shape");
  if (shape && t.find("radius") && !t.find("radius")->required &&
      std::find(shape->choices.begin(), shape->choices.end(), "polygon") != shape->choices.end() &&
      (t.path == "element" || t.path == "lattice")) {
    out["if"] = {{"properties", {{"shape", {{"const", "polygon"}}}}}, {"required", ojson::array({"shape"})}};
    out["else"] = {{"required", ojson::array({"radius"})}};
  }
  return out;
}

}  // namespace

std::string quantity_pattern(bool angle) {
  const std::string number = R"([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)";
  if (angle) return R"(^\s*)" + number + R"(\s*(?:deg|rad|°)\s*$)";
  const std::string factor = "(?:" + unit_alternatives() + R"()(?:\^[+-]?\d+|⁻?[¹²³])?)";
  return R"(^\s*)" + number + R"((?:\s*(?:1?/)?\s*)" + factor + R"((?:[\s*·⋅/]+)" + factor + R"()*)?\s*$)";
}

ojson case_schema() {
  const TableSpec& top = case_key_tables().front();
  ojson s{{"$schema", "http://json-schema.org/draft-07/schema#"},
          {"title", "dem2d case file"},
          {"description", top.description + " Made by `dem2d schema` from the reader's key table (lib/dem/cases/case_keys.hpp)."}};
  const ojson body = table_schema(top);  // a named object: items() does not keep a temporary alive
  for (const auto& [name, value] : body.items()) s[name] = value;
  s["definitions"] = definitions();
  return s;
}

}  // namespace dem
