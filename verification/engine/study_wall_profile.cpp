#include "engine/study_wall_profile.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "dem/cases/text.hpp"
#include "engine/study_run.hpp"
#include "ref/registry.hpp"

namespace fs = std::filesystem;

namespace ver {

namespace {

const char* const kHeader = "wall,s [m],x [m],y [m],depth [m],fn [N],fs [N]";

std::string words(const Figure& f, const std::string& key, const std::string& fallback) {
  const auto it = f.curve_labels.find(key);
  return it == f.curve_labels.end() ? fallback : it->second;
}

bool listed(const std::vector<std::string>& only, const std::string& label) {
  return only.empty() || std::find(only.begin(), only.end(), label) != only.end();
}

/// mu_w of a variant for the mobilisation: the figure's args over the variant's.
double mu_w_of(const Figure& f, const Variant& v) {
  if (f.args.count("mu_w")) return f.args.at("mu_w");
  return v.args.count("mu_w") ? v.args.at("mu_w") : 0.0;
}

}  // namespace

std::vector<WallContactRow> read_wall_contacts_csv(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read (the run wrote no wall contacts)", file.string()));
  std::vector<WallContactRow> rows;
  std::string line;
  std::size_t n = 0;
  auto bad = [&](const std::string& what) { return std::runtime_error(fmt::format("{}:{}: {}", file.string(), n, what)); };
  while (std::getline(in, line)) {
    ++n;
    if (n == 1) {
      if (line != kHeader) throw bad(fmt::format("expected the header \"{}\"", kHeader));
      continue;
    }
    const std::vector<std::string> cells = dem::split_csv(line);
    if (cells.size() != 7) throw bad(fmt::format("expected 7 cells (wall, s, x, y, depth, fn, fs), got {}", cells.size()));
    double v[6];
    for (std::size_t k = 0; k < 6; ++k) {
      std::size_t used = 0;
      try {
        v[k] = std::stod(cells[k + 1], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != cells[k + 1].size() || !std::isfinite(v[k]))
        throw bad(fmt::format("cell {}: expected a finite number, got \"{}\"", k + 2, cells[k + 1]));
    }
    if (cells[0].empty()) throw bad("cell 1: expected a wall name");
    if (v[3] < -1e-9) throw bad(fmt::format("depth {:.6g} m: a wall contact above the fill's top", v[3]));
    rows.push_back({cells[0], v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  if (n == 0) throw bad("empty file: expected the header line");
  return rows;
}

std::optional<double> wall_profile_value(const WallContactRow& c, const std::string& component, double mu_w) {
  if (component == "fn") return c.fn;
  if (component == "fs") return c.fs;
  if (!(c.fn > 0.0) || !(mu_w > 0.0)) return std::nullopt;  // mobilisation: |τ| / (μ_w σ) per contact
  return std::abs(c.fs) / (mu_w * c.fn);
}

nlohmann::json wall_profile_points(const std::vector<WallContactRow>& rows, const Figure& f, double mu_w,
                                   const std::string& label) {
  std::vector<double> x, y;
  for (const WallContactRow& c : rows) {
    if (std::find(f.walls.begin(), f.walls.end(), c.wall) == f.walls.end()) continue;
    const std::optional<double> value = wall_profile_value(c, f.component, mu_w);
    if (!value) continue;
    x.push_back(c.depth * f.x_scale);
    y.push_back(*value * f.y_scale);
  }
  return {{"label", label}, {"x", x}, {"y", y}, {"style", "points"}};
}

void read_wall_profile(Figure& f, const Study& s, const dem::TableReader& r, const toml::node& n) {
  f.component = r.string("component", "");
  if (f.component != "fn" && f.component != "fs" && f.component != "mobilisation")
    r.fail_at(n, "component", "expected \"fn\", \"fs\" or \"mobilisation\" (|fs| / (mu_w fn)) for a figure of walls");
  for (const char* key : {"y", "probe", "group_arg"})
    if (r.node(key)) r.fail(key, "a figure of walls plots the wall contacts against depth: no y, probe or group_arg");
  if (f.y_from_start || f.y_minus_reference)
    r.fail(f.y_from_start ? "y_from_start" : "y_minus_reference", "not for a figure of walls");
  if (!f.solver.empty()) {
    if (f.component == "mobilisation") r.fail("reference", "the mobilisation's reference is the line 1 (drawn without a solver)");
    if (f.x_arg == "t" || f.reference_points < 2)
      r.fail("reference", "needs x_arg (the solver's depth argument) and reference_points >= 2 (a grid of depths)");
  }
  for (const Variant& v : s.variants) {
    if (!listed(f.variants, v.label)) continue;
    if (f.component == "mobilisation" && !(mu_w_of(f, v) > 0.0))
      r.fail_at(n, "args", fmt::format("the mobilisation needs mu_w > 0 (the figure's args or variant \"{}\"'s)", v.label));
    if (f.solver.empty()) continue;
    std::map<std::string, double> args = v.args;
    for (const auto& [k, x] : f.args) args[k] = x;
    args[f.x_arg] = 0.0;
    for (const auto& info : ref::solvers())
      if (info.name == f.solver)
        for (const auto& a : info.arguments)
          if (!args.count(a.name))
            r.fail_at(n, "args", fmt::format("the reference {} needs {} for variant \"{}\"", f.solver, a.name, v.label));
  }
}

nlohmann::json wall_profile_curves(const StudyRun& run, const Figure& f) {
  const Study& s = run.s;
  nlohmann::json curves = nlohmann::json::array();
  double deepest = 0.0;
  for (std::size_t vi = 0; vi < s.variants.size(); ++vi) {
    const Variant& v = s.variants[vi];
    if (!listed(f.variants, v.label)) continue;
    const auto rows = read_wall_contacts_csv(run.out / "runs" / fmt::format("variant{}", vi) / "wall_contacts.csv");
    double depth = 0.0;
    for (const WallContactRow& c : rows) depth = std::max(depth, c.depth);
    deepest = std::max(deepest, depth);
    curves.push_back(wall_profile_points(rows, f, mu_w_of(f, v), words(f, v.label, "DEM " + v.label)));
    if (f.solver.empty()) continue;
    std::map<std::string, double> args = v.args;
    for (const auto& [k, x] : f.args) args[k] = x;
    std::vector<double> rx, ry;
    for (std::int64_t k = 0; k < f.reference_points; ++k) {
      args[f.x_arg] = depth * static_cast<double>(k) / static_cast<double>(f.reference_points - 1);
      rx.push_back(args[f.x_arg] * f.x_scale);
      ry.push_back(evaluate_solver(f.solver, args) * f.ref_scale * f.y_scale);
    }
    curves.push_back({{"label", words(f, f.solver + "|" + v.label, words(f, f.solver, "reference") + ", " + v.label)},
                      {"x", rx}, {"y", ry}, {"style", "reference"}});
  }
  if (f.component == "mobilisation")
    curves.push_back({{"label", words(f, "full", "full mobilisation (Janssen)")},
                      {"x", {0.0, deepest * f.x_scale}}, {"y", {f.y_scale, f.y_scale}}, {"style", "reference"}});
  return curves;
}

}  // namespace ver
