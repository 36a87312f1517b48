#pragma once
// A checked view of one TOML table of a case file: typed getters with units, and at the end a check
// that no unknown key was given. Every error names file:line: key: what was expected.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "dem/cases/case_file.hpp"
#include "dem/cases/units.hpp"
#include "dem/core/vec2.hpp"

namespace dem {

/// "file:line" of a node (an override names itself: "--set key=value").
std::string where(const toml::node& n, const std::string& fallback_file);

class TableReader {
 public:
  TableReader(const toml::table& t, std::string path, std::string file);

  bool has(const std::string& key) const { return t_.contains(key); }
  const toml::node* node(const std::string& key) const { return t_.get(key); }

  double quantity(const std::string& key, Dimension dim) const;
  double quantity(const std::string& key, Dimension dim, double fallback) const;
  std::optional<double> optional_quantity(const std::string& key, Dimension dim) const;
  /// A quantity that may be given in one of two dimensions (e.g. N/m or Pa per unit thickness).
  /// Returns the value and which dimension was given.
  std::pair<double, Dimension> quantity_either(const std::string& key, Dimension a, Dimension b) const;
  Vec2 vector(const std::string& key, Dimension dim) const;
  Vec2 vector(const std::string& key, Dimension dim, Vec2 fallback) const;
  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi) const;
  std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi, std::int64_t fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  /// One of the allowed words; the error lists them.
  std::string choice(const std::string& key, const std::vector<std::string>& allowed,
                     const std::string& fallback) const;
  std::vector<std::string> strings(const std::string& key) const;
  const toml::table* table(const std::string& key) const;
  void mark(const std::string& key) const { used_.insert(key); }  // read by hand
  /// A value inside an array of `key` (number in SI, or string with a unit), errors named by `key`.
  double quantity_of(const toml::node& n, const std::string& key, Dimension dim) const { return to_quantity(n, key, dim); }

  /// Throws for any key that was not read.
  void finish() const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  [[noreturn]] void fail_here(const std::string& what) const;  // about the table itself
  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& file() const { return file_; }

 private:
  const toml::node& need(const std::string& key) const;
  double to_quantity(const toml::node& n, const std::string& key, Dimension dim) const;

  const toml::table& t_;
  std::string path_, file_;
  mutable std::set<std::string> used_;
};

}  // namespace dem
