// The papers, item by item: the HTML and Markdown tables of the claims.
#include "paper_claims_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "text_format.hpp"

namespace report {

namespace {

constexpr std::size_t kShownRows = 5;  // check rows listed per claim; the rest are counted

constexpr const char* intro =
    "Every figure, table and stated result of the two papers, with the project's counterpart. "
    "<strong>checked</strong>: a study asserts it with a tolerance (its check rows are listed: DEM value, "
    "reference, PASS/FAIL, taken from the study's result.json); <strong>shown</strong>: in the report, not "
    "asserted; <strong>finding</strong>: the project disagrees with the paper or the paper is wrong or unclear, "
    "and docs/findings.md says why with numbers; <strong>absent</strong>: no counterpart yet. "
    "<em>no result</em>: the study has not been run for this report. The items and their wording are "
    "verification/paper_claims.toml; the numbers are never typed there.";

struct Counts {
  std::map<std::string, int> status;
  int failed = 0, no_result = 0, errors = 0;
};

Counts count(const std::vector<ClaimRow>& rows) {
  Counts c;
  for (const auto& r : rows) {
    ++c.status[r.claim.status];
    c.failed += r.verdict == "FAIL";
    c.no_result += r.verdict == "no result";
    c.errors += r.verdict == "error";
  }
  return c;
}

/// The papers in the order of claim_papers, each with its rows in file order.
std::vector<std::pair<std::string, std::vector<const ClaimRow*>>> by_paper(const std::vector<ClaimRow>& rows) {
  std::vector<std::pair<std::string, std::vector<const ClaimRow*>>> out;
  for (const auto& paper : claim_papers) {
    std::vector<const ClaimRow*> mine;
    for (const auto& r : rows)
      if (r.claim.paper == paper) mine.push_back(&r);
    if (!mine.empty()) out.emplace_back(paper, std::move(mine));
  }
  return out;
}

/// The rows to list: failed ones first, then in result order, at most kShownRows.
std::vector<const ClaimCheck*> listed_checks(const ClaimRow& row) {
  std::vector<const ClaimCheck*> all;
  for (const auto& c : row.checks) all.push_back(&c);
  std::stable_partition(all.begin(), all.end(), [](const ClaimCheck* c) { return c->status == "FAIL"; });
  if (all.size() > kShownRows) all.resize(kShownRows);
  return all;
}

/// The part of the listed rows' quantities they share, up to a ", " (the check's label before its variant),
/// so that it is written once; "" when they share none or there is one row.
std::string shared_label(const std::vector<const ClaimCheck*>& rows) {
  if (rows.size() < 2) return {};
  std::string prefix = rows.front()->quantity;
  for (const auto* c : rows) {
    std::size_t n = 0;
    while (n < prefix.size() && n < c->quantity.size() && prefix[n] == c->quantity[n]) ++n;
    prefix.resize(n);
  }
  const auto cut = prefix.rfind(", ");
  return cut == std::string::npos ? std::string() : prefix.substr(0, cut + 2);
}

std::string more_rows(const ClaimRow& row) {
  if (row.checks.size() <= kShownRows) return {};
  const auto failed = std::count_if(row.checks.begin(), row.checks.end(), [](const ClaimCheck& c) { return c.status == "FAIL"; });
  return fmt::format("and {} more rows ({} failed)", row.checks.size() - kShownRows, failed);
}

std::string status_css(const std::string& status) { return "claim-" + slug(status); }

std::string paper_anchor(const std::string& paper) { return std::string(claims_section_id) + "-" + slug(paper); }

// ---- HTML ----

std::string h(const std::string& text) { return html_escape(text); }

std::string badge_html(const std::string& css, const std::string& text) {
  return fmt::format("<span class=\"badge {}\">{}</span>", css, h(text));
}

std::string counterpart_html(const ClaimRow& row) {
  const auto& c = row.claim;
  if (c.study.empty()) return "&mdash;";
  std::string out = row.study_anchor.empty() ? "<code>" + h(c.study) + "</code>"
                                             : fmt::format("<a href=\"#{}\">{}</a>", row.study_anchor, h(c.study));
  if (!row.figure_anchor.empty())
    out += fmt::format("<br><span class=\"small\">figure <a href=\"#{}\">{}</a></span>", row.figure_anchor, h(row.figure_title));
  else if (!c.figure.empty())
    out += "<br><span class=\"small\">figure " + h(c.figure) + "</span>";
  return out;
}

std::string numbers_html(const ClaimRow& row) {
  if (row.verdict == "no result")
    return badge_html("na", "no result") + " <span class=\"small\">study not run for this report</span>";
  std::string out;
  if (row.verdict == "error") out += badge_html("fail", "error") + " <span class=\"note\">" + h(row.error) + "</span><br>";
  const auto listed = listed_checks(row);
  const auto shared = shared_label(listed);
  if (!shared.empty()) out += "<span class=\"small\">" + h(shared.substr(0, shared.size() - 2)) + ":</span><br>";
  for (const auto* c : listed)
    out += fmt::format("<span class=\"small\">{}</span>: DEM {}{} &middot; ref. {} {}<br>", h(c->quantity.substr(shared.size())),
                       h(c->dem), c->interval.empty() ? "" : " <span class=\"small\">95 % CI " + h(c->interval) + "</span>",
                       h(c->reference),
                       badge_html(c->status == "PASS" ? "pass" : c->status == "FAIL" ? "fail" : "na", c->status));
  if (const auto more = more_rows(row); !more.empty()) out += "<span class=\"small\">" + h(more) + "</span>";
  return out.empty() ? "&mdash;" : out;
}

std::string status_html(const ClaimRow& row) {
  std::string out = badge_html(status_css(row.claim.status), row.claim.status);
  if (row.verdict == "FAIL") out += " " + badge_html("fail", "FAIL");
  if (!row.claim.finding.empty()) out += "<br><span class=\"small\">findings " + h(row.claim.finding) + "</span>";
  return out;
}

std::string paper_table_html(const std::string& paper, const std::vector<const ClaimRow*>& rows) {
  std::string out = fmt::format("<h3 id=\"{}\">{}</h3>\n", paper_anchor(paper), h(paper));
  out +=
      "<table class=\"claims\">\n<thead><tr><th>Item</th><th>The paper says</th><th>Counterpart</th>"
      "<th>DEM vs reference (the study's check rows)</th><th>Status</th><th>What the project found</th></tr></thead>\n"
      "<tbody>\n";
  for (const auto* r : rows)
    out += "<tr><td>" + h(r->claim.item) + "</td><td>" + h(r->claim.says) + "</td><td>" + counterpart_html(*r) +
           "</td><td>" + numbers_html(*r) + "</td><td>" + status_html(*r) + "</td><td>" + h(r->claim.note) + "</td></tr>\n";
  return out + "</tbody>\n</table>\n";
}

std::string counts_text(const Counts& c, std::size_t total) {
  std::string out = fmt::format("{} items:", total);
  for (const auto& s : claim_statuses) out += fmt::format(" {} {},", c.status.count(s) ? c.status.at(s) : 0, s);
  out.pop_back();
  out += fmt::format("; {} with a failed check, {} without a result", c.failed, c.no_result);
  if (c.errors) out += fmt::format(", {} with a selector that matches nothing", c.errors);
  return out + ".";
}

// ---- Markdown ----

std::string m(const std::string& text) { return markdown_escape(text); }

std::string numbers_markdown(const ClaimRow& row) {
  if (row.verdict == "no result") return "no result (study not run for this report)";
  std::vector<std::string> parts;
  if (row.verdict == "error") parts.push_back("**error**: " + m(row.error));
  for (const auto* c : listed_checks(row))
    parts.push_back(fmt::format("{}: DEM {}{}, ref. {} **{}**", m(c->quantity), m(c->dem),
                                c->interval.empty() ? "" : " (95 % CI " + m(c->interval) + ")", m(c->reference), c->status));
  if (const auto more = more_rows(row); !more.empty()) parts.push_back(more);
  return parts.empty() ? std::string(missing_value) : fmt::format("{}", fmt::join(parts, "; "));
}

std::string counterpart_markdown(const ClaimRow& row) {
  const auto& c = row.claim;
  if (c.study.empty()) return std::string(missing_value);
  std::string out = row.study_anchor.empty() ? "`" + c.study + "`" : fmt::format("[{}](#{})", m(c.study), row.study_anchor);
  if (!row.figure_file.empty()) out += fmt::format(", figure [{}]({})", m(row.figure_title), row.figure_file);
  else if (!c.figure.empty()) out += ", figure " + m(c.figure);
  return out;
}

}  // namespace

std::string claims_html(const std::vector<ClaimRow>& rows) {
  std::string out = fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n", claims_section_id, claims_section_title);
  out +=
      "<style>.claim-checked { background: #dafbe1; color: #116329; } .claim-shown { background: #ddf4ff; color: #0550ae; }"
      " .claim-finding { background: #fff1e5; color: #953800; } .claim-absent { background: #eaeef2; color: #57606a; }"
      " table.claims td:nth-child(1) { white-space: nowrap; } table.claims td:nth-child(2) { min-width: 14em; }"
      " table.claims td:nth-child(4) { min-width: 24em; } table.claims td:nth-child(5) { white-space: nowrap; }"
      " table.claims td:nth-child(6) { min-width: 16em; }</style>\n";
  out += std::string("<p>") + intro + "</p>\n<p class=\"counts\">" + h(counts_text(count(rows), rows.size())) + "</p>\n";
  for (const auto& [paper, mine] : by_paper(rows)) out += paper_table_html(paper, mine);
  return out + "</section>\n";
}

std::string claims_markdown(const std::vector<ClaimRow>& rows) {
  std::string out = fmt::format("<a id=\"{}\"></a>\n\n## {}\n\n", claims_section_id, claims_section_title);
  std::string text = intro;  // the intro's HTML emphasis as Markdown
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"<strong>", "**"}, {"</strong>", "**"}, {"<em>", "*"}, {"</em>", "*"}})
    for (auto p = text.find(from); p != std::string::npos; p = text.find(from)) text.replace(p, from.size(), to);
  out += text + "\n\n" + counts_text(count(rows), rows.size()) + "\n\n";
  for (const auto& [paper, mine] : by_paper(rows)) {
    out += "### " + m(paper) + "\n\n| Item | The paper says | Counterpart | DEM vs reference | Status | What the project found |\n"
           "|---|---|---|---|---|---|\n";
    for (const auto* r : mine) {
      std::string status = r->claim.status + (r->verdict == "FAIL" ? " **FAIL**" : "");
      if (!r->claim.finding.empty()) status += ", findings " + r->claim.finding;
      out += "| " + m(r->claim.item) + " | " + m(r->claim.says) + " | " + counterpart_markdown(*r) + " | " +
             numbers_markdown(*r) + " | " + status + " | " + m(r->claim.note) + " |\n";
    }
    out += "\n";
  }
  return out;
}

}  // namespace report
