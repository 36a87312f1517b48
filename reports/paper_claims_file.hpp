// The papers' items, one [[claim]] each (verification/paper_claims.toml): what the paper states, the study
// that answers it, the check rows that carry its number, and the status. Read as strictly as a case
// (dem::TableReader): an unknown key, a word that is not allowed, a claim that contradicts its status or a
// study folder that does not exist is refused with file:line: key: what was expected.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace report {

inline const std::vector<std::string> claim_papers{"Kiyama & Fujimura 1983", "Matsui & Nishimura 1999"};
// checked: a study asserts it with a tolerance; shown: in the report, not asserted; finding: the project
// disagrees or the paper is wrong/unclear (a docs/findings.md entry says why); absent: no counterpart yet.
inline const std::vector<std::string> claim_statuses{"checked", "shown", "finding", "absent"};

struct PaperClaim {
  std::string paper;    // one of claim_papers
  std::string item;     // "Fig. 7", "Table 3", "Conclusion 1", "§2(5)"
  std::string says;     // the paper's statement, short, in the project's words
  std::string study;    // the study folder (verification/<study>/) that answers it; "" if none
  std::string check;    // a substring of the `quantity` of the study's check rows; "" if none
  std::string figure;   // a figure id or a snapshot id of the study; "" if none
  std::string status;   // one of claim_statuses
  std::string finding;  // a docs/findings.md entry ("K-9", "M-12", "F10"); "" if none
  std::string note;     // one line: what the project found against the paper
  std::string where;    // "file:line" of the [[claim]] table
};

/// Every [[claim]] of `file`, in file order. The study folders are looked up beside the file
/// (`<file's folder>/<study>/` with a study.toml or sensitivity.toml); a claim with status "absent" may name
/// a study that is still to be written. Throws dem::CaseError.
std::vector<PaperClaim> read_paper_claims(const std::filesystem::path& file);

}  // namespace report
