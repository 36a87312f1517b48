// The report's citations link to the project's own docs/ rendered into the page (reports/cited_docs.hpp).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "cited_docs.hpp"

namespace {

const report::CitedDocs& real_docs() {
  static const report::CitedDocs d = report::render_cited_docs(std::string(DEM2D_SOURCE_DIR) + "/docs");
  return d;
}

}  // namespace

TEST_CASE("The repository's docs render with an anchor per section, equation label and finding", "[report][docs]") {
  const auto& d = real_docs();
  REQUIRE_FALSE(d.html.empty());
  CHECK(report::citation_anchor(d, "references 1.6") == "doc-references-1-6");
  CHECK(report::citation_anchor(d, "references 1.6.9") == "doc-references-1-6");  // falls back to the parent
  CHECK(report::citation_anchor(d, "model 2") == "doc-model-2");
  CHECK(report::citation_anchor(d, "K19") == "doc-model-K19");
  CHECK(report::citation_anchor(d, "K22.a") != "");
  CHECK(report::citation_anchor(d, "M15.1") == "doc-model-M15-1");
  // sub-equations are written with a dot (docs/model.md): the shear spring's K10.a has its own anchor
  CHECK(report::citation_anchor(d, "K6.a") == "doc-model-K6-a");
  CHECK(report::citation_anchor(d, "K10.a") == "doc-model-K10-a");
  // the label → code tables render, a glob in code as written
  CHECK(d.html.find("<td><code>lib/dem/contact/face_contact*</code></td>") != std::string::npos);
  CHECK(report::citation_anchor(d, "F F1") == "doc-findings-F1");
  CHECK(report::citation_anchor(d, "F K-3") == "doc-findings-K-3");
  CHECK(report::citation_anchor(d, "F F8") == "doc-findings-F8");  // "**F8 (M-C). …"
  CHECK(report::citation_anchor(d, "doc findings") == "doc-findings");
  // every anchor a citation can resolve to exists in the page once
  for (const auto& [key, id] : d.anchors) {
    const std::string attr = "id=\"" + id + "\"";
    const auto first = d.html.find(attr);
    CHECK(first != std::string::npos);
    CHECK(d.html.find(attr, first + 1) == std::string::npos);
  }
  // every equation label of both papers has an anchor (K1–K28, M1–M26)
  for (const auto& [paper, last] : {std::pair<char, int>{'K', 28}, std::pair<char, int>{'M', 26}})
    for (int k = 1; k <= last; ++k) {
      std::string label(1, paper);
      label += std::to_string(k);
      INFO(label);
      CHECK(report::citation_anchor(d, label) != "");
    }
}

TEST_CASE("Citations in text are linked, not inside tags, links, figures or unknown labels", "[report][docs]") {
  const auto& d = real_docs();
  const std::string page =
      "<p>tolerance from refs §1.6 and (K19); M15.1 linearised; shear spring (K10.a); see findings F2 and docs/findings.md.</p>"
      "<p>closed forms of docs/references.md §1.2</p>"
      "<p title=\"refs §1.6\">K99 and M27 are no labels; M-A is a case</p>"
      "<svg><text>K19</text></svg><a href=\"x\">refs §2</a>";
  const std::string out = report::link_citations(page, d);
  CHECK(out.find("<a class=\"cite\" href=\"#doc-references-1-6\">refs §1.6</a>") != std::string::npos);
  CHECK(out.find("(<a class=\"cite\" href=\"#doc-model-K19\">K19</a>)") != std::string::npos);
  CHECK(out.find("<a class=\"cite\" href=\"#doc-model-M15-1\">M15.1</a>") != std::string::npos);
  CHECK(out.find("(<a class=\"cite\" href=\"#doc-model-K10-a\">K10.a</a>)") != std::string::npos);
  CHECK(out.find("href=\"#doc-findings-F2\">findings F2</a>") != std::string::npos);
  CHECK(out.find("href=\"#doc-findings\">docs/findings.md</a>") != std::string::npos);
  CHECK(out.find("href=\"#doc-references-1-2\">docs/references.md §1.2</a>") != std::string::npos);
  CHECK(out.find("<p title=\"refs §1.6\">K99 and M27 are no labels; M-A is a case</p>") != std::string::npos);
  CHECK(out.find("<svg><text>K19</text></svg><a href=\"x\">refs §2</a>") != std::string::npos);
  // without docs nothing changes
  CHECK(report::link_citations(page, report::CitedDocs{}) == page);
}

TEST_CASE("Markdown renders with cmark-gfm (tables and emphasis and lists) and raw HTML stays escaped", "[report][docs]") {
  const std::string html = report::markdown_html(
      "readme-x", "## Measured (K19)\n\n| | K19 1e-4 |\n|---|---|\n| rate | **61.9** \\| 62 |\n\n"
                  "**Reference.** a <script>alert(1)</script> text\n\n- one\n- two\n",
      4);
  CHECK(html.find("<h4 id=\"doc-readme-x-Measured--K19-\">") != std::string::npos);  // `##` below the study's <h3>
  CHECK(html.find("<th>K19 1e-4</th>") != std::string::npos);
  CHECK(html.find("<td><strong>61.9</strong> | 62</td>") != std::string::npos);  // an escaped pipe in a cell
  CHECK(html.find("<p><strong>Reference.</strong> a &lt;script&gt;alert(1)&lt;/script&gt; text</p>") != std::string::npos);
  CHECK(html.find("<li>one</li>") != std::string::npos);
  CHECK(html.find("|---|") == std::string::npos);
  CHECK(html.find("<script>") == std::string::npos);
}

TEST_CASE("A range of labels anchors each label from its first to its last and no further", "[report][docs]") {
  // a model.md of its own: a section, then one paragraph that states the range (K16–K19) and (M3-M5)
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "dem2d_cited_docs_range";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "model.md") << "# Model\n\n## 1 Contacts\n\nThe averaged increments (K16–K19) and (M3-M5), and (M7).\n";
  const report::CitedDocs d = report::render_cited_docs(dir);
  for (const char* label : {"K16", "K17", "K18", "K19", "M3", "M4", "M5", "M7"}) {
    CAPTURE(label);
    CHECK(report::citation_anchor(d, label) == std::string("doc-model-") + label);
  }
  for (const char* label : {"K15", "K20", "M2", "M6"}) {
    CAPTURE(label);
    CHECK(report::citation_anchor(d, label) == "");
  }
  std::filesystem::remove_all(dir);
}
