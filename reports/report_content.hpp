// What goes into the report, assembled once and written twice (HTML and Markdown).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "snapshot_gallery.hpp"
#include "study_result.hpp"

namespace report {

struct RenderedFigure {
  std::string title;
  std::string file;  // relative to out_dir ("figures/<study>-convergence-1.svg"); "" if none
  std::string svg;   // the SVG text for inlining; "" if none
  std::string note;  // shown with (or instead of) the figure: why skipped, gnuplot failure
};

struct StudyReport {
  StudyResult source;
  std::vector<RenderedFigure> convergence;  // one per entry of "series", same order
  std::vector<RenderedFigure> figures;      // one per entry of "figures", same order
  std::vector<SnapshotPicture> snapshots;   // one per entry of "snapshots", same order (snapshot_gallery.hpp)
};

struct HeaderField {
  std::string label, value;
};

struct ReportContent {
  std::string title;
  std::vector<HeaderField> header;
  std::vector<StudyReport> studies;
  std::string docs_html;  // the cited documentation (cited_docs.hpp), "" if docs/ was not found
  std::string speed_html, speed_markdown;  // the speed benchmark's section (speed_table.hpp), "" if none
  std::string claims_html, claims_markdown;  // the papers, item by item (paper_claims_table.hpp), "" if none
  std::string features_html, features_markdown;  // model.md's equations against the studies (feature_matrix.hpp)
};

struct Counts {
  int checks_passed = 0, checks_failed = 0, checks_other = 0;
  int studies_passed = 0, studies_failed = 0, studies_unreadable = 0, studies_other = 0;
};
Counts count_outcomes(const ReportContent& content);

// Header lines: code version, build type, machine (report provenance first, else the studies'),
// report date, date range of the study runs, studies folder, then any other provenance keys.
std::vector<HeaderField> header_fields(const nlohmann::json& provenance,
                                       const std::vector<StudyResult>& studies,
                                       const std::filesystem::path& studies_dir);

// Anchor of a study's section in the HTML page.
std::string study_anchor(const StudyResult& study);

// Anchor of a study's figure (its declared id) in the HTML page.
std::string figure_anchor(const StudyResult& study, const std::string& figure_id);
// Anchor of the gallery of a study's snapshot id (snapshot_gallery.hpp) in the HTML page: the prefix + slug(id).
std::string snapshot_anchor_prefix(const StudyResult& study);
std::string snapshot_anchor(const StudyResult& study, const std::string& snapshot_id);

// Display name: the "study" field, else the folder name.
std::string study_name(const StudyResult& study);

// Cells of one check row, formatted (shared by the HTML and Markdown writers).
// `asserts` says in words what the check requires ("|error| ≤ tol", "DEM > reference + tol",
// "decreases across the variants by > tol per step"), so that a direction check is not read as a
// failed closeness check.
struct CheckRow {
  std::string quantity, reference, dem, error, tolerance, tolerance_reason, order, status, note,
      asserts;
};
CheckRow check_row(const nlohmann::json& check);
std::string check_assertion(const nlohmann::json& check);

// One row of the study overview (the table of contents): title, counts, orders, wall time.
struct OverviewRow {
  std::string anchor, name, title, status, orders, wall_time;
  int passed = 0, failed = 0;
};
std::vector<OverviewRow> overview_rows(const ReportContent& content);

// A study's README (carried in result.json): its first paragraph (the purpose) and the rest
// (findings, known limits), title line dropped. Empty strings when there is none.
struct ReadmeParts {
  std::string purpose, rest;
};
ReadmeParts readme_parts(const nlohmann::json& result);

// The machine the report was written on: OS, CPU model, compiler and library versions.
std::vector<HeaderField> machine_fields();
/// The CPU line of the header from /proc/cpuinfo's text: the first "model name" and the count of
/// "processor" entries; none where no model name is given (some ARM kernels).
std::optional<HeaderField> cpu_field(const std::string& cpuinfo);

// Setup of a study as label/value pairs: kind, case, parameter, each setup entry, overrides.
std::vector<HeaderField> setup_fields(const nlohmann::json& result);

// Per-level rows of a series: level, h, value, error, observed order.
std::vector<std::vector<std::string>> series_level_rows(const nlohmann::json& series);
inline const std::vector<std::string> series_level_columns{"level", "h", "value", "error",
                                                           "observed order"};
// One line: fitted vs expected order, Richardson value, GCI, asymptotic ratio, reference.
std::string series_summary(const nlohmann::json& series);

// A "tables" entry: columns + rows (cells formatted), or preformatted text.
struct TableData {
  std::string title;
  std::vector<std::string> columns;  // as many as the widest row (blank headers if undeclared)
  std::vector<std::vector<std::string>> rows;
  std::optional<std::string> preformatted;
};
TableData table_data(const nlohmann::json& table);

// A study's wall time in words, saying what the run cache served: "1.3 s", or "0.0 s; 12 of 12 runs
// reused from the cache (their original run time 1.3 s, code 90b980b, 2026-11-27T04:58:01Z)".
// `brief`: the table cell's form, "0.0 s (12/12 cached, originally 1.3 s)". "—" when not recorded.
std::string wall_time_words(const nlohmann::json& provenance, bool brief = false);

// Lowercase status for CSS classes: pass, fail, unreadable, na.
std::string status_class(const std::string& status);

}  // namespace report
