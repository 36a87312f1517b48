#pragma once
// A JSON Schema (draft-07) of the case format, made from the key table (case_keys.hpp): every table and
// key, its type, the dimension and SI unit of a quantity, the allowed words, the default, a description.
// `dem2d schema` prints it; editors with a TOML language server (taplo, Even Better TOML) validate and
// complete cases with it (docs/running.md). A quantity is a number (SI) or a string "number unit" (the
// pattern checks the form and the unit symbols; the reader also checks the dimension); an angle must
// carry its unit. The reader stays the authority: it also refuses combinations (kn with kn_modulus),
// ranges and references (a material name that is not declared) that the schema does not express.
#include <string>

#include <nlohmann/json.hpp>

namespace dem {

nlohmann::ordered_json case_schema();

/// The regular expression (ECMA 262 / Python) of a quantity string: a number, optionally followed by a
/// unit expression of known symbols ("25 mm", "750 kgf/cm^2", "5 1/s"); `angle`: the unit is required
/// and is deg, rad or °.
std::string quantity_pattern(bool angle);

}  // namespace dem
