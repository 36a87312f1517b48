// Reading result.json files and tolerant field access.
#include "study_result.hpp"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>

namespace report {

std::vector<StudyResult> read_study_results(const std::filesystem::path& studies_dir) {
  std::vector<StudyResult> studies;
  for (const auto& entry : std::filesystem::directory_iterator(studies_dir)) {
    if (!entry.is_directory()) continue;
    const auto path = entry.path() / "result.json";
    StudyResult study;
    study.folder = entry.path().filename().string();
    study.path = path;
    if (!std::filesystem::is_regular_file(path)) {
      // A study that was started but has no result (killed, or still running) is listed, never
      // replaced by an older result: `dem2d study` removes result.json before it starts.
      if (std::filesystem::is_regular_file(entry.path() / "running.json")) {
        study.read_error = "no result.json: the study was interrupted or is still running";
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
        study.result = nlohmann::json::parse(buffer.str());
        if (!study.result.is_object()) study.read_error = "top level is not a JSON object";
      } catch (const nlohmann::json::exception& e) {
        study.read_error = e.what();
      }
    }
    if (!study.readable())
      std::cerr << "report: warning: unreadable " << path.string() << ": " << study.read_error
                << "\n";
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
  if (const auto passed = bool_field(study.result, "passed")) return *passed ? "PASS" : "FAIL";
  bool any_passed = false;
  for (const auto& check : array_field(study.result, "checks")) {
    const auto status = check_status(check);
    if (status == "FAIL") return "FAIL";
    any_passed |= status == "PASS";
  }
  return any_passed ? "PASS" : "n/a";
}

}  // namespace report
