#include "sensitivity_overview.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <tuple>

#include "study_result.hpp"
#include "text_format.hpp"

namespace report {

namespace {

struct Entry {
  std::string parameter, value, interval;
  double x = NAN, low = NAN, high = NAN;  // the value and its interval "[low, high]" (NaN: none)
};

double parse(const nlohmann::json& cell) {
  if (cell.is_number()) return cell.get<double>();
  if (!cell.is_string()) return NAN;
  const std::string s = cell.get<std::string>();
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  return end != s.c_str() ? x : NAN;
}

std::string text(const nlohmann::json& cell) {
  return cell.is_string() ? cell.get<std::string>() : cell.is_null() ? std::string() : cell.dump();
}

/// "[a, b]" → a, b (NaN if not of that form).
std::pair<double, double> bounds(const std::string& interval) {
  double a = NAN, b = NAN;
  if (interval.size() > 2 && interval.front() == '[') {
    char* end = nullptr;
    a = std::strtod(interval.c_str() + 1, &end);
    if (end == interval.c_str() + 1) a = NAN;
    if (const auto comma = interval.find(','); comma != std::string::npos) {
      const char* p = interval.c_str() + comma + 1;
      b = std::strtod(p, &end);
      if (end == p) b = NAN;
    }
  }
  return {a, b};
}

/// The parameters that cannot be told apart from `pick` by its interval: each other entry whose
/// interval reaches into pick's (most: other.high >= pick.low; least: other.low <= pick.high).
std::string overlapping(const std::vector<Entry>& entries, const Entry& pick, bool most) {
  if (!std::isfinite(pick.low) || !std::isfinite(pick.high)) return {};
  std::string names;
  for (const auto& e : entries) {
    if (&e == &pick || !std::isfinite(e.x) || !std::isfinite(e.low) || !std::isfinite(e.high)) continue;
    if (most ? e.high >= pick.low : e.low <= pick.high) names += (names.empty() ? "" : ", ") + e.parameter;
  }
  return names.empty() ? std::string() : " (intervals overlap: " + names + ")";
}

bool starts(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

std::string count(const nlohmann::json& setup, const char* key) {
  if (const auto n = number_field(setup, key)) return std::to_string(static_cast<long long>(*n));
  return std::string(missing_value);
}

}  // namespace

std::vector<SensitivityOverviewRow> sensitivity_overview_rows(const ReportContent& content) {
  std::vector<SensitivityOverviewRow> out;
  for (const auto& study : content.studies) {
    const auto& result = study.source.result;
    if (text_field(result, "kind") != "sensitivity") continue;
    // Per output: the entries of the strongest measure (rank 0 Sobol', 1 Morris, 2 one-at-a-time).
    std::vector<std::string> outputs;
    std::map<std::string, std::pair<int, std::vector<Entry>>> by_output;
    std::map<std::string, std::string> noise;  // output → "fraction [low, high]" (the first row: Sobol' before Morris)
    for (const auto& table : array_field(result, "tables")) {
      const std::string title = text_field(table, "title");
      if (starts(title, "Run-to-run noise"))
        for (const auto& row : array_field(table, "rows"))
          if (row.is_array() && row.size() > 8) noise.try_emplace(text(row[0]), text(row[7]) + " " + text(row[8]));
      int rank = -1;
      std::size_t value_col = 0, interval_col = 0;
      if (starts(title, "Sobol' indices")) rank = 0, value_col = 4, interval_col = 5;
      else if (starts(title, "Morris elementary effects")) rank = 1, value_col = 2;
      else if (starts(title, "One-at-a-time sweeps")) rank = 2, value_col = 5;
      if (rank == 1 && table.contains("columns") && table["columns"].is_array() && table["columns"].size() > 3 &&
          table["columns"][3].is_string() && table["columns"][3].get<std::string>().find("interval") != std::string::npos)
        interval_col = 3;  // μ*'s bootstrap interval (results written before it had none)
      if (rank < 0) continue;
      for (const auto& row : array_field(table, "rows")) {
        if (!row.is_array() || row.size() <= std::max(value_col, interval_col)) continue;
        const std::string output = text(row[0]);
        if (rank == 0 && starts(text(row[1]), "dummy (inert")) continue;  // the noise floor, not a parameter
        auto [it, fresh] = by_output.try_emplace(output, rank, std::vector<Entry>{});
        if (fresh) outputs.push_back(output);
        if (rank > it->second.first) continue;
        if (rank < it->second.first) it->second = {rank, {}};
        Entry e{text(row[1]), text(row[value_col]), interval_col ? text(row[interval_col]) : std::string(), parse(row[value_col])};
        if (rank == 2) e.x = std::abs(e.x);
        std::tie(e.low, e.high) = bounds(e.interval);
        it->second.second.push_back(e);
      }
    }
    const auto& setup = object_field(result, "setup");
    for (const auto& output : outputs) {
      const auto& [rank, entries] = by_output[output];
      SensitivityOverviewRow r;
      r.anchor = study_anchor(study.source);
      r.study = study_name(study.source);
      r.output = output;
      r.measure = rank == 0 ? "S_T (Jansen)" : rank == 1 ? "μ* (Morris)" : "range (one-at-a-time)";
      const Entry* most = nullptr;
      const Entry* least = nullptr;
      for (const auto& e : entries) {
        if (!std::isfinite(e.x)) continue;
        if (!most || e.x > most->x) most = &e;
        if (!least || e.x < least->x) least = &e;
      }
      const std::string none(missing_value);
      r.most = most ? most->parameter + overlapping(entries, *most, true) : none;
      r.most_value = most ? most->value : none;
      r.most_interval = most && !most->interval.empty() ? most->interval : none;
      r.least = least ? least->parameter + overlapping(entries, *least, false) : none;
      r.least_value = least ? least->value : none;
      r.least_interval = least && !least->interval.empty() ? least->interval : none;
      r.runs = count(setup, "runs");
      r.failed = count(setup, "failed runs");
      const auto nz = noise.find(output);
      r.noise = nz != noise.end() ? nz->second : std::string(missing_value);
      out.push_back(r);
    }
  }
  return out;
}

}  // namespace report
