// Counting outcomes and assembling the header of the report.
#include "report_content.hpp"

#include <cstdio>

#include <fmt/format.h>
#include <sys/utsname.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

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
    else if (status == "UNREADABLE" || status == "BROKEN")
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
  for (auto& f : machine_fields())  // the app's provenance may name the compiler already
    if (!((f.label == "Compiler" && provenance.is_object() && provenance.contains("compiler")) ||
          (f.label == "Libraries" && provenance.is_object() && provenance.contains("libraries"))))
      fields.push_back(f);
  if (provenance.is_object())
    for (const auto& [key, value] : provenance.items())
      if (key != "code_version" && key != "build_type" && key != "machine" && key != "date") {
        std::string label = key;  // "report command", "wall_time_s" → "Report command", "Wall time s"
        for (char& c : label) c = c == '_' ? ' ' : c;
        if (!label.empty() && label[0] >= 'a' && label[0] <= 'z') label[0] = static_cast<char>(label[0] - 'a' + 'A');
        fields.push_back({label, format_value(value)});
      }
  return fields;
}

std::string study_anchor(const StudyResult& study) { return "study-" + slug(study.folder); }
std::string figure_anchor(const StudyResult& study, const std::string& figure_id) {
  return "figure-" + slug(study.folder) + "-" + slug(figure_id);
}
std::string snapshot_anchor_prefix(const StudyResult& study) { return "snapshot-" + slug(study.folder) + "-"; }
std::string snapshot_anchor(const StudyResult& study, const std::string& snapshot_id) {
  return snapshot_anchor_prefix(study) + slug(snapshot_id);
}

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
  row.asserts = check_assertion(check);
  return row;
}

std::string check_assertion(const nlohmann::json& check) {
  const auto expect = text_field(check, "expect");
  const bool rel = text_field(check, "error_kind") == "rel";
  const std::string err = rel ? "|DEM − reference| / |reference|" : "|DEM − reference|";
  std::string out;
  if (expect == "above") out = "DEM > reference + tol";
  else if (expect == "below") out = "DEM < reference − tol";
  else if (expect == "decreasing") out = "decreases from variant to variant, each step > tol (error = smallest step)";
  else if (expect == "increasing") out = "increases from variant to variant, each step > tol (error = smallest step)";
  else if (expect == "toward_reference")
    out = std::string("moves toward the reference from variant to variant: ") + err +
          " shrinks by > tol per step (error = smallest shrink)";
  else out = err + " ≤ tol";
  if (number_field(check, "expected_order")) out += "; observed order within expected ± band";
  return out;
}

std::vector<OverviewRow> overview_rows(const ReportContent& content) {
  std::vector<OverviewRow> rows;
  for (const auto& study : content.studies) {
    const auto& source = study.source;
    OverviewRow row;
    row.anchor = study_anchor(source);
    row.name = study_name(source);
    row.title = text_field(source.result, "title");
    if (row.title.empty()) row.title = row.name;
    row.status = study_status(source);
    for (const auto& check : array_field(source.result, "checks")) {
      const auto status = check_status(check);
      row.passed += status == "PASS";
      row.failed += status == "FAIL";
      if (const auto order = number_field(check, "observed_order")) {
        if (!row.orders.empty()) row.orders += ", ";
        row.orders += format_number(*order);
        if (const auto expected = number_field(check, "expected_order"))
          row.orders += " (" + format_number(*expected) + ")";
      }
    }
    row.wall_time = wall_time_words(object_field(source.result, "provenance"), true);
    rows.push_back(row);
  }
  return rows;
}

ReadmeParts readme_parts(const nlohmann::json& result) {
  ReadmeParts parts;
  std::string text = text_field(result, "readme");
  if (text.empty()) return parts;
  // Paragraphs separated by blank lines; a leading "# title" line is dropped.
  std::vector<std::string> paragraphs;
  std::string current;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const auto end = std::min(text.find('\n', pos), text.size());
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      if (!current.empty()) paragraphs.push_back(current);
      current.clear();
      continue;
    }
    if (line.rfind("# ", 0) == 0 && paragraphs.empty() && current.empty()) continue;
    current += (current.empty() ? "" : "\n") + line;
  }
  if (!current.empty()) paragraphs.push_back(current);
  if (paragraphs.empty()) return parts;
  parts.purpose = paragraphs.front();
  for (std::size_t k = 1; k < paragraphs.size(); ++k) parts.rest += (k > 1 ? "\n\n" : "") + paragraphs[k];
  return parts;
}

std::optional<HeaderField> cpu_field(const std::string& cpuinfo) {
  std::istringstream in(cpuinfo);
  int cores = 0;
  std::string model;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("processor", 0) == 0) ++cores;
    if (model.empty() && line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
      model = line.substr(line.find(':') + 2);
  }
  if (model.empty()) return std::nullopt;
  return HeaderField{"CPU", fmt::format("{} ({} logical cores)", model, cores)};
}

namespace {
std::vector<HeaderField> ask_machine() {
  std::vector<HeaderField> fields;
  struct utsname u {};
  if (uname(&u) == 0) fields.push_back({"OS", fmt::format("{} {} {}", u.sysname, u.release, u.machine)});
  std::ifstream os_release("/etc/os-release");
  for (std::string line; std::getline(os_release, line);)
    if (line.rfind("PRETTY_NAME=", 0) == 0) {
      std::string name = line.substr(12);
      name.erase(std::remove(name.begin(), name.end(), '"'), name.end());
      if (!fields.empty()) fields.back().value = name + " (" + fields.back().value + ")";
    }
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::stringstream text;
  text << cpuinfo.rdbuf();
  if (auto cpu = cpu_field(text.str())) fields.push_back(std::move(*cpu));
#if defined(__clang__)
  fields.push_back({"Compiler", fmt::format("clang {}", __clang_version__)});
#elif defined(__GNUC__)
  fields.push_back({"Compiler", fmt::format("GCC {}.{}.{}", __GNUC__, __GNUC_MINOR__, __GNUC_PATCHLEVEL__)});
#endif
  fields.push_back({"Libraries", fmt::format("fmt {}.{}.{}, nlohmann_json {}.{}.{}, C++ {}", FMT_VERSION / 10000,
                                             FMT_VERSION / 100 % 100, FMT_VERSION % 100, NLOHMANN_JSON_VERSION_MAJOR,
                                             NLOHMANN_JSON_VERSION_MINOR, NLOHMANN_JSON_VERSION_PATCH, __cplusplus)});
#ifdef GNUPLOT_EXECUTABLE
  if (FILE* p = popen(GNUPLOT_EXECUTABLE " --version 2>/dev/null", "r")) {  // the figures' plotter
    char buf[128] = {0};
    std::string v = std::fgets(buf, sizeof buf, p) ? buf : "";
    pclose(p);
    while (!v.empty() && (v.back() == '\n' || v.back() == '\r')) v.pop_back();
    if (!v.empty()) fields.push_back({"Plots", v});
  }
#endif
  return fields;
}
}  // namespace

std::vector<HeaderField> machine_fields() {
  // The machine and its plotter do not change while a process runs: asked once (gnuplot --version takes
  // ~50 ms, and the report fuzzer writes a report per input).
  static const std::vector<HeaderField> fields = ask_machine();
  return fields;
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
  // Levels declared as [[level]] tables carry their labels ("1x3", ...); otherwise the index.
  const nlohmann::json* labels = series.is_object() && series.contains("level_labels") ? &series["level_labels"] : nullptr;
  auto name = [&](std::size_t k) {
    if (labels && labels->is_array() && k < labels->size() && (*labels)[k].is_string()) return (*labels)[k].get<std::string>();
    return std::to_string(k);
  };
  std::vector<std::vector<std::string>> rows;
  for (std::size_t k = 0; k < h.size(); ++k)
    rows.push_back({name(k), at(h, k), at(value, k), at(error, k), at(order, k)});
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

std::string wall_time_words(const nlohmann::json& provenance, bool brief) {
  const auto wall = number_field(provenance, "wall_time_s");
  if (!wall) return std::string(missing_value);
  std::string out = fmt::format("{:.1f} s", *wall);
  const auto reused = number_field(provenance, "runs_reused");
  if (!reused || *reused <= 0) return out;
  const double total = *reused + number_field(provenance, "runs_run").value_or(0.0);
  const auto original = number_field(provenance, "reused_run_seconds");
  if (brief)
    return out + fmt::format(" ({:.0f}/{:.0f} cached{})", *reused, total,
                             original ? fmt::format(", originally {:.1f} s", *original) : std::string());
  out += fmt::format("; {:.0f} of {:.0f} runs reused from the cache", *reused, total);
  std::vector<std::string> from;
  if (original) from.push_back(fmt::format("their original run time {:.1f} s", *original));
  if (const auto code = text_field(provenance, "reused_code_version"); !code.empty()) from.push_back("code " + code);
  if (const auto date = text_field(provenance, "reused_date"); !date.empty()) from.push_back(date);
  if (!from.empty()) out += " (" + fmt::format("{}", fmt::join(from, ", ")) + ")";
  return out;
}

std::string status_class(const std::string& status) {
  if (status == "PASS") return "pass";
  if (status == "FAIL") return "fail";
  if (status == "UNREADABLE" || status == "BROKEN") return "unreadable";
  return "na";
}

}  // namespace report
