// The section "The papers, item by item" of the report: one table per paper, a row per claim (item, what the
// paper says, the project's counterpart linked, the picked check rows' DEM value vs reference with PASS/FAIL,
// the status, what the project found). Made from match_claims (paper_claims.hpp).
#pragma once

#include <string>
#include <vector>

#include "paper_claims.hpp"

namespace report {

inline constexpr const char* claims_section_id = "paper-claims";
inline constexpr const char* claims_section_title = "The papers, item by item";

/// The HTML section (id claims_section_id); citations in it ("findings K-9") are linked by the page.
std::string claims_html(const std::vector<ClaimRow>& rows);
/// The same in Markdown; figures link their SVG files.
std::string claims_markdown(const std::vector<ClaimRow>& rows);

}  // namespace report
