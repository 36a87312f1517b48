#include "cited_docs.hpp"

#include <cctype>
#include <cstdlib>
#include <regex>
#include <set>
#include <vector>

#include <cmark-gfm-core-extensions.h>
#include <cmark-gfm-extension_api.h>
#include <cmark-gfm.h>

#include <fmt/format.h>

#include "text_format.hpp"

namespace report {

namespace {

namespace fs = std::filesystem;

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

/// The text of an inline subtree: text and code as written, line breaks as spaces, markup dropped.
std::string plain_text(cmark_node* node) {
  std::string out;
  cmark_iter* it = cmark_iter_new(node);
  for (cmark_event_type ev; (ev = cmark_iter_next(it)) != CMARK_EVENT_DONE;) {
    if (ev != CMARK_EVENT_ENTER) continue;
    cmark_node* n = cmark_iter_get_node(it);
    const auto type = cmark_node_get_type(n);
    if (type == CMARK_NODE_TEXT || type == CMARK_NODE_CODE) out += cmark_node_get_literal(n);
    else if (type == CMARK_NODE_SOFTBREAK || type == CMARK_NODE_LINEBREAK) out += ' ';
  }
  cmark_iter_free(it);
  return out;
}

/// HTML of our own (ids) in the tree: custom nodes are written as they are, also without CMARK_OPT_UNSAFE
/// (which governs the raw HTML of the Markdown text, escaped here).
cmark_node* custom_node(cmark_node_type type, const std::string& enter, const std::string& exit) {
  cmark_node* n = cmark_node_new(type);
  cmark_node_set_on_enter(n, enter.c_str());
  cmark_node_set_on_exit(n, exit.c_str());
  return n;
}

/// One document → HTML with cmark-gfm (CommonMark and GitHub's tables); raw HTML in the text is not passed
/// through. Anchors: headings "doc N.M" (numbered) and the labels / findings entries. `#` and `##` are
/// written as <h{top}>, `###` as <h{top+1}>, …, at most <h6>.
std::string render_md(const std::string& doc, const std::string& text, std::map<std::string, std::string>& anchors,
                      int top) {
  static const bool registered = [] {
    cmark_gfm_core_extensions_ensure_registered();
    return true;
  }();
  (void)registered;
  const int options = CMARK_OPT_DEFAULT;
  cmark_parser* parser = cmark_parser_new(options);
  if (cmark_syntax_extension* table = cmark_find_syntax_extension("table"))
    cmark_parser_attach_syntax_extension(parser, table);
  cmark_parser_feed(parser, text.data(), text.size());
  cmark_node* root = cmark_parser_finish(parser);

  std::vector<cmark_node*> blocks, raw;  // headings and paragraphs in the order of the text; raw HTML
  cmark_iter* it = cmark_iter_new(root);
  for (cmark_event_type ev; (ev = cmark_iter_next(it)) != CMARK_EVENT_DONE;) {
    cmark_node* n = cmark_iter_get_node(it);
    const auto type = cmark_node_get_type(n);
    if (ev == CMARK_EVENT_ENTER && (type == CMARK_NODE_HEADING || type == CMARK_NODE_PARAGRAPH)) blocks.push_back(n);
    if (ev == CMARK_EVENT_ENTER && (type == CMARK_NODE_HTML_INLINE || type == CMARK_NODE_HTML_BLOCK)) raw.push_back(n);
  }
  cmark_iter_free(it);
  // raw HTML is shown as text, escaped (cmark would leave it out as "<!-- raw HTML omitted -->")
  for (cmark_node* n : raw) {
    cmark_node* t = cmark_node_new(CMARK_NODE_TEXT);
    cmark_node_set_literal(t, cmark_node_get_literal(n));
    if (cmark_node_get_type(n) == CMARK_NODE_HTML_BLOCK) {
      cmark_node* p = cmark_node_new(CMARK_NODE_PARAGRAPH);
      cmark_node_append_child(p, t);
      t = p;
    }
    cmark_node_replace(n, t);
    cmark_node_free(n);
  }

  std::set<std::string> used;  // ids given in this text
  auto unique = [&](const std::string& base) {
    std::string id = base;
    for (int k = 2; used.count(id); ++k) id = base + "-" + std::to_string(k);
    used.insert(id);
    return id;
  };
  bool after_first_section = false;
  for (cmark_node* n : blocks) {
    if (cmark_node_get_type(n) == CMARK_NODE_HEADING) {
      const int level = cmark_node_get_heading_level(n);
      const std::string title = plain_text(n);
      static const std::regex number("^([0-9]+(?:\\.[0-9]+)*)\\.?\\s");
      std::smatch m;
      std::string id = "doc-" + doc + "-" + slug(title);
      if (std::regex_search(title, m, number)) id = "doc-" + doc + "-" + slug(std::string(m[1]));
      if (level == 1) id = "doc-" + doc;
      id = unique(id);
      if (level == 1) anchors["doc " + doc] = id;
      else if (m.size() > 1 && m[1].matched) anchors[doc + " " + std::string(m[1])] = id;
      if (level == 2) after_first_section = true;
      const int h = std::min(6, std::max(top, top + level - 2));
      // the heading with its id: a custom block around the heading's inline content
      cmark_node* block = custom_node(CMARK_NODE_CUSTOM_BLOCK, fmt::format("<h{} id=\"{}\">", h, id),
                                      fmt::format("</h{}>", h));
      while (cmark_node* child = cmark_node_first_child(n)) {
        cmark_node_unlink(child);
        cmark_node_append_child(block, child);
      }
      cmark_node_replace(n, block);
      cmark_node_free(n);
      continue;
    }
    std::string ids;
    if (doc == "model" && after_first_section)
      for (const auto& l : labels_in(plain_text(n)))
        if (!anchors.count(l)) {
          const std::string id = unique("doc-model-" + slug(l));
          anchors[l] = id;
          ids += "<a id=\"" + id + "\"></a>";
        }
    cmark_node* first = cmark_node_first_child(n);
    static const std::regex entry("^((F[0-9]+)|([KM]-[0-9]+))(\\.| \\()");  // "F2." and "F8 (M-C)."
    std::smatch m;
    const std::string lead = first && cmark_node_get_type(first) == CMARK_NODE_STRONG ? plain_text(first) : "";
    if (doc == "findings" && std::regex_search(lead, m, entry)) {
      const std::string id = unique("doc-findings-" + std::string(m[1]));
      anchors["F " + std::string(m[1])] = id;
      ids += "<a id=\"" + id + "\"></a>";
    }
    if (!ids.empty()) cmark_node_prepend_child(n, custom_node(CMARK_NODE_CUSTOM_INLINE, ids, ""));
  }
  char* html = cmark_render_html(root, options, cmark_parser_get_syntax_extensions(parser));
  std::string out(html);
  free(html);  // NOLINT: cmark allocates with the default allocator
  cmark_node_free(root);
  cmark_parser_free(parser);
  return out;
}

}  // namespace

std::string markdown_html(const std::string& doc, const std::string& text, int top) {
  std::map<std::string, std::string> anchors;  // a text's own headings only: nothing cites them
  return render_md(doc, text, anchors, top);
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
            render_md(name, read_text_file(p), d.anchors, 3) + "</section>\n";
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
