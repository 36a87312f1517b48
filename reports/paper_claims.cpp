// Matching the papers' claims against the studies' results: the check rows a selector picks, the figure
// a claim names, and what is missing.
#include "paper_claims.hpp"

#include <fmt/format.h>

#include "study_result.hpp"
#include "text_format.hpp"

namespace report {

namespace {

const StudyReport* find_study(const std::vector<StudyReport>& studies, const std::string& folder) {
  for (const auto& s : studies)
    if (s.source.folder == folder) return &s;
  return nullptr;
}

std::string verdict_of(const std::vector<ClaimCheck>& checks) {
  bool all_pass = true;
  for (const auto& c : checks) {
    if (c.status == "FAIL") return "FAIL";
    all_pass = all_pass && c.status == "PASS";
  }
  return all_pass ? "PASS" : "n/a";
}

/// The check rows whose quantity contains the selector; an error when the result has none.
void pick_checks(ClaimRow& row, const StudyReport& study) {
  const auto& checks = array_field(study.source.result, "checks");
  for (const auto& check : checks) {
    const CheckRow cells = check_row(check);
    if (cells.quantity.find(row.claim.check) == std::string::npos) continue;
    const auto low = number_field(check, "ci_low"), high = number_field(check, "ci_high");
    const std::string interval = low && high ? "[" + format_number(*low) + ", " + format_number(*high) + "]" : "";
    row.checks.push_back({cells.quantity, cells.dem, cells.reference, cells.status, interval});
  }
  if (!row.checks.empty()) {
    row.verdict = verdict_of(row.checks);
    return;
  }
  row.verdict = "error";
  row.error = fmt::format("check \"{}\" matches none of the {} check rows of {}", row.claim.check, checks.size(),
                          study.source.path.string());
}

/// The snapshot gallery of the study with the claim's id (linked to its heading); false if there is none.
bool find_snapshot(ClaimRow& row, const StudyReport& study) {
  for (const auto& s : array_field(study.source.result, "snapshots")) {
    if (text_field(s, "id") != row.claim.figure) continue;
    row.figure_anchor = snapshot_anchor(study.source, row.claim.figure);
    row.figure_title = text_field(s, "title");
    if (row.figure_title.empty()) row.figure_title = row.claim.figure;
    return true;
  }
  return false;
}

/// The figure (or snapshot gallery) of the study with the claim's id; an error when the result declares none.
void find_figure(ClaimRow& row, const StudyReport& study) {
  if (find_snapshot(row, study)) return;
  const auto& figures = array_field(study.source.result, "figures");
  for (std::size_t k = 0; k < figures.size(); ++k) {
    if (text_field(figures[k], "id") != row.claim.figure) continue;
    row.figure_anchor = figure_anchor(study.source, row.claim.figure);
    if (k < study.figures.size()) {
      row.figure_file = study.figures[k].file;
      row.figure_title = study.figures[k].title;
    }
    if (row.figure_title.empty()) row.figure_title = text_field(figures[k], "title");
    if (row.figure_title.empty()) row.figure_title = row.claim.figure;
    return;
  }
  const std::string what = fmt::format("figure \"{}\" is not among the {} figures and {} snapshots of {}", row.claim.figure,
                                       figures.size(), array_field(study.source.result, "snapshots").size(),
                                       study.source.path.string());
  row.error = row.error.empty() ? what : row.error + "; " + what;
  row.verdict = "error";
}

}  // namespace

std::vector<ClaimRow> match_claims(const std::vector<PaperClaim>& claims, const std::vector<StudyReport>& studies,
                                   std::vector<std::string>& errors) {
  std::vector<ClaimRow> rows;
  for (const auto& claim : claims) {
    ClaimRow row;
    row.claim = claim;
    if (!claim.study.empty()) {
      const StudyReport* study = find_study(studies, claim.study);
      if (!study || !study->source.readable()) {
        if (!claim.check.empty() || !claim.figure.empty()) row.verdict = "no result";
      } else {
        row.study_anchor = study_anchor(study->source);
        if (!claim.check.empty()) pick_checks(row, *study);
        if (!claim.figure.empty()) find_figure(row, *study);
      }
    }
    if (row.verdict == "error")
      errors.push_back(fmt::format("{}: claim ({}, {}): {}", claim.where, claim.paper, claim.item, row.error));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace report
