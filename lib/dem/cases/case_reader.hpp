#pragma once
// A checked view of one TOML table: typed getters with units, and at the end a check that no unknown
// key was given ("did you mean …" for a near miss). Every TOML file the project reads goes through it
// (cases, study files, sensitivity files, refinement tables). Every error names
// file:line: key: what was expected. Each getter records what it read in the thread's KeyLog, if one is
// recording (key_log.hpp: the check that the case schema matches the reader).
#include <filesystem>
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
  /// `help`: where the keys of this kind of file are documented (named by an unknown-key error).
  TableReader(const toml::table& t, std::string path, std::string file, std::string help = "cases/README.md");

  bool has(const std::string& key) const {
    known_.insert(key);  // a key the reader knows: a candidate for "did you mean"
    return t_.contains(key);
  }
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
  /// A finite plain number in [lo, hi] (open at an end where `open_lo` / `open_hi`).
  double number_in(const std::string& key, double lo, double hi, double fallback, bool open_lo = false,
                   bool open_hi = false) const;
  /// A finite number or a string with any unit ("2.5 mm"), in SI, with the dimension it was given in
  /// (a bare number is dimensionless).
  Quantity any_quantity(const std::string& key) const;
  std::optional<Quantity> optional_any_quantity(const std::string& key) const;
  /// The same for an element of an array read through `key`.
  Quantity any_quantity_of(const toml::node& n, const std::string& key) const;
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
  void mark(const std::string& key) const;  // read by hand
  /// A value inside an array of `key` (number in SI, or string with a unit), errors named by `key`.
  double quantity_of(const toml::node& n, const std::string& key, Dimension dim) const;

  /// Throws for any key that was not read, naming the nearest known key ("did you mean …").
  void finish() const;
  /// A table of `key` = number or quantity pairs (e.g. reference arguments { zeta = 0.3 }), in SI.
  std::map<std::string, double> quantity_table(const std::string& key) const;
  /// An error about a node inside this table (an array element), at that node's line.
  [[noreturn]] void fail_at(const toml::node& n, const std::string& key, const std::string& what) const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  [[noreturn]] void fail_here(const std::string& what) const;  // about the table itself
  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& file() const { return file_; }

 private:
  const toml::node& need(const std::string& key) const;
  double to_quantity(const toml::node& n, const std::string& key, Dimension dim) const;

  const toml::table& t_;
  std::string path_, file_, help_;
  mutable std::set<std::string> used_, known_;
};

/// Parses a TOML file: "file not found: <path>" (with `from`, e.g. "(from study.toml:9)", when
/// another file named it) and "file:line: syntax: …" as CaseError.
toml::table parse_toml_file(const std::filesystem::path& path, const std::string& from = "");

/// Parses TOML text as if it were the file `path` (the same "file:line: syntax: …" errors, every node's
/// source names `path`); the file system is not touched (the fuzz targets read from memory).
toml::table parse_toml_text(std::string_view text, const std::filesystem::path& path);

/// The word of `known` nearest to `word` (edit distance ≤ max(2, |word|/3)), or "" if none is near.
std::string nearest_word(const std::string& word, const std::vector<std::string>& known);

}  // namespace dem
