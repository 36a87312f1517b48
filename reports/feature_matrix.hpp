// What is verified, feature by feature: the rows of docs/model.md's code-site tables (each an equation or
// a group of them, "M8, M9 | tension cut-off | code") against the studies of the report. A study CHECKS a
// feature when one of its check rows (label, reference, reason) cites one of the row's labels; it SHOWS it
// when only its title, requirement, reference, setup, figures or README do. A feature that no study checks
// stands out: the map of what the verification does not cover yet, unless model.md's table "| Equations |
// Why no study checks it |" names the row: a definition or a choice that no output can check on its own
// (the matrix shows the reason instead of a study).
#pragma once

#include <string>
#include <vector>

#include "report_content.hpp"

namespace report {

inline constexpr const char* features_section_id = "feature-matrix";
inline constexpr const char* not_checkable_header = "Why no study checks it";
inline constexpr const char* features_section_title = "What is verified: the model's equations against the studies";

struct FeatureRow {
  std::string equations, what;            // the code-site table's first two cells
  std::vector<std::string> labels;        // its labels, ranges expanded ("K6–K8" → K6, K7, K8)
  std::vector<std::string> checked_by;    // study folders whose checks cite a label of the row
  std::vector<std::string> shown_in;      // study folders citing one elsewhere (and not checking it)
  std::string not_checkable;              // why no study output can check it (model.md), or empty
};

/// The labels a text cites (K, M or G, 1–2 digits, an optional ".x"), each once, in order of appearance.
std::vector<std::string> cited_labels(const std::string& text);

/// Whether a citation of `cited` covers `label`: the same label, one of its sub-labels (M15 ← M15.1), or
/// its group (M15.1 ← M15).
bool covers(const std::string& cited, const std::string& label);

/// The rows of every table of model.md whose header row starts with "Equations" and ends with "Code", each
/// with the reason of the row of equal first cell in a table whose header ends with "Why no study checks it".
std::vector<FeatureRow> feature_rows(const std::string& model_md);

/// The rows with the studies that check or show each one (readable studies only). A citation covers a row
/// as `covers` says, except between a group and a sub-label that head rows of their own (M19 and M19.r):
/// there only the label itself counts.
std::vector<FeatureRow> match_features(std::vector<FeatureRow> rows, const std::vector<StudyReport>& studies);

std::string features_html(const std::vector<FeatureRow>& rows);
std::string features_markdown(const std::vector<FeatureRow>& rows);

}  // namespace report
