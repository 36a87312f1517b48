#include "cited_docs.hpp"

#include <cctype>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "text_format.hpp"

namespace report {

namespace {

namespace fs = std::filesystem;

bool starts_with(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }

/// Inline Markdown on escaped text: `code`, **bold**.
std::string inline_md(const std::string& raw) {
  std::string t = html_escape(raw);
  static const std::regex code("`([^`]+)`"), letter("\\*([A-Za-z])\\*"), bold("\\*\\*([^*]+)\\*\\*"),
      italic("\\*([^*\\s][^*]*)\\*");
  static const std::regex bold_italic_tail("\\*\\*([^*]+)\\*([^*]+)\\*\\*\\*");  // **K*n***
  t = std::regex_replace(t, code, "<code>$1</code>");
  t = std::regex_replace(t, bold_italic_tail, "<strong>$1<em>$2</em></strong>");
  t = std::regex_replace(t, letter, "<em>$1</em>");  // "**K*n***": the letter first, then the bold around it
  t = std::regex_replace(t, bold, "<strong>$1</strong>");
  t = std::regex_replace(t, italic, "<em>$1</em>");
  return t;
}

std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cur;
  for (std::size_t k = 1; k < line.size(); ++k) {
    if (line[k] == '|' && line[k - 1] != '\\') {
      cells.push_back(cur);
      cur.clear();
    } else {
      cur += line[k];
    }
  }
  for (auto& c : cells) {
    const auto a = c.find_first_not_of(' '), b = c.find_last_not_of(' ');
    c = a == std::string::npos ? std::string() : c.substr(a, b - a + 1);
  }
  return cells;
}

/// The equation labels a paragraph of model.md states: "(K19", "(M15.1)", and every label of a range
/// "(K16–K19)".
std::vector<std::string> labels_in(const std::string& text) {
  std::vector<std::string> out;
  // a label opening a parenthesis or following a comma / semicolon inside one: "(M1, M13)", "(M20; refs …)"
  static const std::regex label("(?:\\(|, |; )([KM])([0-9]{1,2})((?:\\.[a-z0-9]+)?)(?:(?:–|-)\\1([0-9]{1,2}))?\\b");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), label); it != std::sregex_iterator(); ++it) {
    const std::string letter = (*it)[1];
    const int a = std::stoi((*it)[2]);
    out.push_back(letter + std::to_string(a) + std::string((*it)[3]));
    if ((*it)[3].length() > 0) out.push_back(letter + std::to_string(a));  // M13.1 also anchors M13
    if ((*it)[4].matched)
      for (int k = a + 1; k <= std::stoi((*it)[4]); ++k) out.push_back(letter + std::to_string(k));
  }
  return out;
}

/// One document → HTML; anchors: headings "doc N.M" (numbered) and the labels / findings entries.
std::string render_md(const std::string& doc, const std::string& text, std::map<std::string, std::string>& anchors) {
  std::istringstream in(text);
  std::string line, out, para;
  std::vector<std::string> table, list;
  bool fence = false, after_first_section = false;
  std::string pre;
  auto flush_para = [&] {
    if (para.empty()) return;
    std::string ids;
    if (doc == "model" && after_first_section)
      for (const auto& l : labels_in(para))
        if (!anchors.count(l)) {
          const std::string id = "doc-model-" + slug(l);
          anchors[l] = id;
          ids += "<a id=\"" + id + "\"></a>";
        }
    static const std::regex entry("^\\*\\*((F[0-9]+)|([KM]-[0-9]+))\\.");
    std::smatch m;
    if (doc == "findings" && std::regex_search(para, m, entry)) {
      const std::string id = "doc-findings-" + std::string(m[1]);
      anchors["F " + std::string(m[1])] = id;
      ids += "<a id=\"" + id + "\"></a>";
    }
    out += "<p>" + ids + inline_md(para) + "</p>\n";
    para.clear();
  };
  auto flush_table = [&] {
    if (table.empty()) return;
    out += "<table>\n";
    bool head = true;
    for (const auto& row : table) {
      const auto cells = table_cells(row);
      if (!cells.empty() && cells[0].find("---") != std::string::npos) continue;
      out += "<tr>";
      for (const auto& c : cells) out += (head ? "<th>" : "<td>") + inline_md(c) + (head ? "</th>" : "</td>");
      out += "</tr>\n";
      head = false;
    }
    out += "</table>\n";
    table.clear();
  };
  auto flush_list = [&] {
    if (list.empty()) return;
    out += "<ul>\n";
    for (const auto& item : list) {
      para = item;
      std::string before = out;
      out.clear();
      flush_para();
      std::string li = out;  // "<p>…</p>\n" → "<li>…</li>\n"
      out = before + "<li>" + li.substr(3, li.size() - 8) + "</li>\n";
    }
    out += "</ul>\n";
    list.clear();
  };
  auto flush_all = [&] {
    flush_para();
    flush_table();
    flush_list();
  };
  while (std::getline(in, line)) {
    if (starts_with(line, "```")) {
      if (fence) {
        out += "<pre>" + html_escape(pre) + "</pre>\n";
        pre.clear();
      } else {
        flush_all();
      }
      fence = !fence;
      continue;
    }
    if (fence) {
      pre += line + "\n";
      continue;
    }
    if (line.empty()) {
      flush_all();
      continue;
    }
    if (line.size() >= 3 && line.find_first_not_of('-') == std::string::npos) {  // a rule
      flush_all();
      out += "<hr>\n";
      continue;
    }
    if (line[0] == '#') {
      flush_all();
      const auto level = line.find_first_not_of('#');
      const std::string title = line.substr(std::min(line.size(), level + 1));
      static const std::regex number("^([0-9]+(?:\\.[0-9]+)*)\\.?\\s");
      std::smatch m;
      std::string id = "doc-" + doc + "-" + slug(title);
      if (std::regex_search(title, m, number)) {
        id = "doc-" + doc + "-" + slug(std::string(m[1]));
        anchors[doc + " " + std::string(m[1])] = id;
      }
      if (level == 1) anchors["doc " + doc] = id = "doc-" + doc;
      if (level == 2) after_first_section = true;
      const int h = static_cast<int>(std::min<std::size_t>(std::max<std::size_t>(level + 1, 3), 6));  // #, ## → h3
      out += fmt::format("<h{} id=\"{}\">{}</h{}>\n", h, id, inline_md(title), h);
      continue;
    }
    if (line[0] == '|') {
      flush_para();
      flush_list();
      table.push_back(line);
      continue;
    }
    if (starts_with(line, "- ") || starts_with(line, "* ")) {
      flush_para();
      flush_table();
      list.push_back(line.substr(2));
      continue;
    }
    if (!list.empty() && starts_with(line, "  ")) {
      list.back() += " " + line.substr(line.find_first_not_of(' '));
      continue;
    }
    flush_table();
    flush_list();
    para += (para.empty() ? "" : " ") + line;
  }
  flush_all();
  if (fence) out += "<pre>" + html_escape(pre) + "</pre>\n";
  return out;
}

}  // namespace

std::string markdown_html(const std::string& doc, const std::string& text) {
  std::map<std::string, std::string> anchors;  // a text's own headings only: nothing cites them
  return render_md(doc, text, anchors);
}

CitedDocs render_cited_docs(const fs::path& docs_dir) {
  CitedDocs d;
  const std::vector<std::pair<std::string, std::string>> docs = {
      {"model", "The physics (docs/model.md)"},
      {"references", "The reference solutions (docs/references.md)"},
      {"findings", "Findings about the papers (docs/findings.md)"}};
  std::string body;
  for (const auto& [name, title] : docs) {
    const fs::path p = docs_dir / (name + ".md");
    if (!fs::is_regular_file(p)) continue;
    body += "<section class=\"doc\" id=\"doc-section-" + name + "\">\n<h2>" + html_escape(title) + "</h2>\n" +
            render_md(name, read_text_file(p), d.anchors) + "</section>\n";
  }
  if (body.empty()) return d;
  d.html = "<div id=\"cited-docs\">\n<p class=\"small\">The project's own documentation, as in the repository's "
           "<code>docs/</code> when this report was written; every citation on this page links here.</p>\n" +
           body + "</div>\n";
  return d;
}

std::string citation_anchor(const CitedDocs& docs, std::string key) {
  while (true) {
    const auto it = docs.anchors.find(key);
    if (it != docs.anchors.end()) return it->second;
    const auto dot = key.rfind('.');
    if (dot == std::string::npos || dot < key.find(' ') + 1) break;
    key.resize(dot);
  }
  return "";
}

std::string link_citations(const std::string& html, const CitedDocs& docs) {
  if (docs.anchors.empty()) return html;
  static const std::regex cite(
      "((?:refs|(?:docs/)?references\\.md)\\s+§\\s?([0-9]+(?:\\.[0-9]+)*))"   // 1, 2
      "|((?:docs/)?model\\.md\\s+§\\s?([0-9]+(?:\\.[0-9]+)*))"                 // 3, 4
      "|((?:docs/)?findings(?:\\.md)?,?\\s+(F[0-9]+|[KM]-[0-9]+))"   // 5, 6
      "|(docs/(model|references|findings)\\.md)"                     // 7, 8
      "|\\b(([KM])([0-9]{1,2})(?:\\.[a-z0-9]+)?)\\b(?![-.][A-Za-z0-9])");  // 9, 10, 11
  auto link_text = [&](const std::string& text) {
    std::string out;
    auto last = text.cbegin();
    for (auto it = std::sregex_iterator(text.begin(), text.end(), cite); it != std::sregex_iterator(); ++it) {
      const std::smatch& m = *it;
      std::string key;
      if (m[1].matched) key = "references " + std::string(m[2]);
      else if (m[3].matched) key = "model " + std::string(m[4]);
      else if (m[5].matched) key = "F " + std::string(m[6]);
      else if (m[7].matched) key = "doc " + std::string(m[8]);
      else {
        const int n = std::stoi(m[11]);
        if (n < 1 || n > (m[10] == "K" ? 28 : 26)) continue;
        key = m[9];
      }
      const std::string id = citation_anchor(docs, key);
      if (id.empty()) continue;
      out.append(last, m[0].first);
      out += "<a class=\"cite\" href=\"#" + id + "\">" + std::string(m[0]) + "</a>";
      last = m[0].second;
    }
    out.append(last, text.cend());
    return out;
  };
  std::string out;
  out.reserve(html.size() + html.size() / 8);
  int skip = 0;  // inside <a>, <svg>, <style>, <script>, <title>
  std::size_t k = 0;
  while (k < html.size()) {
    if (html[k] == '<') {
      const std::size_t end = html.find('>', k);
      if (end == std::string::npos) {
        out.append(html, k, std::string::npos);
        break;
      }
      const std::string tag = html.substr(k, end - k + 1);
      auto is = [&](const char* name) {
        const std::string n(name);
        return tag.compare(1, n.size(), n) == 0 && (tag.size() == n.size() + 2 || !std::isalnum(static_cast<unsigned char>(tag[n.size() + 1])));
      };
      for (const char* t : {"a", "svg", "style", "script", "title", "h1", "h2", "h3", "h4", "h5", "h6"}) {
        if (is(t)) ++skip;
        if (is((std::string("/") + t).c_str())) --skip;
      }
      out += tag;
      k = end + 1;
      continue;
    }
    const std::size_t next = std::min(html.find('<', k), html.size());
    const std::string text = html.substr(k, next - k);
    out += skip > 0 ? text : link_text(text);
    k = next;
  }
  return out;
}

}  // namespace report
