// Counting outcomes and assembling the header of the report.
#include "report_content.hpp"

#include <algorithm>
#include <set>

#include "text_format.hpp"

namespace report {

Counts count_outcomes(const ReportContent& content) {
  Counts counts;
  for (const auto& study : content.studies) {
    const auto status = study_status(study.source);
    if (status == "PASS")
      ++counts.studies_passed;
    else if (status == "FAIL")
      ++counts.studies_failed;
    else if (status == "UNREADABLE")
      ++counts.studies_unreadable;
    else
      ++counts.studies_other;
    if (!study.source.readable()) continue;
    for (const auto& check : array_field(study.source.result, "checks")) {
      const auto check_result = check_status(check);
      if (check_result == "PASS")
        ++counts.checks_passed;
      else if (check_result == "FAIL")
        ++counts.checks_failed;
      else
        ++counts.checks_other;
    }
  }
  return counts;
}

namespace {

std::set<std::string> study_values(const std::vector<StudyResult>& studies, const char* key) {
  std::set<std::string> values;
  for (const auto& study : studies) {
    const auto value = text_field(object_field(study.result, "provenance"), key);
    if (!value.empty()) values.insert(value);
  }
  return values;
}

std::string join(const std::set<std::string>& values) {
  std::string out;
  for (const auto& v : values) out += (out.empty() ? "" : ", ") + v;
  return out;
}

// The report's own value if given (noting differing study values), else the studies' values.
std::string describe(const nlohmann::json& provenance, const std::vector<StudyResult>& studies,
                     const char* key) {
  const auto own = text_field(provenance, key);
  const auto theirs = study_values(studies, key);
  if (own.empty()) return theirs.empty() ? "unknown" : join(theirs);
  if (theirs.empty() || (theirs.size() == 1 && *theirs.begin() == own)) return own;
  return own + " (studies: " + join(theirs) + ")";
}

}  // namespace

std::vector<HeaderField> header_fields(const nlohmann::json& provenance,
                                       const std::vector<StudyResult>& studies,
                                       const std::filesystem::path& studies_dir) {
  std::vector<HeaderField> fields;
  fields.push_back({"Code version", describe(provenance, studies, "code_version")});
  fields.push_back({"Build type", describe(provenance, studies, "build_type")});
  fields.push_back({"Machine", describe(provenance, studies, "machine")});
  const auto date = text_field(provenance, "date");
  fields.push_back({"Report generated", date.empty() ? utc_now_iso8601() : date});
  const auto run_dates = study_values(studies, "date");
  if (!run_dates.empty())
    fields.push_back({"Studies run", run_dates.size() == 1
                                         ? *run_dates.begin()
                                         : *run_dates.begin() + " \u2013 " + *run_dates.rbegin()});
  fields.push_back({"Studies folder", studies_dir.string()});
  if (provenance.is_object())
    for (const auto& [key, value] : provenance.items())
      if (key != "code_version" && key != "build_type" && key != "machine" && key != "date")
        fields.push_back({key, format_value(value)});
  return fields;
}

std::string study_anchor(const StudyResult& study) { return "study-" + slug(study.folder); }

std::string study_name(const StudyResult& study) {
  const auto name = text_field(study.result, "study");
  return name.empty() ? study.folder : name;
}

CheckRow check_row(const nlohmann::json& check) {
  CheckRow row;
  row.quantity = text_field(check, "quantity");
  row.reference = format_number(number_field(check, "reference"));
  row.dem = format_number(number_field(check, "dem"));
  row.error = format_number(number_field(check, "error"));
  const auto kind = text_field(check, "error_kind");
  if (number_field(check, "error") && !kind.empty()) row.error += " (" + kind + ")";
  row.tolerance = format_number(number_field(check, "tolerance"));
  row.tolerance_reason = text_field(check, "tolerance_reason");
  row.order =
      format_order(number_field(check, "observed_order"), number_field(check, "expected_order"),
                   number_field(check, "order_band"));
  row.status = check_status(check);
  row.note = text_field(check, "note");
  return row;
}

std::vector<HeaderField> setup_fields(const nlohmann::json& result) {
  std::vector<HeaderField> fields;
  auto add = [&](const char* label, const std::string& value) {
    if (!value.empty()) fields.push_back({label, value});
  };
  add("Kind", text_field(result, "kind"));
  add("Case", text_field(result, "case"));
  add("Parameter", text_field(result, "parameter"));
  for (const auto& [key, value] : object_field(result, "setup").items())
    fields.push_back({key, format_value(value)});
  const auto& overrides = array_field(object_field(result, "provenance"), "overrides");
  if (!overrides.empty()) add("Overrides", format_value(overrides));
  return fields;
}

std::vector<std::vector<std::string>> series_level_rows(const nlohmann::json& series) {
  const auto h = number_array(series, "h");
  const auto value = number_array(series, "value");
  const auto error = number_array(series, "error");
  const auto order = number_array(series, "observed_order");
  auto at = [](const std::vector<std::optional<double>>& v, std::size_t k) {
    return k < v.size() ? format_number(v[k]) : std::string(missing_value);
  };
  std::vector<std::vector<std::string>> rows;
  for (std::size_t k = 0; k < h.size(); ++k)
    rows.push_back({std::to_string(k), at(h, k), at(value, k), at(error, k), at(order, k)});
  return rows;
}

std::string series_summary(const nlohmann::json& series) {
  std::string out = "fitted order " + format_number(number_field(series, "fitted_order"));
  if (const auto expected = number_field(series, "expected_order"))
    out += " (expected " + format_number(*expected) + ")";
  const auto reference = number_field(series, "reference");
  out += reference ? "; reference " + format_number(*reference)
                   : std::string("; no reference: errors against Richardson");
  out += "; Richardson " + format_number(number_field(series, "richardson"));
  out += "; GCI fine " + format_number(number_field(series, "gci_fine"));
  out += "; asymptotic ratio " + format_number(number_field(series, "asymptotic_ratio"));
  if (const auto asymptotic = bool_field(series, "asymptotic"))
    out += *asymptotic ? " (asymptotic)" : " (not asymptotic)";
  return out;
}

TableData table_data(const nlohmann::json& table) {
  TableData data;
  data.title = text_field(table, "title");
  if (table.is_object() && table.contains("preformatted")) {
    data.preformatted = text_field(table, "preformatted");
    return data;
  }
  for (const auto& c : array_field(table, "columns")) data.columns.push_back(format_value(c));
  for (const auto& r : array_field(table, "rows")) {
    std::vector<std::string> row;
    if (r.is_array())
      for (const auto& c : r) row.push_back(format_value(c));
    else
      row.push_back(format_value(r));
    if (row.size() > data.columns.size()) data.columns.resize(row.size());
    data.rows.push_back(std::move(row));
  }
  return data;
}

std::string status_class(const std::string& status) {
  if (status == "PASS") return "pass";
  if (status == "FAIL") return "fail";
  if (status == "UNREADABLE") return "unreadable";
  return "na";
}

}  // namespace report
