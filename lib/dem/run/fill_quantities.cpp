#include "dem/run/fill_quantities.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace dem {

double fill_top(const Simulation& s) {
  const Elements& e = s.model().elements;
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i]) top = std::max(top, e.y[i] + e.radius[i]);
  return top;
}

namespace {
/// Area of the part of a disk (centre at height 0, radius r) below the line y = h: the integral of the
/// chord 2√(r² − y²) from −r to h, r² (u√(1 − u²) + asin u + π/2) with u = h/r.
double area_below(double h, double r) {
  if (h <= -r) return 0.0;
  if (h >= r) return std::numbers::pi * r * r;
  const double u = h / r;
  return r * r * (u * std::sqrt(1.0 - u * u) + std::asin(u) + 0.5 * std::numbers::pi);
}
}  // namespace

double disk_area_between(double yc, double r, double y0, double y1) {
  return area_below(y1 - yc, r) - area_below(y0 - yc, r);
}

double strip_area_fraction(const Simulation& s, double x0, double x1, double y0, double y1) {
  const Elements& e = s.model().elements;
  double area = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i] && e.x[i] >= x0 && e.x[i] < x1) area += disk_area_between(e.y[i], e.radius[i], y0, y1);
  return area / ((x1 - x0) * (y1 - y0));
}

std::optional<QuantityFn> compile_fill_quantity(const std::string& name) {
  if (name == "active.top") return QuantityFn(fill_top);
  const std::string head = "active.area_fraction(";
  if (name.rfind(head, 0) != 0) return std::nullopt;
  const std::string what = "expected active.area_fraction(x0,x1,y0,y1) in metres with x0 < x1 and y0 < y1";
  if (name.back() != ')') throw std::invalid_argument(what);
  std::vector<double> v;
  std::string args = name.substr(head.size(), name.size() - head.size() - 1);
  for (std::size_t start = 0;;) {
    const auto comma = args.find(',', start);
    const std::string cell = args.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    try {
      std::size_t used = 0;
      v.push_back(std::stod(cell, &used));
      if (used != cell.size() || !std::isfinite(v.back())) throw std::invalid_argument(cell);
    } catch (const std::exception&) {
      throw std::invalid_argument(what);
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() != 4 || !(v[0] < v[1]) || !(v[2] < v[3])) throw std::invalid_argument(what);
  const double x0 = v[0], x1 = v[1], y0 = v[2], y1 = v[3];
  return QuantityFn([x0, x1, y0, y1](const Simulation& s) { return strip_area_fraction(s, x0, x1, y0, y1); });
}

}  // namespace dem
