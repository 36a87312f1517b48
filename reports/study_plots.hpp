// Plot descriptions from result.json entries: a convergence series (log-log error vs h with a
// reference slope) and a declared x-y figure.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "gnuplot_plot.hpp"

namespace report {

// Error vs h on log-log axes, points + lines, with a dashed line of the expected order through the
// finest plotted point labelled "slope p". Null (and the reason in why_not) when no level has a
// positive error. note_out receives remarks for a drawn plot (e.g. levels left out).
// tolerance: the absolute error tolerance of the matching check, drawn as a horizontal band line.
std::optional<Plot> convergence_plot(const nlohmann::json& series, std::string& why_not,
                                     std::string& note_out,
                                     std::optional<double> tolerance = std::nullopt);

// A "figures" entry as declared (title, labels, logx/logy, xrange/yrange, curves with style); the
// key sits outside, below the plot, so that it never covers a curve. Null (reason in
// why_not) when it has no drawable point.
std::optional<Plot> figure_plot(const nlohmann::json& figure, std::string& why_not);

}  // namespace report
