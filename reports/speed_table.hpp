// The speed benchmark in the report: the table and the cost plot that bench/suite.py wrote (issue 14),
// shown as measured, beside the verification results. The report never runs the benchmark.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace report {

struct SpeedTable {
  std::filesystem::path table;  // the suite's table (Markdown)
  std::filesystem::path plot;   // its cost plot (SVG); empty if there is none
  std::string table_md;         // the table file's text
  std::string plot_svg;         // the plot file's text ("" if none)
};

/// The suite's output in `bench`: a suite folder (`bench/suite.py --out DIR`: table.md, cost.svg), or a
/// folder of kept results (bench/results: suite_<date>[_<part>].md with cost_<same>.svg), of which the
/// table whose name sorts last. None if the folder holds neither.
std::optional<SpeedTable> find_speed_table(const std::filesystem::path& bench);

/// The section's HTML (id "speed") and Markdown; the Markdown links the plot as `plot_link`.
std::string speed_html(const SpeedTable& t);
std::string speed_markdown(const SpeedTable& t, const std::string& plot_link);

}  // namespace report
