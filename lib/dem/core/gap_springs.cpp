// Gap springs (docs/model.md §6, B1–B5): bonds between disks in contact or slightly apart at the start, in
// parallel with their contact law; one readable loop, run on one thread after the other sweeps by step() and
// by the reference step alike.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>

#include "dem/core/simulation.hpp"

namespace dem {

void Simulation::form_gap_springs() {
  gap_springs_.clear();
  const bool any = std::any_of(m_.laws.begin(), m_.laws.end(), [](const PairLaw& l) { return l.kind == LawKind::linear && l.gap.enabled; });
  if (!any) return;
  const Elements& e = m_.elements;
  if (std::any_of(e.shape.begin(), e.shape.end(), [](Shape s) { return s != Shape::disk; }))
    throw std::invalid_argument("gap springs bond disks only: a case with gap springs cannot hold PREs or polygons (not modelled)");
  if (m_.numerics.reorder_every > 0) throw std::invalid_argument("numerics.reorder_every is not available with gap springs");
  if (!m_.preloads.empty()) throw std::invalid_argument("a static preload is not available with gap springs");
  // (B1): every pair whose surface gap is at most the law's distance now. The elements sorted by x, each
  // pair tried while the x distance can still be within reach.
  double reach = 0.0, r_max = 0.0;
  for (const PairLaw& l : m_.laws)
    if (l.gap.enabled) reach = std::max(reach, l.gap.distance);
  for (std::size_t i = 0; i < e.size(); ++i) r_max = std::max(r_max, e.radius[i]);
  std::vector<std::uint32_t> by_x(e.size());
  std::iota(by_x.begin(), by_x.end(), 0u);
  std::stable_sort(by_x.begin(), by_x.end(), [&](std::uint32_t a, std::uint32_t b) { return e.x[a] < e.x[b]; });
  for (std::size_t a = 0; a < by_x.size(); ++a)
    for (std::size_t b = a + 1; b < by_x.size() && e.x[by_x[b]] - e.x[by_x[a]] <= 2.0 * r_max + reach; ++b) {
      const std::uint32_t i = std::min(by_x[a], by_x[b]), j = std::max(by_x[a], by_x[b]);
      const std::int32_t law = m_.law_index(e.material[i], e.material[j]);
      if (law < 0 || !m_.laws[static_cast<std::size_t>(law)].gap.enabled) continue;
      const GapSpringLaw& g = m_.laws[static_cast<std::size_t>(law)].gap;
      const double gap = std::hypot(e.x[j] - e.x[i], e.y[j] - e.y[i]) - e.radius[i] - e.radius[j];
      if (gap > g.distance) continue;
      GapSpring s;
      s.i = i, s.j = j, s.law = law;
      const double m_eff = e.mass[i] * e.mass[j] / (e.mass[i] + e.mass[j]);
      s.eta_n = 2.0 * g.damping_ratio * std::sqrt(m_eff * g.kn);  // (B3)
      s.eta_s = 2.0 * g.damping_ratio * std::sqrt(m_eff * g.ks);
      gap_springs_.push_back(s);
    }
  std::sort(gap_springs_.begin(), gap_springs_.end(),
            [](const GapSpring& a, const GapSpring& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
}

void Simulation::sweep_gap_springs(double inv_dt) {
  Elements& e = m_.elements;
  for (GapSpring& b : gap_springs_) {
    if (!b.intact) continue;
    const std::uint32_t i = b.i, j = b.j;
    if (!e.active[i] || !e.active[j]) {  // an element left the run: its bonds go with it
      b.intact = false;
      b.en = b.es = b.fn = b.fs = 0.0;
      continue;
    }
    const double ddx = e.x[j] - e.x[i], ddy = e.y[j] - e.y[i];
    const double dist = std::sqrt(ddx * ddx + ddy * ddy);
    const double nx = ddx / dist, ny = ddy / dist;  // from i towards j
    const double ux = e.dx[i] - e.dx[j], uy = e.dy[i] - e.dy[j];
    const double du_n = ux * nx + uy * ny;  // (K5), approach positive
    const double du_s = -ux * ny + uy * nx + e.radius[i] * e.dphi[i] + e.radius[j] * e.dphi[j];
    const GapSpringLaw& law = m_.laws[static_cast<std::size_t>(b.law)].gap;
    const GapSpringForce f = gap_spring_force(law, du_n, du_s, dist - e.radius[i] - e.radius[j], inv_dt, b);
    b.fn = f.fn, b.fs = f.fs;
    if (f.broke) continue;
    // (B5) as (K15): force on i is −f_n n − f_s t, t = (−sin α, cos α); on j the opposite.
    const double fx = -f.fn * nx + f.fs * ny, fy = -f.fn * ny - f.fs * nx;
    e.fx[i] += fx, e.fy[i] += fy, e.fx[j] -= fx, e.fy[j] -= fy;
    e.moment[i] -= e.radius[i] * f.fs;
    e.moment[j] -= e.radius[j] * f.fs;
  }
}

double Simulation::gap_spring_energy() const {
  double sum = 0.0;
  for (const GapSpring& b : gap_springs_) {
    if (!b.intact) continue;
    const GapSpringLaw& l = m_.laws[static_cast<std::size_t>(b.law)].gap;
    if (l.kn > 0.0) sum += 0.5 * b.en * b.en / l.kn;
    if (l.ks > 0.0) sum += 0.5 * b.es * b.es / l.ks;
  }
  return sum;
}

std::size_t Simulation::gap_springs_intact() const {
  return static_cast<std::size_t>(std::count_if(gap_springs_.begin(), gap_springs_.end(), [](const GapSpring& b) { return b.intact; }));
}

}  // namespace dem
