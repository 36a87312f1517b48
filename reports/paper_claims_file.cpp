// Reading verification/paper_claims.toml: one [[claim]] per item of the two papers.
#include "paper_claims_file.hpp"

#include <fmt/format.h>

#include <regex>

#include "dem/cases/case_file.hpp"
#include "dem/cases/case_reader.hpp"

namespace report {

namespace {

namespace fs = std::filesystem;
using dem::TableReader;

constexpr const char* kHelp = "verification/README.md, \"The papers, item by item\"";

/// The study folders beside the claims file (each with a study.toml or a sensitivity.toml).
std::vector<std::string> study_folders(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ignored;
  for (const auto& e : fs::directory_iterator(dir, ignored))
    if (e.is_directory() && (fs::is_regular_file(e.path() / "study.toml") || fs::is_regular_file(e.path() / "sensitivity.toml")))
      out.push_back(e.path().filename().string());
  return out;
}

/// A required string on one line, not blank.
std::string one_line(const TableReader& r, const std::string& key) {
  const std::string v = r.string(key);
  if (v.find_first_not_of(" \t") == std::string::npos) r.fail(key, "expected a text, got an empty string");
  if (v.find('\n') != std::string::npos) r.fail(key, "expected one line (no line break)");
  return v;
}

/// An optional string that, when given, is not blank.
std::string optional_text(const TableReader& r, const std::string& key) {
  if (!r.has(key)) {
    r.mark(key);
    return {};
  }
  return one_line(r, key);
}

void check_study(const TableReader& r, const PaperClaim& c, const fs::path& dir) {
  if (c.study.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") != std::string::npos ||
      c.study == "." || c.study == "..")
    r.fail("study", fmt::format("expected a study folder name (letters, digits, '_', '-', '.'), got \"{}\"", c.study));
  if (c.status == "absent") return;  // may name the study that is still to be written
  const auto known = study_folders(dir);
  if (std::find(known.begin(), known.end(), c.study) != known.end()) return;
  const std::string near = dem::nearest_word(c.study, known);
  r.fail("study", fmt::format("no study folder {}/ (with a study.toml or sensitivity.toml){}",
                              (dir / c.study).string(), near.empty() ? "" : fmt::format("; did you mean \"{}\"?", near)));
}

/// What each status needs: checked a study and a check, shown a study, finding an entry, absent no check.
void check_status_fields(const TableReader& r, const PaperClaim& c) {
  if ((!c.check.empty() || !c.figure.empty()) && c.study.empty())
    r.fail(c.check.empty() ? "figure" : "check", "names a row of a study's result: give the study too");
  if (c.status == "checked" && c.check.empty())
    r.fail("check", "missing: status \"checked\" needs the check rows that assert it (a substring of their quantity)");
  if (c.status == "shown" && c.study.empty())
    r.fail("study", "missing: status \"shown\" needs the study that shows it");
  if (c.status == "finding" && c.finding.empty())
    r.fail("finding", "missing: status \"finding\" needs its docs/findings.md entry (e.g. \"K-9\")");
  if (c.status == "absent" && !c.check.empty())
    r.fail("check", "an absent claim has no check; give status \"checked\" (or \"finding\") with it");
  static const std::regex entry("F[0-9]+|[KM]-[0-9]+");
  if (!c.finding.empty() && !std::regex_match(c.finding, entry))
    r.fail("finding", fmt::format("expected a docs/findings.md entry (F10, K-9, M-12), got \"{}\"", c.finding));
}

PaperClaim read_claim(const TableReader& r, const toml::node& n, const fs::path& dir) {
  PaperClaim c;
  c.where = dem::where(n, r.file());
  c.paper = r.choice("paper", claim_papers, "");
  c.item = one_line(r, "item");
  c.says = one_line(r, "says");
  c.status = r.choice("status", claim_statuses, "");
  c.study = optional_text(r, "study");
  c.check = optional_text(r, "check");
  c.figure = optional_text(r, "figure");
  c.finding = optional_text(r, "finding");
  c.note = one_line(r, "note");
  r.finish();  // a misspelled key first: it would otherwise read as a missing one
  if (!c.study.empty()) check_study(r, c, dir);
  check_status_fields(r, c);
  return c;
}

}  // namespace

std::vector<PaperClaim> read_paper_claims(const fs::path& file) {
  const toml::table root = dem::parse_toml_file(file);
  const std::string name = file.string();
  TableReader top(root, "", name, kHelp);
  top.mark("claim");
  const toml::node* n = top.node("claim");
  if (!n) top.fail("claim", "missing: at least one [[claim]] table");
  const toml::array* arr = n->as_array();
  if (!arr || arr->empty()) top.fail("claim", "expected [[claim]] tables");
  std::vector<PaperClaim> claims;
  for (const auto& x : *arr) {
    const toml::table* t = x.as_table();
    if (!t) top.fail_at(x, "claim", "expected [[claim]] tables (a table each), got a value");
    TableReader r(*t, "claim", name, kHelp);
    claims.push_back(read_claim(r, x, file.parent_path().empty() ? fs::path(".") : file.parent_path()));
  }
  top.finish();
  return claims;
}

}  // namespace report
