#include "dem/core/discharge.hpp"

#include <cmath>

#include "dem/core/model.hpp"

namespace dem {

namespace {
Vec2 slit_mid(const Model& m) {
  const Wall& w = m.walls[static_cast<std::size_t>(m.discharge.slit)];
  return (w.a + w.b) * 0.5;
}
Vec2 down(const Model& m) {
  const double g = norm(m.gravity);
  return g > 0.0 ? m.gravity * (1.0 / g) : Vec2{0.0, -1.0};
}
}  // namespace

double below_outlet(const Model& m, double x, double y) {
  return dot(down(m), Vec2{x, y} - slit_mid(m)) - m.discharge.outlet_depth;
}

std::size_t remove_discharged(Model& m) {
  if (!m.discharge.enabled) return 0;
  Elements& e = m.elements;
  std::size_t n = 0;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i] && below_outlet(m, e.x[i], e.y[i]) > 0.0) {
      e.active[i] = 0;
      ++n;
    }
  return n;
}

Discharged discharged(const Model& m) {
  Discharged d;
  if (!m.discharge.enabled) return d;
  const Elements& e = m.elements;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (!e.active[i] && below_outlet(m, e.x[i], e.y[i]) > 0.0) {
      ++d.count;
      d.mass += e.mass[i];
    }
  return d;
}

std::optional<std::size_t> keystone(const Model& m) {
  if (!m.discharge.enabled) return std::nullopt;
  const Wall& w = m.walls[static_cast<std::size_t>(m.discharge.slit)];
  const Vec2 ab = w.b - w.a, mid = slit_mid(m);
  const double len2 = dot(ab, ab);
  const Elements& e = m.elements;
  std::optional<std::size_t> best;
  double best_d2 = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i] || !(below_outlet(m, e.x[i], e.y[i]) <= 0.0)) continue;
    const Vec2 c{e.x[i], e.y[i]};
    const double s = len2 > 0.0 ? dot(c - w.a, ab) / len2 : 0.0;
    if (s < 0.0 || s > 1.0) continue;  // not over the slit
    const double d2 = dot(c - mid, c - mid);
    // ties: the lower id (the case's numbering, whatever order the run keeps the elements in)
    if (!best || d2 < best_d2 || (d2 == best_d2 && !e.id.empty() && e.id[i] < e.id[*best])) best = i, best_d2 = d2;
  }
  return best;
}

}  // namespace dem
