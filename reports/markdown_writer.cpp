// Markdown page writer.
#include "markdown_writer.hpp"

#include <fmt/format.h>

#include "sensitivity_overview.hpp"
#include "text_format.hpp"

namespace report {

namespace {

std::string escape(const std::string& text) { return markdown_escape(text); }

std::string status_text(const std::string& status) {
  if (status == "PASS") return "\u2705 PASS";
  if (status == "FAIL") return "\u274c **FAIL**";
  if (status == "UNREADABLE") return "\u26a0\ufe0f **UNREADABLE**";
  if (status == "BROKEN") return "\u26a0\ufe0f **BROKEN**";
  return status;
}

// Escaped copies of cells, padded or cut to width.
std::vector<std::string> escaped(const std::vector<std::string>& cells, std::size_t width) {
  std::vector<std::string> out(width);
  for (std::size_t i = 0; i < width && i < cells.size(); ++i) out[i] = escape(cells[i]);
  return out;
}

// One table line from cells that are already Markdown.
std::string table_line(const std::vector<std::string>& cells) {
  std::string out = "|";
  for (const auto& c : cells) {
    out += ' ';
    out += c;
    out += " |";
  }
  out += '\n';
  return out;
}

std::string table_head(const std::vector<std::string>& columns) {
  std::string out = table_line(escaped(columns, columns.size())) + "|";
  for (std::size_t i = 0; i < columns.size(); ++i) out += "---|";
  out += '\n';
  return out;
}

std::string table(const std::vector<std::string>& columns,
                  const std::vector<std::vector<std::string>>& rows) {
  std::string out = table_head(columns);
  for (const auto& row : rows) out += table_line(escaped(row, columns.size()));
  out += '\n';
  return out;
}

std::string key_value_table(const std::vector<HeaderField>& fields) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& f : fields) rows.push_back({f.label, f.value});
  return table({"", ""}, rows);
}

// A checks table: text cells plus a last "Result" column that is already Markdown.
std::string checks_table(
    std::vector<std::string> columns,
    const std::vector<std::pair<std::vector<std::string>, std::string>>& rows) {
  columns.push_back("Result");
  std::string out = table_head(columns);
  for (const auto& [cells, status] : rows) {
    auto line = escaped(cells, columns.size());
    line.back() = status_text(status);
    out += table_line(line);
  }
  out += '\n';
  return out;
}

std::string figure(const RenderedFigure& figure) {
  if (figure.file.empty())
    return fmt::format("*{}: {}*\n\n", escape(figure.title), escape(figure.note));
  std::string out = fmt::format("![{}]({})\n\n", escape(figure.title), figure.file);
  if (!figure.note.empty()) out += fmt::format("*{}*\n\n", escape(figure.note));
  return out;
}

std::string fence(const std::string& text) {
  const std::string marker = text.find("```") == std::string::npos ? "```" : "~~~~";
  return marker + "\n" + text + (text.empty() || text.back() != '\n' ? "\n" : "") + marker + "\n\n";
}

std::string summary(const ReportContent& content) {
  const auto counts = count_outcomes(content);
  std::string out = "## Summary\n\n";
  out += fmt::format("**{} passed, {} failed", counts.checks_passed, counts.checks_failed);
  if (counts.checks_other > 0) out += fmt::format(", {} without verdict", counts.checks_other);
  out += fmt::format("** of {} checks in {} studies ({} passed, {} failed",
                     counts.checks_passed + counts.checks_failed + counts.checks_other,
                     content.studies.size(), counts.studies_passed, counts.studies_failed);
  if (counts.studies_unreadable > 0)
    out += fmt::format(", {} unreadable or broken", counts.studies_unreadable);
  if (counts.studies_other > 0) out += fmt::format(", {} without verdict", counts.studies_other);
  out += ").\n\n";
  if (content.studies.empty()) return out + "No result.json found.\n\n";

  std::vector<std::pair<std::vector<std::string>, std::string>> rows;
  for (const auto& study : content.studies) {
    const auto& source = study.source;
    const auto name = study_name(source);
    if (!source.readable()) {
      rows.push_back(
          {{name, "unreadable: " + source.read_error, "", "", "", "", "", ""}, "UNREADABLE"});
      continue;
    }
    const auto& checks = array_field(source.result, "checks");
    if (checks.empty())
      rows.push_back({{name, "(no checks)", "", "", "", "", "", ""}, study_status(source)});
    for (const auto& check : checks) {
      const auto r = check_row(check);
      rows.push_back(
          {{name, r.quantity, r.reference, r.dem, r.error, r.tolerance, r.asserts, r.order}, r.status});
    }
  }
  return out + checks_table({"Study", "Quantity", "Reference", "DEM", "Error", "Tolerance", "Asserts",
                             "Order (observed vs expected \u00b1 band)"},
                            rows);
}

std::string study_section(const StudyReport& study) {
  const auto& source = study.source;
  const auto& result = source.result;
  auto title = text_field(result, "title");
  if (title.empty()) title = study_name(source);
  std::string out = "<a id=\"" + study_anchor(source) + "\"></a>\n\n## " + escape(title) + " \u2014 " +
                    status_text(study_status(source)) + "\n\n";
  out += "Study `" + study_name(source) + "`, " + escape(source.path.string()) + "\n\n";
  if (!source.readable())
    return out + "Unreadable result file: " + escape(source.read_error) + "\n\n";

  const auto requirement = text_field(result, "requirement");
  if (!requirement.empty()) out += "**Requirement.** " + escape(requirement) + "\n\n";
  const auto readme = readme_parts(result);
  if (!readme.purpose.empty()) {
    out += "**Purpose (README).** " + escape(readme.purpose) + "\n\n";
    if (!readme.rest.empty()) out += "**Findings and known limits (README).**\n\n" + fence(readme.rest);
  }
  const auto& provenance = object_field(result, "provenance");
  const auto command = text_field(provenance, "command");
  if (!command.empty()) {
    out += "Command: `" + command + "`";
    if (number_field(provenance, "wall_time_s")) out += " · wall time " + wall_time_words(provenance);
    out += "\n\n";
  }
  const auto setup = setup_fields(result);
  if (!setup.empty()) out += "### Setup\n\n" + key_value_table(setup);
  const auto reference = text_field(result, "reference");
  if (!reference.empty()) out += "### Reference\n\n" + escape(reference) + "\n\n";
  const auto& checks = array_field(result, "checks");
  if (!checks.empty()) {
    std::vector<std::pair<std::vector<std::string>, std::string>> rows;
    for (const auto& check : checks) {
      const auto r = check_row(check);
      rows.push_back({{r.quantity, r.reference, r.dem, r.error, r.tolerance, r.asserts,
                       r.tolerance_reason, r.order, r.note},
                      r.status});
    }
    out += "### Checks\n\n" +
           checks_table({"Quantity", "Reference", "DEM", "Error", "Tolerance", "Asserts", "Why this tolerance",
                         "Order (observed vs expected \u00b1 band)", "Note"},
                        rows);
  }
  const auto& series = array_field(result, "series");
  if (!study.convergence.empty()) {
    out += "### Convergence\n\n";
    for (std::size_t k = 0; k < study.convergence.size() && k < series.size(); ++k) {
      out += figure(study.convergence[k]);
      out += escape(series_summary(series[k])) + "\n\n";
      out += table(series_level_columns, series_level_rows(series[k]));
      for (const auto& note : array_field(series[k], "notes"))
        if (note.is_string()) out += "- *" + escape(note.get<std::string>()) + "*\n";
      out += "\n";
    }
  }
  if (!study.figures.empty()) {
    out += "### Figures\n\n";
    for (const auto& f : study.figures) out += figure(f);
  }
  out += snapshot_gallery_markdown(study.snapshots);
  const auto& tables = array_field(result, "tables");
  if (!tables.empty()) {
    out += "### Tables\n\n";
    for (const auto& t : tables) {
      const auto data = table_data(t);
      out += "#### " + escape(data.title) + "\n\n";
      out += data.preformatted ? fence(*data.preformatted) : table(data.columns, data.rows);
    }
  }
  return out;
}

}  // namespace

std::string markdown_page(const ReportContent& content) {
  std::string out = "# " + escape(content.title) + "\n\n";
  out += key_value_table(content.header);
  if (!content.docs_html.empty())
    out += "Citations (\"refs §x.y\", equation labels K1–K28 and M1–M26, \"findings F2\") refer to the repository's "
           "`docs/references.md`, `docs/model.md` and `docs/findings.md`; `index.html` includes them, every citation "
           "linked.\n\n";
  out += "## Studies\n\n";
  {
    std::vector<std::string> columns{"Study", "Title", "Checks passed", "Checks failed",
                                     "Observed orders (expected)", "Wall time", "Result"};
    out += table_head(columns);
    for (const auto& row : overview_rows(content)) {
      auto line = escaped({row.name, row.title, std::to_string(row.passed), std::to_string(row.failed),
                           row.orders, row.wall_time, ""},
                          columns.size());
      line[0] = "[" + escape(row.name) + "](#" + row.anchor + ")";
      line.back() = status_text(row.status);
      out += table_line(line);
    }
    out += "\n";
  }
  if (const auto rows = sensitivity_overview_rows(content); !rows.empty()) {
    out += "## Sensitivity studies: overview\n\nPer study and output, the most and the least influential parameter by the "
           "strongest measure the study computed: the Sobol' total index S_T with its bootstrap interval, else Morris μ*, "
           "else the one-at-a-time range (max − min).\n\n";
    out += table_head(sensitivity_overview_columns);
    for (const auto& r : rows) {
      auto line = escaped({r.study, r.output, r.measure, r.most, r.most_value, r.most_interval, r.least, r.least_value,
                           r.least_interval, r.runs, r.failed, r.noise},
                          sensitivity_overview_columns.size());
      line[0] = "[" + escape(r.study) + "](#" + r.anchor + ")";
      out += table_line(line);
    }
    out += "\n";
  }
  out += summary(content);
  out += content.claims_markdown;
  out += content.features_markdown;
  for (const auto& study : content.studies) out += study_section(study);
  out += content.speed_markdown;
  out +=
      "---\n\n*Generated by `dem2d report` from the studies' result.json files; do not edit by "
      "hand.*\n";
  return out;
}

}  // namespace report
