#include "dem/core/discharge.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

#include "dem/core/model.hpp"

namespace dem {

namespace {
/// The outlet line: its point under the slit's mid-point and the direction of g, computed once per call
/// (not per element: a norm and a division each).
struct OutletLine {
  Vec2 down, mid;
  double depth = 0.0;
  explicit OutletLine(const Model& m) : depth(m.discharge.outlet_depth) {
    const Wall& w = m.walls[static_cast<std::size_t>(m.discharge.slit)];
    mid = (w.a + w.b) * 0.5;
    const double g = norm(m.gravity);
    down = g > 0.0 ? m.gravity * (1.0 / g) : Vec2{0.0, -1.0};
  }
  double below(double x, double y) const { return dot(down, Vec2{x, y} - mid) - depth; }
};

/// Whether an active element may lie below the outlet line: the sign bit of its distance below the line is
/// clear (below > 0, or +0, or a NaN without sign): a branch-free pass the compiler vectorises, since in most
/// steps no disk crosses the line.
bool any_may_be_below(const OutletLine& line, const double* __restrict x, const double* __restrict y,
                      const std::uint8_t* __restrict active, std::size_t n) {
  std::uint64_t maybe = 0;
  for (std::size_t i = 0; i < n; ++i)
    maybe |= (~std::bit_cast<std::uint64_t>(line.below(x[i], y[i])) >> 63) & static_cast<std::uint64_t>(active[i] != 0);
  return maybe != 0;
}

}  // namespace

double below_outlet(const Model& m, double x, double y) { return OutletLine(m).below(x, y); }

bool may_discharge(const Model& m) {
  if (!m.discharge.enabled) return false;
  const Elements& e = m.elements;
  return any_may_be_below(OutletLine(m), e.x.data(), e.y.data(), e.active.data(), e.size());
}

std::size_t remove_discharged(Model& m) {
  if (!may_discharge(m)) return 0;
  const OutletLine line(m);
  Elements& e = m.elements;
  std::size_t n = 0;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i] && line.below(e.x[i], e.y[i]) > 0.0) {
      e.active[i] = 0;
      ++n;
    }
  return n;
}

Discharged discharged(const Model& m) {
  Discharged d;
  if (!m.discharge.enabled) return d;
  const OutletLine line(m);
  const Elements& e = m.elements;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (!e.active[i] && line.below(e.x[i], e.y[i]) > 0.0) {
      ++d.count;
      d.mass += e.mass[i];
    }
  return d;
}

std::optional<std::size_t> keystone(const Model& m) {
  if (!m.discharge.enabled) return std::nullopt;
  const Wall& w = m.walls[static_cast<std::size_t>(m.discharge.slit)];
  const OutletLine line(m);
  const Vec2 ab = w.b - w.a, mid = line.mid;
  const double len2 = dot(ab, ab);
  const Elements& e = m.elements;
  std::optional<std::size_t> best;
  double best_d2 = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i] || !(line.below(e.x[i], e.y[i]) <= 0.0)) continue;
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
