// gnuplot scripts with inline data blocks, run through the shell.
#include "gnuplot_plot.hpp"

#include "text_format.hpp"

#include <fmt/format.h>
#include <cstdio>
#include <string_view>
#include "dem/run/output_files.hpp"
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <system_error>
#include <utility>

namespace report {

namespace {

// Colours of successive curves (matplotlib's default cycle); reference slopes are grey.
constexpr const char* curve_colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                         "#9467bd", "#8c564b", "#e377c2", "#17becf"};

bool drawable(double x, double y, bool logx, bool logy) {
  return std::isfinite(x) && std::isfinite(y) && (!logx || x > 0.0) && (!logy || y > 0.0);
}

// Dash patterns and point shapes of successive curves: solid, dashed, dotted, dash-dot, ...;
// filled circle, square, triangle, diamond, ...
constexpr int dash_types[] = {1, 2, 3, 4, 5};
constexpr int point_types[] = {7, 5, 9, 13, 6, 4, 8, 12};

// Reference curves are black; several in one figure (e.g. Bray & Goodman and the PRE model's rigid
// block) get successive dash patterns: dashed, dash-dot, dotted, ...
constexpr int reference_dash_types[] = {2, 4, 3, 5};

std::string with_clause(const Curve& curve, std::size_t index, std::size_t reference_index = 0) {
  if (curve.dashed) return "with lines dt 2 lw 1.5 lc rgb '#555555'";
  if (curve.style == "reference")
    return fmt::format("with lines dt {} lw 2.5 lc rgb '#000000'",
                       reference_dash_types[reference_index % std::size(reference_dash_types)]);
  if (curve.style == "band") return "with lines dt 3 lw 1.5 lc rgb '#a40e26'";
  const int dt = dash_types[index % std::size(dash_types)];
  const int pt = point_types[index % std::size(point_types)];
  // Later curves drawn thinner, so that one lying exactly on an earlier one leaves it visible.
  const double lw = std::max(1.2, 3.0 - 0.6 * static_cast<double>(index));
  if (curve.style == "lines") return fmt::format("with lines dt {} lw {:.1f}", dt, lw);
  if (curve.style == "errorbars")
    return fmt::format("with yerrorbars pt {} ps {:.2g} lw 1.5", curve.point_type > 0 ? curve.point_type : pt,
                       curve.point_size > 0.0 ? curve.point_size : 0.7);
  if (curve.style == "boxes") return "with boxes fs solid 0.45 border";
  if (curve.style == "points")
    return fmt::format("with points pt {} ps {:.2g}", curve.point_type > 0 ? curve.point_type : pt,
                       curve.point_size > 0.0 ? curve.point_size : 0.9);
  return fmt::format("with linespoints dt {} lw 2 pt {} ps 0.9", dt, pt);
}

// A path inside a single-quoted gnuplot string.
std::string gnuplot_path(const std::filesystem::path& path) {
  std::string out;
  for (char c : path.string()) out += c == '\'' ? std::string("''") : std::string(1, c);
  return "'" + out + "'";
}

// An explicit tic label: gnuplot reads it as a format for the tic's value, so a literal % is written %%
// ("fill gap (dummy: ±3 %)" is otherwise "Bad format character").
std::string tic_label(const std::string& label) {
  std::string out;
  for (const char c : gnuplot_label(label)) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

// A word for /bin/sh: single-quoted, embedded ' as '\''.
std::string shell_quote(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Tics for a log axis over [lo, hi]: gnuplot's decades when the range spans 2 decades or more,
// else 1-2-5 steps so that a narrow range still gets several labels. "" = gnuplot's default.
std::string log_tics(double lo, double hi) {
  if (!(lo > 0.0) || !(hi > lo) || hi / lo >= 100.0) return {};
  std::vector<std::string> tics;
  for (int exponent = static_cast<int>(std::floor(std::log10(lo)));
       exponent <= static_cast<int>(std::ceil(std::log10(hi))); ++exponent)
    for (double mantissa : {1.0, 2.0, 5.0}) {
      const double tic = mantissa * std::pow(10.0, exponent);
      if (tic >= lo * (1 - 1e-12) && tic <= hi * (1 + 1e-12))
        tics.push_back(fmt::format("{:g}", tic));
    }
  if (tics.size() < 2) return {};
  std::string list;
  for (const auto& tic : tics) list += (list.empty() ? "" : ", ") + tic;
  return "(" + list + ")";
}

// Range of the drawable points of all curves along x (or y).
std::pair<double, double> data_range(const Plot& plot, bool along_x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& curve : plot.curves)
    for (std::size_t i = 0; i < curve.x.size() && i < curve.y.size(); ++i)
      if (drawable(curve.x[i], curve.y[i], plot.logx, plot.logy)) {
        const double v = along_x ? curve.x[i] : curve.y[i];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  return {lo, hi};
}

// A log axis hugging the data, margin 4 % of its log span (gnuplot would widen it to whole
// decades).
std::string log_axis(const Plot& plot, bool along_x) {
  const char* axis = along_x ? "x" : "y";
  std::string s = fmt::format("set logscale {0} 10\nset format {0} '%h'\n", axis);
  const auto [lo, hi] = data_range(plot, along_x);
  if (!(lo > 0.0) || !(hi >= lo)) return s;
  const double margin = hi > lo ? std::pow(hi / lo, 0.04) : 2.0;
  s += fmt::format("set {}range [{:.17g}:{:.17g}]\n", axis, lo / margin, hi * margin);
  const auto tics = log_tics(lo, hi);
  if (!tics.empty()) s += fmt::format("set {}tics {}\n", axis, tics);
  return s;
}

}  // namespace

std::string gnuplot_label(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '\'':
        out += "''";
        break;
      case '^':
      case '_':
      case '@':
      case '&':
      case '~':
      case '{':
      case '}':
      case '\\':
        out += '\\';
        out += c;
        break;
      case '\n':
      case '\r':
      case '\t':
        out += ' ';
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::size_t drawable_points(const Curve& curve, bool logx, bool logy) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < curve.x.size() && i < curve.y.size(); ++i)
    count += drawable(curve.x[i], curve.y[i], logx, logy) ? 1 : 0;
  return count;
}

std::string gnuplot_script(const Plot& plot, const std::filesystem::path& svg_file) {
  std::string s;
  s +=
      "# Generated by the dem2d report generator. Rerun in this folder with: gnuplot <this file>\n";
  s += "set terminal svg size 640,420 dynamic enhanced font 'Helvetica,12'\n";
  s += "set encoding utf8\n";
  s += "set output " + gnuplot_path(svg_file) + "\n";
  s += "set title '" + gnuplot_label(plot.title) + "'\n";
  s += "set xlabel '" + gnuplot_label(plot.xlabel) + "'\n";
  s += "set ylabel '" + gnuplot_label(plot.ylabel) + "'\n";
  s += "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n";
  s += "set key " + plot.key_position + " spacing 1.2\n";
  if (plot.logx) s += log_axis(plot, true);
  if (plot.logy) s += log_axis(plot, false);
  // Plain decimal tick labels with enough digits that neighbours differ (gnuplot's %h); a given
  // range replaces the automatic one.
  for (bool along_x : {true, false}) {
    if (along_x ? plot.logx : plot.logy) continue;
    const auto [lo, hi] = data_range(plot, along_x);
    const double magnitude = std::max(std::abs(lo), std::abs(hi)), span = hi - lo;
    if (std::isfinite(magnitude) && span > 0.0 && magnitude / span > 1e3) {
      const int digits = std::min(15, static_cast<int>(std::ceil(std::log10(magnitude / span))) + 3);
      s += fmt::format("set format {} '%.{}g'\n", along_x ? "x" : "y", digits);
    }
  }
  if (!plot.yticks.empty()) {
    std::string list;
    for (const auto& [v, label] : plot.yticks)
      list += fmt::format("{}'{}' {:.17g}", list.empty() ? "" : ", ", tic_label(label), v);
    s += "set ytics (" + list + ")\nset grid noytics\n";
  }
  if (!plot.xticks.empty()) {
    std::string list;
    for (const auto& [v, label] : plot.xticks)
      list += fmt::format("{}'{}' {:.17g}", list.empty() ? "" : ", ", tic_label(label), v);
    s += "set xtics (" + list + ")\nset grid noxtics\n";
  }
  for (const auto& label : plot.labels)
    if (drawable(label.x, label.y, plot.logx, plot.logy))
      s += fmt::format("set label '{}' at {:.17g},{:.17g} offset 0.7,0.5 font ',10'\n", gnuplot_label(label.text), label.x, label.y);
  if (plot.xrange.size() == 2) s += fmt::format("set xrange [{:.17g}:{:.17g}]\n", plot.xrange[0], plot.xrange[1]);
  if (plot.yrange.size() == 2) s += fmt::format("set yrange [{:.17g}:{:.17g}]\n", plot.yrange[0], plot.yrange[1]);

  std::vector<std::string> plot_items;
  std::size_t colour = 0, references = 0;
  for (std::size_t c = 0; c < plot.curves.size(); ++c) {
    const Curve& curve = plot.curves[c];
    if (drawable_points(curve, plot.logx, plot.logy) == 0) continue;
    const std::string block = fmt::format("$curve{}", c);
    s += block + " << EOD\n";
    const bool bars = curve.style == "errorbars" && curve.ylow.size() >= curve.x.size() && curve.yhigh.size() >= curve.x.size();
    for (std::size_t i = 0; i < curve.x.size() && i < curve.y.size(); ++i)
      if (drawable(curve.x[i], curve.y[i], plot.logx, plot.logy)) {
        if (bars && !(drawable(curve.x[i], curve.ylow[i], plot.logx, plot.logy) && drawable(curve.x[i], curve.yhigh[i], plot.logx, plot.logy)))
          continue;
        s += bars ? fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}\n", curve.x[i], curve.y[i], curve.ylow[i], curve.yhigh[i])
                  : fmt::format("{:.17g} {:.17g}\n", curve.x[i], curve.y[i]);
      }
    s += "EOD\n";
    const std::string columns = bars ? "1:2:3:4" : curve.style == "boxes" ? fmt::format("1:2:({:.17g})", curve.box_width) : "1:2";
    std::string item = block + " using " + columns + " " +
                       (curve.style == "errorbars" && !bars ? std::string("with points")
                                                           : with_clause(curve, colour, curve.style == "reference" ? references++ : 0));
    if (!curve.colour.empty())
      item += " lc rgb '" + gnuplot_label(curve.colour) + "'";
    else if (!curve.dashed && curve.style != "reference" && curve.style != "band")
      item += fmt::format(" lc rgb '{}'", curve_colours[colour++ % std::size(curve_colours)]);
    item += " title '" + gnuplot_label(curve.label) + "'";
    plot_items.push_back(item);
  }
  if (plot_items.empty()) {  // nothing to draw: an empty frame rather than a gnuplot error
    s += "set xrange [0:1]\nset yrange [0:1]\nunset logscale\n";
    plot_items.push_back("NaN notitle");
  }
  s += "plot ";
  for (std::size_t i = 0; i < plot_items.size(); ++i) s += (i ? ", \\\n     " : "") + plot_items[i];
  s += "\nunset output\n";
  return s;
}

namespace {

// A whole SVG document: it opens and closes (gnuplot on a full disk leaves one cut at a buffer's end).
bool complete_svg(const std::string& svg) {
  std::size_t end = svg.size();
  while (end > 0 && std::isspace(static_cast<unsigned char>(svg[end - 1]))) --end;
  return svg.find("<svg") != std::string::npos && std::string_view(svg).substr(0, end).ends_with("</svg>");
}

}  // namespace

PlotOutcome render_svg(const Plot& plot, const std::filesystem::path& svg_file,
                       const std::filesystem::path& gnuplot) {
  // gnuplot draws into <name>.svg.partial by a script of its own; only a complete SVG is renamed into place,
  // and the script kept beside it (<name>.gp, to rerun by hand) names the final file. Nothing half written
  // ever has the final name, and a failure leaves the previous report's figure (the report removes figures
  // it did not write once its index files are in place).
  PlotOutcome outcome;
  const auto svg_path = std::filesystem::absolute(svg_file);
  const auto folder = svg_path.parent_path();
  const auto partial_svg = folder / (svg_path.filename().string() + ".partial");
  const auto run_script = folder / (svg_path.stem().string() + ".gp.partial");
  auto script_path = svg_path;
  script_path.replace_extension(".gp");
  auto log_path = svg_path;
  log_path.replace_extension(".log");
  std::error_code ignored;
  std::filesystem::remove(partial_svg, ignored);  // the previous report's svg_path stays until this one replaces it
  auto fail = [&](std::string why) {
    outcome.error = std::move(why);
    outcome.svg.clear();
    for (const auto& f : {partial_svg, run_script}) std::filesystem::remove(f, ignored);
    return outcome;
  };
  {
    std::ofstream script(run_script, std::ios::binary);
    script << gnuplot_script(plot, partial_svg.filename());  // relative: gnuplot runs in its folder
    script.close();
    if (!script) return fail("cannot write " + run_script.string());
  }
  // A bare name ("gnuplot") is looked up on PATH; a path is made absolute before the cd.
  const std::string program =
      gnuplot.has_parent_path() ? std::filesystem::absolute(gnuplot).string() : gnuplot.string();
  const std::string command = "cd " + shell_quote(folder.string()) + " && " + shell_quote(program) +
                              " " + shell_quote(run_script.filename().string()) + " > " +
                              shell_quote(log_path.string()) + " 2>&1";
  const int status = std::system(command.c_str());
  const int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;  // -1: killed by a signal
  const std::string log = read_text_file(log_path);
  std::filesystem::remove(log_path, ignored);
  std::filesystem::remove(run_script, ignored);
  outcome.svg = read_text_file(partial_svg);
  if (exit_code != 0 || !complete_svg(outcome.svg)) {
    std::string why = fmt::format("gnuplot failed (exit code {}){}{}", exit_code, log.empty() ? "" : ": ", log.substr(0, 500));
    if (exit_code == 0) why = fmt::format("gnuplot wrote an incomplete SVG ({} bytes, no closing </svg>: a full disk?)", outcome.svg.size());
    while (!why.empty() && std::isspace(static_cast<unsigned char>(why.back()))) why.pop_back();
    return fail(why);
  }
  try {
    dem::write_file_atomic(script_path, gnuplot_script(plot, svg_path.filename()), false);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  if (std::rename(partial_svg.c_str(), svg_path.c_str()) != 0)
    return fail("cannot rename " + partial_svg.string() + " to " + svg_path.filename().string());
  outcome.ok = true;
  return outcome;
}

}  // namespace report
