// The map of what is verified (feature_matrix.hpp).
#include "feature_matrix.hpp"

#include <fmt/format.h>

#include <algorithm>
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

bool cites_any(const std::vector<std::string>& cited, const std::vector<std::string>& labels) {
  for (const auto& c : cited)
    for (const auto& l : labels)
      if (covers(c, l)) return true;
  return false;
}

std::string study_list_html(const std::vector<std::string>& folders) {
  std::string out;
  for (const auto& f : folders) out += fmt::format("{}<a href=\"#study-{}\">{}</a>", out.empty() ? "" : ", ", f, html_escape(f));
  return out.empty() ? std::string(missing_value) : out;
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
  std::vector<FeatureRow> rows;
  std::istringstream in(model_md);
  std::string line;
  bool in_table = false;
  while (std::getline(in, line)) {
    if (line.rfind("|", 0) != 0) {
      in_table = false;
      continue;
    }
    const auto c = cells(line);
    if (!in_table) {
      in_table = c.size() >= 3 && c.front() == "Equations" && c.back() == "Code";
      continue;
    }
    if (c.size() < 2 || c[0].find_first_not_of("-: ") == std::string::npos) continue;  // the |---| row
    FeatureRow r;
    r.equations = c[0];
    r.what = c[1];
    r.labels = row_labels(c[0]);
    if (!r.labels.empty()) rows.push_back(std::move(r));
  }
  return rows;
}

std::vector<FeatureRow> match_features(std::vector<FeatureRow> rows, const std::vector<StudyReport>& studies) {
  for (const auto& s : studies) {
    if (!s.source.readable()) continue;
    const nlohmann::json& r = s.source.result;
    std::string checks, elsewhere;
    strings_of(array_field(r, "checks"), checks);
    for (const char* key : {"title", "requirement", "reference", "setup", "figures", "tables", "readme", "snapshots"})
      if (r.contains(key)) strings_of(r[key], elsewhere);
    const auto in_checks = cited_labels(checks), in_rest = cited_labels(elsewhere);
    for (auto& row : rows) {
      if (cites_any(in_checks, row.labels)) row.checked_by.push_back(s.source.folder);
      else if (cites_any(in_rest, row.labels)) row.shown_in.push_back(s.source.folder);
    }
  }
  return rows;
}

std::string features_html(const std::vector<FeatureRow>& rows) {
  const auto checked = std::count_if(rows.begin(), rows.end(), [](const FeatureRow& r) { return !r.checked_by.empty(); });
  std::string out = fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n", features_section_id, features_section_title);
  out += "<style>tr.unchecked td:first-child { background: #fff1e5; color: #953800; font-weight: bold; }"
         " table.features td:nth-child(3), table.features td:nth-child(4) { font-size: 0.9em; }</style>\n";
  out += fmt::format(
      "<p>Each row of the code-site tables of docs/model.md (an equation or a group of them) against the studies "
      "of this report: a study <strong>checks</strong> a row when one of its check rows cites a label of it, and "
      "<strong>shows</strong> it when only its text, figures or README do (labels cited as written, a group "
      "label covering its sub-labels). <strong>{} of {}</strong> rows are checked; the others are marked.</p>\n",
      checked, rows.size());
  out += "<table class=\"features\">\n<thead><tr><th>Equations</th><th>What</th><th>Checked by</th><th>Shown in</th></tr></thead>\n<tbody>\n";
  for (const auto& r : rows)
    out += fmt::format("<tr{}><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", r.checked_by.empty() ? " class=\"unchecked\"" : "",
                       html_escape(r.equations), html_escape(r.what), study_list_html(r.checked_by), study_list_html(r.shown_in));
  return out + "</tbody>\n</table>\n</section>\n";
}

std::string features_markdown(const std::vector<FeatureRow>& rows) {
  const auto checked = std::count_if(rows.begin(), rows.end(), [](const FeatureRow& r) { return !r.checked_by.empty(); });
  std::string out = fmt::format("<a id=\"{}\"></a>\n\n## {}\n\n", features_section_id, features_section_title);
  out += fmt::format("{} of {} rows of docs/model.md's code-site tables are checked by a study (a check row cites a "
                     "label of the row); the others are in bold.\n\n| Equations | What | Checked by | Shown in |\n|---|---|---|---|\n",
                     checked, rows.size());
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& f : v) s += (s.empty() ? "" : ", ") + markdown_escape(f);
    return s.empty() ? std::string(missing_value) : s;
  };
  for (const auto& r : rows) {
    const std::string eq = markdown_escape(r.equations);
    out += "| " + (r.checked_by.empty() ? "**" + eq + "**" : eq) + " | " + markdown_escape(r.what) + " | " + list(r.checked_by) +
           " | " + list(r.shown_in) + " |\n";
  }
  return out + "\n";
}

}  // namespace report
