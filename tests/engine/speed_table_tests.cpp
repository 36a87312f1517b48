// The speed section of the report (reports/speed_table.hpp) from a suite's table and cost plot: the plot
// gets a viewBox from its own width and height (so the page may scale it), the words about how speed is
// measured appear in both formats. Planted bugs that turn it red: the viewBox inserted inside the tag
// name, the attribute value read from the wrong place, the Markdown's words left out.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "speed_table.hpp"
#include "temp_dir.hpp"

namespace {
report::SpeedTable table_with_plot(const std::string& svg) {
  report::SpeedTable t;
  t.table = "bench/results/suite_2026-11-22.md";
  t.table_md = "| elements | dem2d | LAMMPS |\n|---:|---:|---:|\n| 1000 | 1.0 | 2.0 |\n";
  t.plot = "bench/results/cost_2026-11-22.svg";
  t.plot_svg = svg;
  return t;
}
}  // namespace

TEST_CASE("speed section: a plot without a viewBox gets one from its width and height", "[report]") {
  const std::string html = report::speed_html(table_with_plot("<svg width=\"640\" height=\"480\"><rect x=\"1\"/></svg>"));
  CHECK(html.find("<svg viewBox=\"0 0 640 480\" width=\"640\" height=\"480\"") != std::string::npos);
  CHECK(html.find("<section id=\"speed\">") != std::string::npos);
  CHECK(html.find("suite_2026-11-22.md") != std::string::npos);
  CHECK(html.find("<code>dem2d_alternate</code>") != std::string::npos);
  // one it has already is kept as it is
  const std::string kept = report::speed_html(table_with_plot("<svg viewBox=\"0 0 10 20\" width=\"640\" height=\"480\"></svg>"));
  CHECK(kept.find("viewBox=\"0 0 10 20\"") != std::string::npos);
  CHECK(kept.find("viewBox=\"0 0 640 480\"") == std::string::npos);
}

TEST_CASE("speed section: the Markdown says how speed is measured, code as code", "[report]") {
  const std::string md = report::speed_markdown(table_with_plot(""), "figures/speed.svg");
  CHECK(md.find("## Speed: dem2d beside LAMMPS") != std::string::npos);
  CHECK(md.find("interleaved block by block in one process (`dem2d_alternate`)") != std::string::npos);
  CHECK(md.find("never in the tests.") != std::string::npos);
  CHECK(md.find("<code>") == std::string::npos);
  CHECK(md.find("![cost per element-step against size](figures/speed.svg)") != std::string::npos);
  CHECK(md.find("| 1000 | 1.0 | 2.0 |") != std::string::npos);
}
