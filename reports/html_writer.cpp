// HTML page writer.
#include "html_writer.hpp"

#include <fmt/format.h>

#include "cited_docs.hpp"
#include "inline_svg.hpp"
#include "feature_matrix.hpp"
#include "paper_claims_table.hpp"
#include "sensitivity_overview.hpp"
#include "text_format.hpp"

namespace report {

namespace {

constexpr const char* style_sheet = R"(
body { font-family: -apple-system, "Segoe UI", Helvetica, Arial, sans-serif; color: #1f2328;
       line-height: 1.45; max-width: 1340px; margin: 0 auto; padding: 0 1.5em 3em; }
h1 { margin: 1em 0 .4em; }
h2 { border-bottom: 1px solid #d0d7de; padding-bottom: .2em; margin-top: 2.2em; }
h3 { margin: 1.4em 0 .4em; }
table { border-collapse: collapse; margin: .4em 0 1em; font-size: .9em; }
th, td { border: 1px solid #d0d7de; padding: .25em .6em; text-align: left; vertical-align: top; }
th { background: #f6f8fa; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
table.meta th { width: 11em; }
.badge { display: inline-block; padding: .05em .6em; border-radius: .8em; font-size: .8em;
         font-weight: 600; vertical-align: middle; }
.pass { background: #dafbe1; color: #116329; }
.fail { background: #ffebe9; color: #a40e26; }
.unreadable { background: #fff1e5; color: #953800; }
.na { background: #eaeef2; color: #57606a; }
td.pass, td.fail, td.unreadable, td.na { font-weight: 600; text-align: center; }
.counts { font-size: 1.05em; }
.requirement { font-size: 1.05em; }
.plots { display: grid; grid-template-columns: repeat(auto-fill, minmax(440px, 1fr)); gap: 1.2em; }
figure { margin: 0; }
figure svg { width: 100%; height: auto; display: block; border: 1px solid #eaeef2; }
.gallery { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
figure.snapshot { max-width: 100%; }
figure.snapshot img { width: 100%; height: auto; display: block; border: 1px solid #eaeef2; }
figcaption { font-size: .9em; color: #57606a; margin-top: .2em; }
.note { color: #953800; font-style: italic; font-size: .9em; }
.missing-figure { border: 1px dashed #d0d7de; padding: 2em 1em; color: #953800; }
.small { font-size: .85em; color: #57606a; }
pre { background: #f6f8fa; padding: .8em; overflow-x: auto; }
.readme { font-size: .92em; background: #f6f8fa; padding: .1em .8em; }
.readme table { background: #fff; }
.readme h4 { margin: .8em 0 .3em; }
table.overview td:nth-child(2) { max-width: 38em; }
footer { margin-top: 3em; font-size: .85em; color: #57606a; }
nav#toc ol { columns: 2; column-gap: 2.5em; font-size: .92em; }
nav#toc .badge { font-size: .7em; }
a.cite { text-decoration: none; border-bottom: 1px dotted #0969da; }
section.doc { font-size: .93em; }
section.doc h3 { font-size: 1.25em; }
)";

std::string escape(const std::string& text) { return html_escape(text); }

std::string badge(const std::string& status) {
  return fmt::format("<span class=\"badge {}\">{}</span>", status_class(status), escape(status));
}

std::string status_cell(const std::string& status) {
  return fmt::format("<td class=\"{}\">{}</td>", status_class(status), escape(status));
}

std::string num_cell(const std::string& text) {
  return "<td class=\"num\">" + escape(text) + "</td>";
}
std::string cell(const std::string& text) { return "<td>" + escape(text) + "</td>"; }

std::string key_value_table(const std::vector<HeaderField>& fields, const char* css_class) {
  std::string out = fmt::format("<table class=\"{}\">\n", css_class);
  for (const auto& f : fields)
    out += "<tr><th>" + escape(f.label) + "</th>" + cell(f.value) + "</tr>\n";
  return out + "</table>\n";
}

std::string summary_section(const ReportContent& content) {
  const auto counts = count_outcomes(content);
  std::string out = "<section id=\"summary\">\n<h2>Summary</h2>\n<p class=\"counts\">";
  out += fmt::format(
      "<span class=\"badge pass\">{} passed</span> "
      "<span class=\"badge fail\">{} failed</span> ",
      counts.checks_passed, counts.checks_failed);
  if (counts.checks_other > 0)
    out += fmt::format("<span class=\"badge na\">{} without verdict</span> ", counts.checks_other);
  out += fmt::format("of {} checks in {} studies ({} passed, {} failed",
                     counts.checks_passed + counts.checks_failed + counts.checks_other,
                     content.studies.size(), counts.studies_passed, counts.studies_failed);
  if (counts.studies_unreadable > 0)
    out += fmt::format(", {} unreadable or broken", counts.studies_unreadable);
  if (counts.studies_other > 0) out += fmt::format(", {} without verdict", counts.studies_other);
  out += ").</p>\n";
  if (content.studies.empty()) return out + "<p>No result.json found.</p>\n</section>\n";

  out +=
      "<table class=\"checks\">\n<thead><tr><th>Study</th><th>Quantity</th><th>Reference</th>"
      "<th>DEM</th><th>Error</th><th>Tolerance</th><th>Asserts</th><th>Order (observed vs expected "
      "&plusmn; band)</th><th>Result</th></tr></thead>\n<tbody>\n";
  for (const auto& study : content.studies) {
    const auto& source = study.source;
    const auto link = fmt::format("<td><a href=\"#{}\">{}</a></td>", study_anchor(source),
                                  escape(study_name(source)));
    if (!source.readable()) {
      out += "<tr>" + link + "<td colspan=\"7\">unreadable: " + escape(source.read_error) +
             "</td>" + status_cell("UNREADABLE") + "</tr>\n";
      continue;
    }
    const auto& checks = array_field(source.result, "checks");
    if (checks.empty())
      out += "<tr>" + link + "<td colspan=\"7\">(no checks)</td>" +
             status_cell(study_status(source)) + "</tr>\n";
    for (const auto& check : checks) {
      const auto row = check_row(check);
      out += "<tr>" + link + cell(row.quantity) + num_cell(row.reference) + num_cell(row.dem) +
             num_cell(row.error) + num_cell(row.tolerance) + cell(row.asserts) +
             num_cell(row.order) + status_cell(row.status) + "</tr>\n";
    }
  }
  return out + "</tbody>\n</table>\n</section>\n";
}

std::string overview_section(const ReportContent& content) {
  std::string out =
      "<section id=\"contents\">\n<h2>Studies</h2>\n<table class=\"overview\">\n<thead><tr>"
      "<th>Study</th><th>Title</th><th>Checks passed</th><th>Checks failed</th>"
      "<th>Observed orders (expected)</th><th>Wall time</th><th>Result</th></tr></thead>\n<tbody>\n";
  for (const auto& row : overview_rows(content))
    out += fmt::format("<tr><td><a href=\"#{}\">{}</a></td>", row.anchor, escape(row.name)) +
           cell(row.title) + num_cell(std::to_string(row.passed)) +
           num_cell(std::to_string(row.failed)) + cell(row.orders) + num_cell(row.wall_time) +
           status_cell(row.status) + "</tr>\n";
  return out + "</tbody>\n</table>\n</section>\n";
}

/// Every sensitivity study in one table (sensitivity_overview.hpp); "" when there is none.
std::string sensitivity_overview_section(const ReportContent& content) {
  const auto rows = sensitivity_overview_rows(content);
  if (rows.empty()) return {};
  std::string out =
      "<section id=\"sensitivity-overview\">\n<h2>Sensitivity studies: overview</h2>\n"
      "<p>Per study and output, the most and the least influential parameter by the strongest measure the study "
      "computed: the Sobol' total index S_T with its bootstrap interval, else Morris &mu;*, else the one-at-a-time range "
      "(max &minus; min). Indices of a transformed output are labelled so (ln(y), rank(y)). With replicates, the noise "
      "fraction of a single run (run-to-run noise over noise + parameter effect) with its bootstrap interval.</p>\n"
      "<table class=\"overview\">\n<thead><tr>";
  for (const auto& c : sensitivity_overview_columns) out += "<th>" + escape(c) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& r : rows)
    out += fmt::format("<tr><td><a href=\"#{}\">{}</a></td>", r.anchor, escape(r.study)) + cell(r.output) + cell(r.measure) +
           cell(r.most) + num_cell(r.most_value) + num_cell(r.most_interval) + cell(r.least) + num_cell(r.least_value) +
           num_cell(r.least_interval) + num_cell(r.runs) + num_cell(r.failed) + num_cell(r.noise) + "</tr>\n";
  return out + "</tbody>\n</table>\n</section>\n";
}

std::string checks_table(const nlohmann::json& checks) {
  std::string out =
      "<table class=\"checks\">\n<thead><tr><th>Quantity</th><th>Reference</th>"
      "<th>DEM</th><th>Error</th><th>Tolerance</th><th>Asserts</th><th>Why this tolerance</th>"
      "<th>Order (observed vs expected &plusmn; band)</th><th>Result</th>"
      "<th>Note</th></tr></thead>\n<tbody>\n";
  for (const auto& check : checks) {
    const auto row = check_row(check);
    out += "<tr>" + cell(row.quantity) + num_cell(row.reference) + num_cell(row.dem) +
           num_cell(row.error) + num_cell(row.tolerance) + cell(row.asserts) +
           cell(row.tolerance_reason) +
           num_cell(row.order) + status_cell(row.status) + cell(row.note) + "</tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

std::string figure_block(const RenderedFigure& figure, const std::string& id_prefix, const std::string& anchor = "") {
  std::string out = anchor.empty() ? "<figure>\n" : "<figure id=\"" + anchor + "\">\n";
  if (!figure.svg.empty())
    out += inline_svg(figure.svg, id_prefix) + "\n";
  else
    out += "<div class=\"missing-figure\">" + escape(figure.note) + "</div>\n";
  out += "<figcaption>" + escape(figure.title);
  if (!figure.svg.empty() && !figure.note.empty())
    out += " <span class=\"note\">(" + escape(figure.note) + ")</span>";
  return out + "</figcaption>\n</figure>\n";
}

std::string plain_table(const std::vector<std::string>& columns,
                        const std::vector<std::vector<std::string>>& rows) {
  std::string out = "<table>\n<thead><tr>";
  for (const auto& c : columns) out += "<th>" + escape(c) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const auto& c : row) out += cell(c);
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

std::string series_block(const nlohmann::json& series, const RenderedFigure& figure,
                         const std::string& id_prefix) {
  std::string out = "<div class=\"series\">\n" + figure_block(figure, id_prefix);
  out += "<p class=\"small\">" + escape(series_summary(series)) + "</p>\n";
  out += "<table>\n<thead><tr>";
  for (const auto& c : series_level_columns) out += "<th>" + escape(c) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : series_level_rows(series)) {
    out += "<tr>";
    for (const auto& c : row) out += num_cell(c);
    out += "</tr>\n";
  }
  out += "</tbody>\n</table>\n";
  const auto& notes = array_field(series, "notes");
  for (const auto& note : notes)
    if (note.is_string()) out += "<p class=\"note\">" + escape(note.get<std::string>()) + "</p>\n";
  return out + "</div>\n";
}

std::string table_block(const nlohmann::json& table) {
  const auto data = table_data(table);
  std::string out = "<h4>" + escape(data.title) + "</h4>\n";
  if (data.preformatted) return out + "<pre>" + escape(*data.preformatted) + "</pre>\n";
  return out + plain_table(data.columns, data.rows);
}

std::string study_section(const StudyReport& study) {
  const auto& source = study.source;
  const auto& result = source.result;
  const auto status = study_status(source);
  std::string out = fmt::format("<section class=\"study\" id=\"{}\">\n", study_anchor(source));
  auto title = text_field(result, "title");
  if (title.empty()) title = study_name(source);
  out += "<h2>" + escape(title) + " " + badge(status) + "</h2>\n";
  out += "<p class=\"small\">study <code>" + escape(study_name(source)) + "</code> &middot; " +
         escape(source.path.string()) + "</p>\n";
  if (!source.readable())
    return out + "<p class=\"note\">Unreadable result file: " + escape(source.read_error) +
           "</p>\n</section>\n";

  const auto requirement = text_field(result, "requirement");
  if (!requirement.empty())
    out +=
        "<p class=\"requirement\"><strong>Requirement.</strong> " + escape(requirement) + "</p>\n";
  const auto readme = readme_parts(result);
  if (!readme.purpose.empty()) {
    // the README's Markdown rendered as the docs are (cited_docs.hpp); its headings below the study's <h3>
    const std::string doc = "readme-" + slug(source.folder);
    const std::string purpose = markdown_html(doc, readme.purpose, 4);
    const std::string label = "<p class=\"purpose\"><strong>Purpose (README).</strong>";
    out += purpose.rfind("<p>", 0) == 0 ? label + " " + purpose.substr(3) : label + "</p>\n" + purpose;
    if (!readme.rest.empty())
      out += "<details open><summary>Findings and known limits (README)</summary>\n<div class=\"readme\">\n" +
             markdown_html(doc, readme.rest, 4) + "</div>\n</details>\n";
  }
  const auto& provenance = object_field(result, "provenance");
  const auto command = text_field(provenance, "command");
  if (!command.empty()) {
    out += "<p class=\"small\">Command: <code>" + escape(command) + "</code>";
    if (number_field(provenance, "wall_time_s")) out += " &middot; wall time " + escape(wall_time_words(provenance));
    out += "</p>\n";
  }
  const auto setup = setup_fields(result);
  if (!setup.empty()) out += "<h3>Setup</h3>\n" + key_value_table(setup, "setup");
  const auto reference = text_field(result, "reference");
  if (!reference.empty()) out += "<h3>Reference</h3>\n<p>" + escape(reference) + "</p>\n";
  const auto& checks = array_field(result, "checks");
  if (!checks.empty()) out += "<h3>Checks</h3>\n" + checks_table(checks);

  const auto prefix = slug(source.folder);
  const auto& series = array_field(result, "series");
  if (!study.convergence.empty()) {
    out += "<h3>Convergence</h3>\n<div class=\"plots\">\n";
    for (std::size_t k = 0; k < study.convergence.size() && k < series.size(); ++k)
      out += series_block(series[k], study.convergence[k], fmt::format("{}-c{}-", prefix, k + 1));
    out += "</div>\n";
  }
  if (!study.figures.empty()) {
    out += "<h3>Figures</h3>\n<div class=\"plots\">\n";
    for (std::size_t k = 0; k < study.figures.size(); ++k) {
      const auto id = text_field(array_field(result, "figures")[k], "id");  // the anchor a claim links to
      out += figure_block(study.figures[k], fmt::format("{}-f{}-", prefix, k + 1), id.empty() ? "" : figure_anchor(source, id));
    }
    out += "</div>\n";
  }
  out += snapshot_gallery_html(study.snapshots, snapshot_anchor_prefix(source));
  const auto& tables = array_field(result, "tables");
  if (!tables.empty()) {
    out += "<h3>Tables</h3>\n";
    for (const auto& table : tables) out += table_block(table);
  }
  return out + "</section>\n";
}

/// The table of contents: the overview, the table of every check, each study, the cited documents.
std::string contents_nav(const ReportContent& content) {
  std::string out = "<nav id=\"toc\">\n<h2>Contents</h2>\n<ol>\n"
                    "<li><a href=\"#contents\">Studies: overview</a></li>\n"
                    "<li><a href=\"#summary\">Every check</a></li>\n";
  if (!content.claims_html.empty())
    out += fmt::format("<li><a href=\"#{}\">{}</a></li>\n", claims_section_id, claims_section_title);
  if (!content.features_html.empty())
    out += fmt::format("<li><a href=\"#{}\">{}</a></li>\n", features_section_id, features_section_title);
  if (!sensitivity_overview_rows(content).empty())
    out += "<li><a href=\"#sensitivity-overview\">Sensitivity studies: overview</a></li>\n";
  for (const auto& study : content.studies) {
    auto title = text_field(study.source.result, "title");
    if (title.empty()) title = study_name(study.source);
    out += fmt::format("<li><a href=\"#{}\">{}</a> {}</li>\n", study_anchor(study.source), escape(title),
                       badge(study_status(study.source)));
  }
  if (!content.speed_html.empty()) out += "<li><a href=\"#speed\">Speed: dem2d beside LAMMPS</a></li>\n";
  if (!content.docs_html.empty())
    out += "<li><a href=\"#cited\">Cited documentation</a>: <a href=\"#doc-model\">the physics (model.md)</a>, "
           "<a href=\"#doc-references\">the reference solutions (references.md)</a>, "
           "<a href=\"#doc-findings\">the findings (findings.md)</a></li>\n";
  return out + "</ol>\n</nav>\n";
}

}  // namespace

std::string html_page(const ReportContent& content) {
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += "<title>" + escape(content.title) + "</title>\n<style>" + style_sheet + "</style>\n";
  out += "</head>\n<body>\n<header>\n<h1>" + escape(content.title) + "</h1>\n";
  out += key_value_table(content.header, "meta") + "</header>\n";
  out += contents_nav(content) + "<main>\n";
  out += overview_section(content);
  out += sensitivity_overview_section(content);
  out += summary_section(content);
  out += content.claims_html;
  out += content.features_html;
  for (const auto& study : content.studies) out += study_section(study);
  out += content.speed_html;
  if (!content.docs_html.empty())
    out += "<section id=\"cited\">\n<h2>Cited documentation</h2>\n" + content.docs_html + "</section>\n";
  out +=
      "</main>\n<footer>Generated by <code>dem2d report</code> from the studies' result.json "
      "files; do not edit by hand.</footer>\n</body>\n</html>\n";
  return out;
}

}  // namespace report
