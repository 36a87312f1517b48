// An x-y plot description and its rendering to SVG by gnuplot (script with inline data, run as a
// subprocess). Knows nothing about result.json.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace report {

struct Curve {
  std::string label;
  std::vector<double> x, y;  // non-finite points, and non-positive ones on a log axis, are dropped
  std::string style = "linespoints";  // lines | points | linespoints | reference (black, dashed) | band
  bool dashed = false;                // drawn thin, dashed and grey (reference slopes)
  std::string colour;                 // "#rrggbb": overrides the colour cycle (e.g. one colour per mode)
  int point_type = 0;                 // > 0: gnuplot point type, overriding the cycle
  double point_size = 0.0;            // > 0: overrides the default size
  // style "errorbars": a point at (x, y) with a vertical bar from ylow to yhigh (an interval);
  // style "boxes": bars from 0 to y, `box_width` wide (x units), filled half-transparent.
  std::vector<double> ylow, yhigh;
  double box_width = 0.3;
  // Successive lines / points of a plot get distinct dash patterns and point shapes, so that a
  // curve lying on another stays visible.
};

struct Plot {
  std::string title, xlabel, ylabel;
  bool logx = false, logy = false;
  std::string key_position = "top right";  // gnuplot "set key" position ("below": outside, under the plot)
  std::vector<double> xrange, yrange;       // [lo, hi] when given; else from the data
  std::vector<std::pair<double, std::string>> yticks;  // labelled y tics (e.g. rows of a map)
  std::vector<std::pair<double, std::string>> xticks;  // labelled x tics (e.g. parameter names)
  struct Label {
    double x = 0.0, y = 0.0;
    std::string text;
  };
  std::vector<Label> labels;  // text next to a point (e.g. a parameter's name by its Morris point)
  std::vector<Curve> curves;
};

// Label text for a single-quoted gnuplot string in enhanced mode: ' doubled, enhanced-text
// specials (^ _ @ & ~ { } \) escaped, line breaks as spaces.
std::string gnuplot_label(std::string_view text);

// The gnuplot script that writes the plot to svg_file (640x420, enhanced, Helvetica 12).
std::string gnuplot_script(const Plot& plot, const std::filesystem::path& svg_file);

// Number of points of the curve that will be drawn.
std::size_t drawable_points(const Curve& curve, bool logx, bool logy);

struct PlotOutcome {
  bool ok = false;
  std::string svg;    // the SVG text when ok
  std::string error;  // why not, when not ok
};

// Writes <svg_file stem>.gp next to svg_file, runs gnuplot on it in that folder, reads the SVG
// back. Never throws for a gnuplot failure; the error text says what went wrong.
PlotOutcome render_svg(const Plot& plot, const std::filesystem::path& svg_file,
                       const std::filesystem::path& gnuplot);

}  // namespace report
