// The papers, item by item: every [[claim]] of verification/paper_claims.toml (paper_claims_file.hpp) matched
// against the studies' results. The numbers come from the check rows of the named study's result.json,
// never from the claims file: the report stays made from result files.
#pragma once

#include <string>
#include <vector>

#include "paper_claims_file.hpp"
#include "report_content.hpp"

namespace report {

struct ClaimCheck {  // one check row the claim's selector picked
  std::string quantity, dem, reference, status;  // status: PASS, FAIL, n/a
  std::string interval;  // an ensemble check's 95 % CI of the mean, "[low, high]"; "" for a single run
};

struct ClaimRow {
  PaperClaim claim;
  std::string study_anchor;                // the study's section in the page; "" when it has no result
  std::string figure_anchor, figure_file;  // the figure in the page and its SVG file; "" when none
  std::string figure_title;
  std::vector<ClaimCheck> checks;          // in result order
  // "PASS" (every picked row passed), "FAIL" (one failed), "no result" (the study has no readable result),
  // "error" (the selector or the figure id matches nothing in a present result), "" (no check named)
  std::string verdict;
  std::string error;                       // the error in words ("" unless verdict is "error")
};

/// Matches each claim against the studies' results (by folder name). A selector that matches no check
/// of a present, readable result, or a figure id the result does not declare, is an error: its row says
/// so and `errors` lists it as "file:line: claim.check: …". A study without a readable result is "no result".
std::vector<ClaimRow> match_claims(const std::vector<PaperClaim>& claims, const std::vector<StudyReport>& studies,
                                   std::vector<std::string>& errors);

}  // namespace report
