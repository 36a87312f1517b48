// Building plot descriptions from result.json entries.
#include "study_plots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sensitivity_marks.hpp"
#include "study_result.hpp"
#include "text_format.hpp"

namespace report {

std::optional<Plot> convergence_plot(const nlohmann::json& series, std::string& why_not,
                                     std::string& note_out, std::optional<double> tolerance) {
  const auto h = number_array(series, "h");
  const auto error = number_array(series, "error");
  Curve errors;
  errors.label = number_field(series, "reference") ? "error" : "error vs Richardson";
  errors.style = "linespoints";
  std::size_t left_out = 0;
  for (std::size_t k = 0; k < h.size(); ++k) {
    const bool has_error = k < error.size() && error[k];
    if (h[k] && *h[k] > 0.0 && has_error && *error[k] > 0.0 && std::isfinite(*error[k])) {
      errors.x.push_back(*h[k]);
      errors.y.push_back(*error[k]);
    } else {
      ++left_out;
    }
  }
  if (errors.x.empty()) {
    why_not = "no plot: all errors are zero or missing";
    return std::nullopt;
  }
  if (left_out > 0)
    note_out = std::to_string(left_out) + " level(s) with zero or missing error not drawn";

  Plot plot;
  plot.title = text_field(series, "name");
  plot.xlabel = text_field(series, "parameter");
  if (plot.xlabel.empty()) plot.xlabel = "h";
  plot.ylabel = number_field(series, "reference") ? "abs. error |DEM − reference|"
                                                  : "abs. error |DEM − Richardson|";
  // the quantity's unit, when its name states one ("δ(0.5 s) [m]", or a `unit` field)
  std::string unit = text_field(series, "unit");
  if (const auto open = plot.title.rfind(" ["); unit.empty() && open != std::string::npos && plot.title.back() == ']')
    unit = plot.title.substr(open + 2, plot.title.size() - open - 3);
  if (!unit.empty()) plot.ylabel += " [" + unit + "]";
  plot.logx = plot.logy = true;
  plot.key_position = "top left";
  plot.curves.push_back(errors);

  // Reference slope of the expected order through the finest plotted point.
  if (const auto order = number_field(series, "expected_order")) {
    std::size_t finest = 0;
    for (std::size_t i = 1; i < errors.x.size(); ++i)
      if (errors.x[i] < errors.x[finest]) finest = i;
    double coarsest_h = errors.x[finest];
    for (double x : errors.x) coarsest_h = std::max(coarsest_h, x);
    Curve slope;
    slope.label = "slope " + format_number(*order);
    slope.style = "lines";
    slope.dashed = true;
    const double h_f = errors.x[finest], e_f = errors.y[finest];
    slope.x = {h_f, coarsest_h};
    slope.y = {e_f, e_f * std::pow(coarsest_h / h_f, *order)};
    plot.curves.push_back(slope);
  }
  if (tolerance && *tolerance > 0.0) {
    double lo = errors.x.front(), hi = errors.x.front();
    for (double x : errors.x) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    Curve band;
    band.label = "tolerance " + format_number(*tolerance);
    band.style = "band";
    band.x = {lo, hi};
    band.y = {*tolerance, *tolerance};
    plot.curves.push_back(band);
  }
  plot.key_position = "below";
  return plot;
}

std::optional<Plot> figure_plot(const nlohmann::json& figure, std::string& why_not) {
  Plot plot;
  plot.title = text_field(figure, "title");
  plot.xlabel = text_field(figure, "xlabel");
  plot.ylabel = text_field(figure, "ylabel");
  plot.logx = bool_field(figure, "logx").value_or(false);
  plot.logy = bool_field(figure, "logy").value_or(false);
  plot.key_position = "below";
  for (const auto& [key, out] : {std::pair{"xrange", &plot.xrange}, std::pair{"yrange", &plot.yrange}}) {
    const auto r = number_array(figure, key);
    if (r.size() == 2 && r[0] && r[1] && *r[0] < *r[1]) *out = {*r[0], *r[1]};
  }
  for (const auto& tick : array_field(figure, "yticks"))
    if (tick.is_array() && tick.size() == 2 && tick[0].is_number() && tick[1].is_string())
      plot.yticks.emplace_back(tick[0].get<double>(), tick[1].get<std::string>());
  add_sensitivity_marks(figure, plot);
  std::size_t points = 0;
  for (const auto& entry : array_field(figure, "curves")) {
    Curve curve;
    curve.label = text_field(entry, "label");
    const auto style = text_field(entry, "style");
    curve.style = style.empty() ? "lines" : style;
    curve.colour = text_field(entry, "colour");
    curve.point_type = static_cast<int>(number_field(entry, "point").value_or(0.0));
    curve.point_size = number_field(entry, "size").value_or(0.0);
    const auto x = number_array(entry, "x");
    const auto y = number_array(entry, "y");
    for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
      curve.x.push_back(x[i].value_or(
          std::numeric_limits<double>::quiet_NaN()));  // gaps are dropped when plotting
      curve.y.push_back(y[i].value_or(std::numeric_limits<double>::quiet_NaN()));
    }
    add_interval(entry, curve);
    points += drawable_points(curve, plot.logx, plot.logy);
    plot.curves.push_back(curve);
  }
  if (points == 0) {
    why_not = "no plot: the figure has no drawable point";
    return std::nullopt;
  }
  return plot;
}

}  // namespace report
