#pragma once
// What a TableReader reads, key by key: the kind of value, its dimension(s), its allowed words and the
// default it applies when the key is absent. While a KeyLog lives, every TableReader of this thread
// records each key it accepts into it. The case format's key table (case_keys.hpp) is checked against
// these records by a test, so that the schema made from the table (case_schema.hpp) cannot drift from
// the reader: a key the reader accepts that the table lacks, a key of the table the reader never reads,
// or a type, unit, word list or default that differs, fails that test.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dem/cases/units.hpp"

namespace dem {

enum class KeyKind {
  quantity,   // a number (SI) or a string with a unit, of one of `dims`
  element,    // an element of an array read by hand, a quantity of one of `dims`
  number,     // a plain number (or a string of one, "0.3")
  integer,    // a whole number
  boolean,
  string,
  choice,     // one of `choices`
  strings,    // an array of strings
  vector,     // [x, y] of quantities of `dims`
  table,      // a nested table
  other       // read by hand (TableReader::mark): no type recorded
};

const char* to_string(KeyKind k);

/// One read of one key.
struct KeyUse {
  KeyKind kind = KeyKind::other;
  std::vector<Dimension> dims;
  std::vector<std::string> choices;
  nlohmann::json fallback;  // the default applied when the key is absent (null: none given to the getter)
  bool required = false;    // read without a default: missing is an error
  std::optional<std::int64_t> min, max;  // integer: the range the reader accepts
};

/// Table path without array indices ("contact.kn_from_elastic", "" for the top level) → key → its reads.
using KeyUses = std::map<std::string, std::map<std::string, std::vector<KeyUse>>>;

/// "contact.3.kn_from_elastic" → "contact.kn_from_elastic".
std::string table_kind(const std::string& path);

class KeyLog {
 public:
  KeyLog();   // starts recording on this thread (one at a time)
  ~KeyLog();  // stops
  KeyLog(const KeyLog&) = delete;
  KeyLog& operator=(const KeyLog&) = delete;
  const KeyUses& uses() const { return uses_; }

  /// Records a read when a log is active and the call is not nested in another recorded read (choice()
  /// calls string(): only the outer call is recorded). Keep the guard alive for the whole read.
  class Guard {
   public:
    Guard(const std::string& path, const std::string& key, KeyUse use);
    ~Guard();
    Guard(const Guard&) = delete;
    Guard& operator=(const Guard&) = delete;
  };

 private:
  KeyUses uses_;
};

}  // namespace dem
