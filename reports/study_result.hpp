// Reading the studies' result.json files, and tolerant access to their fields: a missing or
// mistyped field reads as absent, so one odd file cannot stop the report.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace report {

struct StudyResult {
  std::string folder;          // study folder name (unique; used for anchors and file names)
  std::filesystem::path path;  // the result.json
  nlohmann::json result;       // parsed content (an object when readable)
  std::string read_error;      // empty when readable
  bool readable() const { return read_error.empty(); }
};

// Every <studies_dir>/*/result.json, sorted by folder name; folders without one are skipped, unless
// they hold running.json (a study started and not finished): then read_error says so.
// Unparsable files are returned with read_error set (and a warning on stderr).
std::vector<StudyResult> read_study_results(const std::filesystem::path& studies_dir);

// Tolerant field access (j may be any JSON value).
std::string text_field(const nlohmann::json& j, const char* key);
std::optional<double> number_field(const nlohmann::json& j, const char* key);
std::optional<bool> bool_field(const nlohmann::json& j, const char* key);
const nlohmann::json& array_field(const nlohmann::json& j, const char* key);   // [] if absent
const nlohmann::json& object_field(const nlohmann::json& j, const char* key);  // {} if absent
std::vector<std::optional<double>> number_array(const nlohmann::json& j, const char* key);

// "PASS", "FAIL" or "n/a" for a check (its "passed" field).
std::string check_status(const nlohmann::json& check);
// A study's status, recomputed from its checks: "PASS" (at least one check, all passed), "FAIL", "BROKEN"
// (no list of checks, no check, a check without a boolean "passed", or the file's own "passed"
// disagreeing with its checks) or "UNREADABLE" (not JSON, not an object, nested deeper than 64, not a file).
std::string study_status(const StudyResult& study);
std::string broken_reason(const StudyResult& study);  // why BROKEN, in words ("" otherwise)

}  // namespace report
