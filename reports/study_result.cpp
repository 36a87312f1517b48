// Reading result.json files and tolerant field access.
#include "study_result.hpp"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fmt/format.h>

namespace report {

namespace {

constexpr int kMaxDepth = 64;  // result.json nests 6 levels; parsing and printing recurse per level

/// The deepest nesting of [ and { in a JSON text (outside strings).
int nesting_depth(const std::string& text) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (in_string) {
      if (c == '\\') ++k;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

}  // namespace

std::vector<StudyResult> read_study_results(const std::filesystem::path& studies_dir) {
  std::vector<StudyResult> studies;
  for (const auto& entry : std::filesystem::directory_iterator(studies_dir)) {
    if (!entry.is_directory()) continue;
    const auto path = entry.path() / "result.json";
    StudyResult study;
    study.folder = entry.path().filename().string();
    study.path = path;
    if (std::filesystem::exists(path) && !std::filesystem::is_regular_file(path)) {
      study.read_error = "result.json is not a file";
      std::cerr << "report: warning: " << path.string() << ": " << study.read_error << "\n";
      studies.push_back(std::move(study));
      continue;
    }
    if (!std::filesystem::is_regular_file(path)) {
      // A study that was started but has no result (killed, or still running) is listed, never
      // replaced by an older result: `dem2d study` removes result.json before it starts.
      if (std::filesystem::is_regular_file(entry.path() / "running.json")) {
        study.read_error = "no result.json: the study was interrupted or is still running";
        try {  // how it ended, if it says ("failed" or "interrupted", with the message)
          std::ifstream mark(entry.path() / "running.json");
          const nlohmann::json j = nlohmann::json::parse(mark);
          const std::string status = j.value("status", "running");
          if (status == "failed" || status == "interrupted")
            study.read_error = "no result.json: the study " + status + ": " + j.value("message", std::string("(no message)"));
        } catch (const std::exception&) {
        }
        std::cerr << "report: warning: " << entry.path().string() << ": " << study.read_error << "\n";
        studies.push_back(std::move(study));
      }
      continue;
    }
    std::ifstream in(path, std::ios::binary);
    std::stringstream buffer;
    if (in) buffer << in.rdbuf();
    if (!in) {
      study.read_error = "cannot open the file";
    } else {
      try {
        if (nesting_depth(buffer.str()) > kMaxDepth)  // a deep file would overflow the stack later
          throw std::runtime_error(fmt::format("nested deeper than {} levels", kMaxDepth));
        study.result = nlohmann::json::parse(buffer.str());
        if (!study.result.is_object()) study.read_error = "top level is not a JSON object";
      } catch (const std::exception& e) {
        study.read_error = e.what();
      }
    }
    if (!study.readable())
      std::cerr << "report: warning: unreadable " << path.string() << ": " << study.read_error
                << "\n";
    else if (const std::string why = broken_reason(study); !why.empty())
      std::cerr << "report: warning: BROKEN " << path.string() << ": " << why << "\n";
    studies.push_back(std::move(study));
  }
  std::sort(studies.begin(), studies.end(),
            [](const StudyResult& a, const StudyResult& b) { return a.folder < b.folder; });
  return studies;
}

std::string text_field(const nlohmann::json& j, const char* key) {
  if (!j.is_object() || !j.contains(key)) return {};
  const auto& v = j.at(key);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_null()) return {};
  return v.dump();
}

std::optional<double> number_field(const nlohmann::json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_number()) return std::nullopt;
  return j.at(key).get<double>();
}

std::optional<bool> bool_field(const nlohmann::json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_boolean()) return std::nullopt;
  return j.at(key).get<bool>();
}

const nlohmann::json& array_field(const nlohmann::json& j, const char* key) {
  static const nlohmann::json empty = nlohmann::json::array();
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_array()) return empty;
  return j.at(key);
}

const nlohmann::json& object_field(const nlohmann::json& j, const char* key) {
  static const nlohmann::json empty = nlohmann::json::object();
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_object()) return empty;
  return j.at(key);
}

std::vector<std::optional<double>> number_array(const nlohmann::json& j, const char* key) {
  std::vector<std::optional<double>> values;
  for (const auto& v : array_field(j, key))
    values.push_back(v.is_number() ? std::optional<double>(v.get<double>()) : std::nullopt);
  return values;
}

std::string check_status(const nlohmann::json& check) {
  const auto passed = bool_field(check, "passed");
  if (!passed) return "n/a";
  return *passed ? "PASS" : "FAIL";
}

std::string study_status(const StudyResult& study) {
  if (!study.readable()) return "UNREADABLE";
  // Recomputed from the checks, never taken from the file's own verdict: a study passes when it has
  // checks and every one passed. Anything else that does not add up is BROKEN.
  const nlohmann::json& r = study.result;
  if (!r.contains("checks") || !r.at("checks").is_array() || r.at("checks").empty()) return "BROKEN";
  bool all = true;
  for (const auto& check : r.at("checks")) {
    const auto passed = bool_field(check, "passed");
    if (!passed) return "BROKEN";
    all = all && *passed;
  }
  if (const auto passed = bool_field(r, "passed"); !passed || *passed != all) return "BROKEN";
  return all ? "PASS" : "FAIL";
}

std::string broken_reason(const StudyResult& study) {
  if (!study.readable() || study_status(study) != "BROKEN") return {};
  const nlohmann::json& r = study.result;
  if (!r.contains("checks") || !r.at("checks").is_array()) return "\"checks\" is not a list of checks";
  if (r.at("checks").empty()) return "no checks";
  for (const auto& check : r.at("checks"))
    if (!bool_field(check, "passed")) return "a check without a true/false \"passed\"";
  return "\"passed\" disagrees with its checks";
}

}  // namespace report
