// The project's own documentation inside the report: docs/model.md, docs/references.md and
// docs/findings.md rendered as the page's last part, every heading, equation label (K1–K28, M1–M26)
// and findings entry (F1, K-3, M-4) with an anchor, and every citation in the page ("refs §1.6",
// "references.md §2.3", "model.md §2", "(K19)", "M15.1", "findings F2", "docs/findings.md") linked to it.
// Why in the page and not links to the .md files: the report stays one file that works offline from a
// fresh clone and when sent to a reviewer without the repository; a browser does not render Markdown
// (file:// .md shows as plain text or is downloaded) and the cited anchors would not exist.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace report {

struct CitedDocs {
  std::string html;                            // the rendered documents (empty: docs/ not found)
  std::map<std::string, std::string> anchors;  // citation key ("refs 1.6", "model 2", "K19", "F1", "doc findings") → id
};

/// Renders docs_dir/{model,references,findings}.md; missing files are left out.
CitedDocs render_cited_docs(const std::filesystem::path& docs_dir);

/// One Markdown text (CommonMark with GitHub's tables, rendered by cmark-gfm; raw HTML in it is escaped)
/// as HTML, as the documents are rendered; heading ids start with "doc-<doc>-". `#` and `##` become
/// <h{top}>, `###` <h{top+1}>, and so on (at most <h6>).
std::string markdown_html(const std::string& doc, const std::string& text, int top = 3);

/// Links every citation in the text of an HTML page (outside tags, <a>, <svg>, <style>, <script>) to
/// its anchor; a citation without an anchor stays text. Returns the page.
std::string link_citations(const std::string& html, const CitedDocs& docs);

/// The anchor id a citation key resolves to ("" if none): a label falls back to its main number
/// (K22.a → K22), a section to its parent (refs §1.6.2 → refs 1.6 → refs 1).
std::string citation_anchor(const CitedDocs& docs, std::string key);

}  // namespace report
