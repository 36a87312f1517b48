// The parts of a declared figure that sensitivity studies use (verification/engine/sensitivity.cpp
// writes them; any study may): labelled x tics, text labels by points, and per-curve intervals.
#pragma once

#include <nlohmann/json.hpp>

#include "gnuplot_plot.hpp"

namespace report {

// figure "xticks": [[x, "name"], ...] (e.g. one tic per parameter of a Sobol' bar chart);
// figure "labels": [{"x": .., "y": .., "text": ".."}, ...] (a parameter's name by its Morris point).
void add_sensitivity_marks(const nlohmann::json& figure, Plot& plot);

// curve "ylow", "yhigh": the interval of each point (style "errorbars"); curve "width": a bar's
// width (style "boxes").
void add_interval(const nlohmann::json& entry, Curve& curve);

}  // namespace report
