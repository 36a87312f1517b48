#include "speed_table.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "cited_docs.hpp"
#include "inline_svg.hpp"
#include "text_format.hpp"

namespace report {

namespace {

namespace fs = std::filesystem;

const char* about =
    "Measured by <code>bench/suite.py</code> (bench/README.md): dem2d and LAMMPS <code>gran/hooke/history</code> on the "
    "same cases, interleaved, the best of several runs of each (and the medians); rates in element-steps per second "
    "of the time loop, ratios taken within the one run; the ratios within dem2d (threads, PRE segments) also "
    "interleaved block by block in one process (<code>dem2d_alternate</code>). Speed is measured there and never "
    "in the tests.";

/// A viewBox from the width and height if the SVG has none (bench/suite.py's plots of 22 November 2026),
/// so that the page may scale it without stretching its box.
std::string with_view_box(std::string svg) {
  const auto open = svg.find("<svg");
  const auto end = svg.find('>', open);
  if (open == std::string::npos || end == std::string::npos || svg.substr(open, end - open).find("viewBox") != std::string::npos)
    return svg;
  auto attribute = [&](const std::string& name) {
    const auto p = svg.find(" " + name + "=\"", open);
    if (p == std::string::npos || p > end) return std::string();
    const auto a = p + name.size() + 3;
    return svg.substr(a, svg.find('"', a) - a);
  };
  const std::string w = attribute("width"), h = attribute("height");
  if (w.empty() || h.empty()) return svg;
  return svg.insert(open + 4, " viewBox=\"0 0 " + w + " " + h + "\"");
}

}  // namespace

std::optional<SpeedTable> find_speed_table(const fs::path& bench) {
  SpeedTable t;
  if (fs::is_regular_file(bench / "table.md")) {  // a suite's own output folder
    t.table = bench / "table.md";
    if (fs::is_regular_file(bench / "cost.svg")) t.plot = bench / "cost.svg";
  } else {
    if (!fs::is_directory(bench)) return std::nullopt;
    std::vector<fs::path> tables;
    for (const auto& f : fs::directory_iterator(bench)) {
      const std::string name = f.path().filename().string();
      if (f.is_regular_file() && name.rfind("suite_", 0) == 0 && f.path().extension() == ".md") tables.push_back(f.path());
    }
    if (tables.empty()) return std::nullopt;
    t.table = *std::max_element(tables.begin(), tables.end(),
                                [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });
    const std::string stem = t.table.stem().string();  // suite_<date…> → cost_<date…>.svg
    const fs::path plot = bench / ("cost_" + stem.substr(6) + ".svg");
    if (fs::is_regular_file(plot)) t.plot = plot;
  }
  t.table_md = read_text_file(t.table);
  if (!t.plot.empty()) t.plot_svg = read_text_file(t.plot);
  return t;
}

std::string speed_html(const SpeedTable& t) {
  std::string out = "<section id=\"speed\">\n<h2>Speed: dem2d beside LAMMPS</h2>\n<p>" + std::string(about) +
                    " Table: <code>" + html_escape(t.table.filename().string()) + "</code>.</p>\n";
  if (!t.plot_svg.empty())
    out += "<figure style=\"max-width: 760px\">" + inline_svg(with_view_box(t.plot_svg), "speed-") +
           "<figcaption>Wall-clock cost per element-step against the number of elements, log–log (a flat line: a cost "
           "per element-step that does not grow with size).</figcaption></figure>\n";
  out += markdown_html("speed", t.table_md);
  return out + "</section>\n";
}

std::string speed_markdown(const SpeedTable& t, const std::string& plot_link) {
  std::string about_md;  // the same words, `code` for <code>
  for (std::string_view rest = about; !rest.empty();) {
    const auto p = rest.find('<');
    about_md += rest.substr(0, p);
    if (p == std::string_view::npos) break;
    about_md += '`';
    rest = rest.substr(rest.find('>', p) + 1);
  }
  std::string out = fmt::format("## Speed: dem2d beside LAMMPS\n\n{} Table: `{}`.\n\n", about_md, t.table.filename().string());
  if (!plot_link.empty()) out += fmt::format("![cost per element-step against size]({})\n\n", plot_link);
  return out + t.table_md + "\n\n";
}

}  // namespace report
