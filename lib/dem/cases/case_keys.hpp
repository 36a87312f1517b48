#pragma once
// The key table of the case format: every table a case file may hold, every key of each, with its type,
// the dimension of its quantity, its allowed words, its default and a description (cases/README.md says
// the same in prose). `dem2d schema` turns it into a JSON Schema (case_schema.hpp). It is checked
// against what the reader itself reads (key_log.hpp) by tests/lib/cases/case_keys_tests.cpp: a key the
// reader accepts that is missing here, a key here that the reader never reads, or a type, dimension,
// word list or default that differs fails that test.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dem/cases/units.hpp"

namespace dem {

enum class SpecKind {
  quantity,         // a number (SI) or a string with a unit of one of `dims` (none: any unit)
  number,           // a plain number
  integer,          // a whole number in [min, max]
  boolean,
  string,
  choice,           // one of `choices`
  strings,          // an array of strings
  vector,           // [x, y], quantities of `dims`
  vector_or_table,  // [x, y], or the table `table` ({ magnitude, direction })
  table,            // the nested table `table`
  tables,           // an array of tables `table` ([[name]])
  interval,         // a whole number of steps, or a time ("1 ms")
  quantities,       // an array of quantities of `dims` (`length` of them, 0: any number)
  vectors,          // an array of [x, y] of `dims`
  numbers           // an array of plain numbers
};

struct KeySpec {
  std::string key;
  SpecKind kind = SpecKind::string;
  std::string description;
  std::vector<Dimension> dims;
  std::vector<std::string> choices;
  nlohmann::json fallback;  // the default as a case writes it; null: none, or one the description states
  bool required = false;    // needed in every table of this kind
  std::optional<std::int64_t> min, max;  // integer
  int length = 0;           // strings, quantities, vectors: exactly this many (0: any)
  std::string table;        // table, tables, vector_or_table: the path of the key table
};

struct TableSpec {
  std::string path;  // "" the top level; "contact"; "contact.kn_from_elastic" (array indices left out)
  std::string description;
  std::vector<KeySpec> keys;
  const KeySpec* find(const std::string& key) const;
};

/// Every table of the case format, the top level first.
const std::vector<TableSpec>& case_key_tables();
/// The table at `path`, or nullptr.
const TableSpec* find_case_table(const std::string& path);

}  // namespace dem
