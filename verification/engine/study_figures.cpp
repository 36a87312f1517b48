#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include <fmt/format.h>

#include "dem/cases/text.hpp"
#include "dem/run/quantities.hpp"
#include "engine/study_run.hpp"
#include "engine/study_wall_profile.hpp"
#include "ref/registry.hpp"

// The figures and tables a study file declares ([[figure]], [[table]]), drawn from the finest run of
// each variant: probe values across variants against a variant argument, or time series from the runs'
// series.csv, each with its reference curves; tables of probes per variant or as a pivot.

namespace fs = std::filesystem;

namespace ver {

namespace {

std::string words(const Figure& f, const std::string& key, const std::string& fallback) {
  const auto it = f.curve_labels.find(key);
  return it == f.curve_labels.end() ? fallback : it->second;
}

bool listed(const std::vector<std::string>& only, const std::string& label) {
  return only.empty() || std::find(only.begin(), only.end(), label) != only.end();
}

double evaluate(const std::string& solver, const std::map<std::string, double>& args) { return evaluate_solver(solver, args); }

/// Probe values across variants against a variant argument, one curve per group.
nlohmann::json probe_curves(const StudyRun& run, const Figure& f) {
  const Study& s = run.s;
  nlohmann::json curves = nlohmann::json::array();
  // Probe values across variants against a variant argument, one curve per group.
  std::vector<double> groups;
  for (std::size_t vi = 0; vi < s.variants.size() && vi < run.finest_runs.size(); ++vi) {
    const Variant& v = s.variants[vi];
    if (!listed(f.variants, v.label)) continue;
    const double g = v.args.count(f.group_arg) ? v.args.at(f.group_arg) : 0.0;
    if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
  }
  double y_unit = 1.0;  // y_relative_to: that variant's value of the probe
  if (!f.y_relative_to.empty()) {
    y_unit = std::nan("");
    for (std::size_t vi = 0; vi < s.variants.size() && vi < run.finest_runs.size(); ++vi)
      if (s.variants[vi].label == f.y_relative_to)
        if (const std::optional<double> y0 = probe_of(run.finest_runs[vi], f.probe); y0 && *y0 != 0.0) y_unit = *y0;
  }
  for (double g : groups) {
    std::vector<double> px, py, rx, ry;
    std::map<std::string, double> ref_args;
    for (std::size_t vi = 0; vi < s.variants.size() && vi < run.finest_runs.size(); ++vi) {
      const Variant& v = s.variants[vi];
      if (!listed(f.variants, v.label) || !v.args.count(f.x_arg)) continue;
      if ((v.args.count(f.group_arg) ? v.args.at(f.group_arg) : 0.0) != g) continue;
      const std::optional<double> y = probe_of(run.finest_runs[vi], f.probe);
      px.push_back(v.args.at(f.x_arg) * f.x_scale);
      py.push_back(y ? (*y / y_unit - f.y_offset) * f.y_scale : std::nan(""));
      if (!f.solver.empty()) {
        std::map<std::string, double> args = v.args;
        for (const auto& [k, x] : f.args) args[k] = x;
        if (ref_args.empty()) ref_args = args;
        rx.push_back(px.back());
        ry.push_back(evaluate(f.solver, args) * f.ref_scale * f.y_scale);
      }
    }
    if (f.reference_points > 1 && !rx.empty()) {  // a smooth curve over the group's span of x_arg
      const auto [lo, hi] = std::minmax_element(rx.begin(), rx.end());
      const double a = *lo / f.x_scale, b = *hi / f.x_scale;
      rx.clear();
      ry.clear();
      for (std::int64_t k = 0; k < f.reference_points; ++k) {
        std::map<std::string, double> args = ref_args;
        args[f.x_arg] = a + (b - a) * static_cast<double>(k) / static_cast<double>(f.reference_points - 1);
        rx.push_back(args[f.x_arg] * f.x_scale);
        ry.push_back(evaluate(f.solver, args) * f.ref_scale * f.y_scale);
      }
    }
    const std::string gname = f.group_arg.empty() ? "DEM" : fmt::format("{} = {:g}", f.group_label, g);
    const std::string gkey = f.group_arg.empty() ? "DEM" : fmt::format("{:g}", g);
    // Against a smooth reference curve the DEM values are points (no line between them to mislead).
    curves.push_back({{"label", words(f, gkey, gname)}, {"x", px}, {"y", py},
                      {"style", f.reference_points > 1 ? "points" : "linespoints"}});
    if (!rx.empty())
      curves.push_back({{"label", words(f, f.solver, "reference") + (f.group_arg.empty() ? "" : ", " + gname)},
                        {"x", rx}, {"y", ry}, {"style", "reference"}});
  }
  return curves;
}

/// Time series of the variants' finest runs (their series.csv), with the reference solvers' curves.
nlohmann::json series_curves(const StudyRun& run, const Figure& f) {
  const Study& s = run.s;
  nlohmann::json curves = nlohmann::json::array();
  std::vector<double> ref_x;
  std::map<std::string, double> ref_args = f.args;
  std::map<std::string, std::vector<std::map<std::string, double>>> drawn_references;  // per solver: its arguments
  for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
    const Variant& v = s.variants.at(vi);  // checked: not hot, and an index past the end throws
    if (!listed(f.variants, v.label)) continue;
    const fs::path csv = run.out / "runs" / fmt::format("variant{}", vi) / "series.csv";
    std::ifstream in(csv);
    std::string line;
    std::vector<std::string> header;
    std::vector<double> xs, ys;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      const std::vector<std::string> cells = dem::split_csv(line);
      if (header.empty()) {  // "e0.y [m]": the quantity and its unit
        for (const std::string& h : cells) header.push_back(dem::series_column_name(h));
        continue;
      }
      auto col = [&](const std::string& name) {
        for (std::size_t k = 0; k < header.size(); ++k)
          if (header[k] == name) return std::stod(cells[k]);
        return std::nan("");
      };
      xs.push_back(col(f.x));
      ys.push_back(col(f.y));
    }
    if (xs.empty()) continue;
    std::map<std::string, double> vargs = v.args;
    for (const auto& [k, x] : f.args) vargs[k] = x;
    const double y0 = ys.front();
    std::vector<double> px, py;
    for (std::size_t k = 0; k < xs.size(); ++k) {
      double y = f.y_from_start ? ys[k] - y0 : ys[k] - f.y_offset;
      if (f.y_minus_reference) {
        std::map<std::string, double> a = vargs;
        a[f.x_arg] = xs[k];
        y -= evaluate(f.solver, a) * f.ref_scale;
      }
      px.push_back(xs[k] * f.x_scale);
      py.push_back(y * f.y_scale);
    }
    if (ref_x.empty()) {
      ref_x = xs;
      ref_args = vargs;
    }
    const std::string name = v.label.empty() ? std::string("DEM") : "DEM " + v.label;
    curves.push_back({{"label", words(f, v.label, name)}, {"x", px}, {"y", py}, {"style", "lines"}});
    if (f.reference_per_variant && !f.y_minus_reference)
      for (const std::string& solver : f.solvers) {
        std::vector<double> rx, ry, grid = xs;
        if (f.reference_points > 1 && !xs.empty()) {  // a uniform grid over the variant's span (a costly solver)
          const auto [lo, hi] = std::minmax_element(xs.begin(), xs.end());
          grid.clear();
          for (std::int64_t k = 0; k < f.reference_points; ++k)
            grid.push_back(*lo + (*hi - *lo) * static_cast<double>(k) / static_cast<double>(f.reference_points - 1));
        }
        for (double x : grid) {
          std::map<std::string, double> a = vargs;
          a[f.x_arg] = x;
          rx.push_back(x * f.x_scale);
          ry.push_back(evaluate(solver, a) * f.ref_scale * f.y_scale);
        }
        // A reference that does not depend on what differs between the variants (e.g. Bray & Goodman
        // for 3 and 75 PREs at one α: the same arguments of the solver apart from x) is drawn once.
        std::map<std::string, double> taken;
        for (const auto& info : ref::solvers())
          if (info.name == solver)
            for (const auto& arg : info.arguments)
              if (arg.name != f.x_arg && vargs.count(arg.name)) taken[arg.name] = vargs.at(arg.name);
        auto& drawn = drawn_references[solver];
        if (std::find(drawn.begin(), drawn.end(), taken) != drawn.end()) continue;
        drawn.push_back(taken);
        curves.push_back({{"label", words(f, solver + "|" + v.label, words(f, solver, "reference") + ", " + v.label)},
                          {"x", rx}, {"y", ry}, {"style", "reference"}});
      }
  }
  if (f.reference_per_variant) ref_x.clear();
  if (!ref_x.empty() && !f.y_minus_reference)
    for (const std::string& solver : f.solvers) {
      std::vector<double> px, py;
      for (double x : ref_x) {
        std::map<std::string, double> a = ref_args;
        a[f.x_arg] = x;
        px.push_back(x * f.x_scale);
        py.push_back(evaluate(solver, a) * f.ref_scale * f.y_scale);
      }
      curves.push_back({{"label", words(f, solver, "reference: " + solver)}, {"x", px}, {"y", py}, {"style", "reference"}});
    }
  return curves;
}

}  // namespace

nlohmann::json draw_figures(const StudyRun& run) {
  const Study& s = run.s;
  nlohmann::json figures = nlohmann::json::array();
  if (!run.mode_chart.is_null()) figures.push_back(run.mode_chart);
  for (const Figure& f : s.figures) {
    const nlohmann::json curves = !f.walls.empty()   ? wall_profile_curves(run, f)
                                  : f.probe.empty() ? series_curves(run, f)
                                                    : probe_curves(run, f);
    nlohmann::json fig = {{"id", f.id}, {"title", f.title}, {"xlabel", f.xlabel}, {"ylabel", f.ylabel},
                          {"logx", f.logx}, {"logy", f.logy}, {"curves", curves}};
    if (!f.x_range.empty()) fig["xrange"] = f.x_range;
    if (!f.y_range.empty()) fig["yrange"] = f.y_range;
    figures.push_back(fig);
  }
  return figures;
}

void fill_tables(StudyRun& run) {
  const Study& s = run.s;
  for (const TableDecl& d : s.tables) {
    nlohmann::json rows = nlohmann::json::array(), columns = nlohmann::json::array();
    auto cell = [&](std::size_t vi, const std::string& probe) -> nlohmann::json {
      if (!run.ensemble_stats.empty() && run.ensemble_stats[vi].count(probe)) {  // an ensemble: mean ± interval
        const EnsembleStat& st = run.ensemble_stats[vi].at(probe);
        if (st.mean && st.half_width)
          return fmt::format("{:.4g} ± {:.2g}", *st.mean * d.scale, *st.half_width * std::abs(d.scale));
      }
      const auto x = probe_of(run.finest_runs[vi], probe);
      return x ? nlohmann::json(fmt::format("{:.4g}", *x * d.scale)) : nlohmann::json("—");
    };
    if (d.row_arg.empty()) {
      columns.push_back("variant");
      for (const auto& p : d.probes) columns.push_back(p);
      for (std::size_t vi = 0; vi < run.finest_runs.size(); ++vi) {
        if (!listed(d.variants, s.variants[vi].label)) continue;
        nlohmann::json row = {s.variants[vi].label};
        for (const auto& p : d.probes) row.push_back(cell(vi, p));
        rows.push_back(row);
      }
    } else {
      std::vector<double> rv, cv;
      for (std::size_t vi = 0; vi < run.finest_runs.size(); ++vi) {
        const Variant& v = s.variants[vi];
        if (!listed(d.variants, v.label) || !v.args.count(d.row_arg) || !v.args.count(d.column_arg)) continue;
        if (std::find(rv.begin(), rv.end(), v.args.at(d.row_arg)) == rv.end()) rv.push_back(v.args.at(d.row_arg));
        if (std::find(cv.begin(), cv.end(), v.args.at(d.column_arg)) == cv.end()) cv.push_back(v.args.at(d.column_arg));
      }
      std::sort(cv.begin(), cv.end());
      columns.push_back(fmt::format("{} \\ {}", d.row_label, d.column_label));
      for (double c : cv) columns.push_back(fmt::format("{} = {:g}", d.column_label, c));
      for (double r : rv) {
        nlohmann::json row = {fmt::format("{} = {:g}", d.row_label, r)};
        for (double c : cv) {
          nlohmann::json value = "";
          for (std::size_t vi = 0; vi < run.finest_runs.size(); ++vi) {
            const Variant& v = s.variants[vi];
            if (listed(d.variants, v.label) && v.args.count(d.row_arg) && v.args.count(d.column_arg) &&
                v.args.at(d.row_arg) == r && v.args.at(d.column_arg) == c)
              value = cell(vi, d.probes.front());
          }
          row.push_back(value);
        }
        rows.push_back(row);
      }
    }
    run.tables.push_back({{"title", d.title}, {"columns", columns}, {"rows", rows}});
  }
}

}  // namespace ver
