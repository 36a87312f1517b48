// The map of what is verified (feature_matrix.hpp).
#include "feature_matrix.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "text_format.hpp"

namespace report {

namespace {

const std::regex& label_pattern() {
  static const std::regex re(R"((^|[^A-Za-z0-9])([KMG][0-9]{1,2})(\.[0-9a-z])?(?![0-9A-Za-z]))");
  return re;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  for (std::size_t k = 1; k < line.size(); ++k) {  // after the leading '|'
    if (line[k] == '|') {
      out.push_back(trim(cell));
      cell.clear();
    } else {
      cell += line[k];
    }
  }
  return out;
}

/// "K6–K8" or "K6-K8" → K6, K7, K8; anything else as cited_labels finds it.
std::vector<std::string> row_labels(const std::string& cell) {
  static const std::regex range(R"(([KMG])([0-9]{1,2})\s*(?:–|-)\s*([KMG])([0-9]{1,2}))");
  std::vector<std::string> out;
  std::string rest = cell;
  std::smatch m;
  while (std::regex_search(rest, m, range)) {
    if (m[1] == m[3])
      for (int k = std::stoi(m[2]); k <= std::stoi(m[4]); ++k) out.push_back(m[1].str() + std::to_string(k));
    rest = m.prefix().str() + " " + m.suffix().str();
  }
  for (const auto& l : cited_labels(rest))
    if (std::find(out.begin(), out.end(), l) == out.end()) out.push_back(l);
  return out;
}

/// Every string inside a JSON value, joined by newlines.
void strings_of(const nlohmann::json& j, std::string& out) {
  if (j.is_string()) {
    out += j.get<std::string>();
    out += '\n';
  } else if (j.is_array() || j.is_object()) {
    for (const auto& v : j) strings_of(v, out);
  }
}

/// Whether a citation covers one of a row's labels. A group and a sub-label that have rows of their own
/// (M19, the paper's wall lever, and M19.r, an alternative to it) are different features: between them
/// only the label itself counts, not the group (`own`: every label that heads a row).
bool cites_any(const std::vector<std::string>& cited, const std::vector<std::string>& labels, const std::set<std::string>& own) {
  for (const auto& c : cited)
    for (const auto& l : labels)
      if (covers(c, l) && (c == l || !own.contains(c) || !own.contains(l))) return true;
  return false;
}

std::string study_list_html(const std::vector<std::string>& folders) {
  std::string out;
  for (const auto& f : folders) out += fmt::format("{}<a href=\"#study-{}\">{}</a>", out.empty() ? "" : ", ", f, html_escape(f));
  return out.empty() ? std::string(missing_value) : out;
}

/// The rows a study checks, and the unchecked ones that model.md explains.
std::pair<std::size_t, std::size_t> counts(const std::vector<FeatureRow>& rows) {
  std::size_t checked = 0, explained = 0;
  for (const auto& r : rows) {
    if (!r.checked_by.empty()) ++checked;
    else if (!r.not_checkable.empty()) ++explained;
  }
  return {checked, explained};
}

const char* row_class(const FeatureRow& r) {
  if (!r.checked_by.empty()) return "";
  return r.not_checkable.empty() ? " class=\"unchecked\"" : " class=\"not-checkable\"";
}

std::string checked_html(const FeatureRow& r) {
  if (r.checked_by.empty() && !r.not_checkable.empty()) return "<em>not checkable</em>: " + html_escape(r.not_checkable);
  return study_list_html(r.checked_by);
}

}  // namespace

std::vector<std::string> cited_labels(const std::string& text) {
  std::vector<std::string> out;
  for (std::sregex_iterator it(text.begin(), text.end(), label_pattern()), end; it != end; ++it) {
    const std::string l = (*it)[2].str() + (*it)[3].str();
    if (std::find(out.begin(), out.end(), l) == out.end()) out.push_back(l);
  }
  return out;
}

bool covers(const std::string& cited, const std::string& label) {
  if (cited == label) return true;
  const auto base = [](const std::string& s) { return s.substr(0, s.find('.')); };
  const bool cited_group = cited.find('.') == std::string::npos, label_group = label.find('.') == std::string::npos;
  if (label_group && !cited_group) return base(cited) == label;  // M15 ← M15.1
  if (!label_group && cited_group) return cited == base(label);  // M15.1 ← M15
  return false;
}

std::vector<FeatureRow> feature_rows(const std::string& model_md) {
  enum class Table { none, code, not_checkable };
  std::vector<FeatureRow> rows;
  std::map<std::string, std::string> reasons;  // equations cell → why no study checks it
  std::istringstream in(model_md);
  std::string line;
  Table table = Table::none;
  while (std::getline(in, line)) {
    if (line.rfind("|", 0) != 0) {
      table = Table::none;
      continue;
    }
    const auto c = cells(line);
    if (table == Table::none) {
      if (c.size() >= 2 && c.front() == "Equations") {
        if (c.size() >= 3 && c.back() == "Code") table = Table::code;
        else if (c.back() == not_checkable_header) table = Table::not_checkable;
      }
      continue;
    }
    if (c.size() < 2 || c[0].find_first_not_of("-: ") == std::string::npos) continue;  // the |---| row
    if (table == Table::not_checkable) {
      reasons[c[0]] = c.back();
      continue;
    }
    FeatureRow r;
    r.equations = c[0];
    r.what = c[1];
    r.labels = row_labels(c[0]);
    if (!r.labels.empty()) rows.push_back(std::move(r));
  }
  for (auto& r : rows)
    if (const auto it = reasons.find(r.equations); it != reasons.end()) r.not_checkable = it->second;
  return rows;
}

std::vector<FeatureRow> match_features(std::vector<FeatureRow> rows, const std::vector<StudyReport>& studies) {
  std::set<std::string> own;
  for (const auto& r : rows) own.insert(r.labels.begin(), r.labels.end());
  for (const auto& s : studies) {
    if (!s.source.readable()) continue;
    const nlohmann::json& r = s.source.result;
    std::string checks, elsewhere;
    strings_of(array_field(r, "checks"), checks);
    for (const char* key : {"title", "requirement", "reference", "setup", "figures", "tables", "readme", "snapshots"})
      if (r.contains(key)) strings_of(r[key], elsewhere);
    const auto in_checks = cited_labels(checks), in_rest = cited_labels(elsewhere);
    for (auto& row : rows) {
      if (cites_any(in_checks, row.labels, own)) row.checked_by.push_back(s.source.folder);
      else if (cites_any(in_rest, row.labels, own)) row.shown_in.push_back(s.source.folder);
    }
  }
  return rows;
}

std::string features_html(const std::vector<FeatureRow>& rows) {
  const auto [checked, explained] = counts(rows);
  std::string out = fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n", features_section_id, features_section_title);
  out += "<style>tr.unchecked td:first-child { background: #fff1e5; color: #953800; font-weight: bold; }"
         " tr.not-checkable td:first-child { background: #f3f4f6; color: #57606a; }"
         " table.features td:nth-child(3), table.features td:nth-child(4) { font-size: 0.9em; }</style>\n";
  out += fmt::format(
      "<p>Each row of the code-site tables of docs/model.md (an equation or a group of them) against the studies "
      "of this report: a study <strong>checks</strong> a row when one of its check rows cites a label of it, and "
      "<strong>shows</strong> it when only its text, figures or README do (labels cited as written, a group "
      "label covering its sub-labels unless both head rows of their own, as M19 and M19.r). <strong>{} of {}</strong> rows are checked; not checkable by a study output on its "
      "own (a definition or a choice; the reason stands in the row, from docs/model.md): {}; unchecked, marked: {}.</p>\n",
      checked, rows.size(), explained, rows.size() - checked - explained);
  out += "<table class=\"features\">\n<thead><tr><th>Equations</th><th>What</th><th>Checked by</th><th>Shown in</th></tr></thead>\n<tbody>\n";
  for (const auto& r : rows)
    out += fmt::format("<tr{}><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", row_class(r), html_escape(r.equations),
                       html_escape(r.what), checked_html(r), study_list_html(r.shown_in));
  return out + "</tbody>\n</table>\n</section>\n";
}

std::string features_markdown(const std::vector<FeatureRow>& rows) {
  const auto [checked, explained] = counts(rows);
  std::string out = fmt::format("<a id=\"{}\"></a>\n\n## {}\n\n", features_section_id, features_section_title);
  out += fmt::format("{} of {} rows of docs/model.md's code-site tables are checked by a study (a check row cites a "
                     "label of the row); not checkable by a study output on its own (a definition or a choice; the reason stands in "
                     "the row): {}; unchecked, in bold: {}.\n\n| Equations | What | Checked by | Shown in |\n|---|---|---|---|\n",
                     checked, rows.size(), explained, rows.size() - checked - explained);
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& f : v) s += (s.empty() ? "" : ", ") + markdown_escape(f);
    return s.empty() ? std::string(missing_value) : s;
  };
  for (const auto& r : rows) {
    const std::string eq = markdown_escape(r.equations);
    const bool unchecked = r.checked_by.empty() && r.not_checkable.empty();
    const std::string by = r.checked_by.empty() && !r.not_checkable.empty() ? "not checkable: " + markdown_escape(r.not_checkable)
                                                                             : list(r.checked_by);
    out += "| " + (unchecked ? "**" + eq + "**" : eq) + " | " + markdown_escape(r.what) + " | " + by + " | " + list(r.shown_in) + " |\n";
  }
  return out + "\n";
}

}  // namespace report
