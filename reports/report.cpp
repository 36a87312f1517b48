// write_report: read the studies, render their plots with gnuplot, write index.html and index.md.
#include "report.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <set>
#include <stdexcept>
#include <system_error>

#include "cited_docs.hpp"
#include "speed_table.hpp"
#include "html_writer.hpp"
#include "markdown_writer.hpp"
#include "feature_matrix.hpp"
#include "paper_claims_table.hpp"
#include "report_content.hpp"
#include "study_plots.hpp"
#include "study_result.hpp"
#include "text_format.hpp"
#include "dem/run/output_files.hpp"

#ifndef GNUPLOT_EXECUTABLE
#define GNUPLOT_EXECUTABLE "gnuplot"
#endif

namespace report {

namespace {

namespace fs = std::filesystem;

constexpr const char* default_title = "DEM verification report";

// Files this generator writes into figures/ that this report does not link (an earlier report's, linked by
// nobody once the new index files are in place; removed after them, so that a report that fails half-way
// leaves the previous one whole with its figures). `keep`: the names written this time.
void remove_old_figures(const fs::path& figures_dir, const std::set<std::string>& keep) {
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(figures_dir, ignored)) {
    const auto extension = entry.path().extension();
    if (entry.is_regular_file() && (extension == ".svg" || extension == ".gp" || extension == ".png" || extension == ".partial") &&
        !keep.count(entry.path().filename().string()))
      fs::remove(entry.path(), ignored);
  }
}

// Through a temporary name and a rename (output_files.hpp): a full disk leaves the previous file whole, and
// the error (dem::OutputError) is exit status 4.
void write_text(const fs::path& path, const std::string& text) { dem::write_file_atomic(path, text); }

// Renders one plot (if any) into out_dir/file; the figure's note says what happened otherwise.
class FigureRenderer {
 public:
  FigureRenderer(fs::path out_dir, fs::path gnuplot)
      : out_dir_(std::move(out_dir)), gnuplot_(std::move(gnuplot)) {}

  RenderedFigure render(const std::optional<Plot>& plot, std::string title, const std::string& file,
                        const std::string& why_not, const std::string& note) {
    RenderedFigure figure;
    figure.title = std::move(title);
    if (!plot) {
      figure.note = why_not;
      return figure;
    }
    const auto outcome = render_svg(*plot, out_dir_ / file, gnuplot_);
    if (!outcome.ok) {
      figure.note = "figure not drawn: " + outcome.error;
      std::cerr << "report: warning: " << file << ": " << outcome.error << "\n";
      return figure;
    }
    figure.file = file;
    written_.insert(fs::path(file).filename().string());
    written_.insert(fs::path(file).replace_extension(".gp").filename().string());
    figure.svg = outcome.svg;
    figure.note = note;
    ++figures_written_;
    return figure;
  }
  int figures_written() const { return figures_written_; }
  std::set<std::string>& written() { return written_; }  // file names in figures/

 private:
  fs::path out_dir_, gnuplot_;
  std::set<std::string> written_;
  int figures_written_ = 0;
};

// File stem per study: its folder as a slug, made unique if two folders share a slug.
std::string unique_stem(const std::string& folder, std::set<std::string>& used) {
  std::string stem = slug(folder);
  for (int i = 2; used.count(stem); ++i) stem = fmt::format("{}-{}", slug(folder), i);
  used.insert(stem);
  return stem;
}

void render_study_plots(StudyReport& study, const std::string& stem, FigureRenderer& renderer) {
  const auto& result = study.source.result;
  const auto& series = array_field(result, "series");
  for (std::size_t k = 0; k < series.size(); ++k) {
    std::string why_not, note;
    // The tolerance of the check this series belongs to (same name), when it bounds the abs. error.
    std::optional<double> tolerance;
    for (const auto& check : array_field(result, "checks"))
      if (text_field(check, "quantity") == text_field(series[k], "name") &&
          text_field(check, "error_kind") != "rel" &&
          (text_field(check, "expect").empty() || text_field(check, "expect") == "within"))
        tolerance = number_field(check, "tolerance");
    const auto plot = convergence_plot(series[k], why_not, note, tolerance);
    auto title = text_field(series[k], "name");
    if (title.empty()) title = fmt::format("series {}", k + 1);
    study.convergence.push_back(renderer.render(
        plot, title, fmt::format("figures/{}-convergence-{}.svg", stem, k + 1), why_not, note));
  }
  const auto& figures = array_field(result, "figures");
  for (std::size_t k = 0; k < figures.size(); ++k) {
    std::string why_not;
    const auto plot = figure_plot(figures[k], why_not);
    auto title = text_field(figures[k], "title");
    const auto id = text_field(figures[k], "id");
    if (title.empty()) title = id.empty() ? fmt::format("figure {}", k + 1) : id;
    const auto file = id.empty()
                          ? fmt::format("figures/{}-figure-{}.svg", stem, k + 1)
                          : fmt::format("figures/{}-figure-{}-{}.svg", stem, k + 1, slug(id));
    study.figures.push_back(renderer.render(plot, title, file, why_not, ""));
  }
}

}  // namespace

Written write_report(const Options& options) {
  return write_report(options, GNUPLOT_EXECUTABLE);
}

Written write_report(const Options& options, const fs::path& gnuplot) {
  if (!fs::is_directory(options.studies_dir))
    throw std::runtime_error("report: studies folder not found: " + options.studies_dir.string());
  const auto claims = options.claims_file.empty() ? std::vector<PaperClaim>{} : read_paper_claims(options.claims_file);
  const fs::path figures_dir = options.out_dir / "figures";
  std::error_code made;
  fs::create_directories(figures_dir, made);
  if (made) throw dem::OutputError(fmt::format("{}: cannot create the report folder: {}", figures_dir.string(), made.message()));

  auto studies = read_study_results(options.studies_dir);
  ReportContent content;
  content.title = options.title.empty() ? default_title : options.title;
  content.header = header_fields(options.provenance, studies, options.studies_dir);

  FigureRenderer renderer(options.out_dir, gnuplot);
  std::set<std::string> used_stems;
  for (auto& source : studies) {
    StudyReport study{std::move(source), {}, {}, {}};
    if (study.source.readable()) {
      try {
        const std::string stem = unique_stem(study.source.folder, used_stems);
        render_study_plots(study, stem, renderer);
        study.snapshots = load_snapshots(study.source, options.out_dir, stem);
      } catch (const std::exception& e) {  // e.g. a file system error: keep the other studies
        study.convergence.clear();
        study.figures.clear();
        study.snapshots.clear();
        study.source.read_error = std::string("plots failed: ") + e.what();
        std::cerr << "report: warning: " << study.source.path.string() << ": " << e.what() << "\n";
      }
    }
    content.studies.push_back(std::move(study));
  }

  Written written;
  if (!options.claims_file.empty()) {
    const auto rows = match_claims(claims, content.studies, written.claim_errors);
    content.claims_html = claims_html(rows);
    content.claims_markdown = claims_markdown(rows);
  }
  written.html = options.out_dir / "index.html";
  written.markdown = options.out_dir / "index.md";
  const CitedDocs docs = options.docs_dir.empty() ? CitedDocs{} : render_cited_docs(options.docs_dir);
  content.docs_html = docs.html;
  if (!options.docs_dir.empty() && fs::exists(options.docs_dir / "model.md")) {
    std::ifstream model(options.docs_dir / "model.md");
    const std::string text((std::istreambuf_iterator<char>(model)), std::istreambuf_iterator<char>());
    const auto rows = match_features(feature_rows(text), content.studies);
    content.features_html = features_html(rows);
    content.features_markdown = features_markdown(rows);
  }
  if (const auto speed = options.bench_dir.empty() ? std::nullopt : find_speed_table(options.bench_dir)) {
    std::string link;
    if (!speed->plot_svg.empty()) {  // the Markdown twin links its copy, as it does the studies' figures
      write_text(figures_dir / "speed_cost.svg", speed->plot_svg);
      renderer.written().insert("speed_cost.svg");
      link = "figures/speed_cost.svg";
    }
    content.speed_html = speed_html(*speed);
    content.speed_markdown = speed_markdown(*speed, link);
  }
  write_text(written.html, link_citations(html_page(content), docs));
  write_text(written.markdown, markdown_page(content));
  for (const StudyReport& study : content.studies)
    for (const auto& picture : study.snapshots)
      if (!picture.file.empty()) renderer.written().insert(fs::path(picture.file).filename().string());
  remove_old_figures(figures_dir, renderer.written());
  written.studies = static_cast<int>(content.studies.size());
  written.figures = renderer.figures_written();
  return written;
}

}  // namespace report
