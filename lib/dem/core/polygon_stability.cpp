// The time-step guard of a model with polygon elements (docs/model.md (P9)): the block-Gershgorin bound of
// stability.cpp with every contact point counted, each with the largest lever its element allows.
//
// A contact point at lever r_i from the centre of element i adds the rank-one term k g gᵀ to the
// mass-normalised stiffness, g_i = (d/√m_i, (r_i × d)/√I_i) for its direction d (the normal, or the
// tangent for the shear spring), so |g_i|² ≤ a_i² = 1/m_i + R_i²/I_i with R_i the circumradius (a disk: its
// radius). Block Gershgorin then bounds every eigenvalue by max_i Σ_c k_c (a_i² + a_i a_j), a_j = 0 for a
// wall or an element that is not free; the dashpots give the damping rate the same way. The contact points an
// element can have: a polygon with V_i corners touches a segment wall at most at V_i corners and the wall's
// 2 ends, a point wall once, a polygon j at V_i + V_j points, a disk once; a disk touches each partner once.
// No packing argument limits the partners: every active element within reach (numerics.guard_reach, G7).
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "dem/core/simulation.hpp"
#include "dem/core/stability.hpp"

namespace dem {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

int corners_of(const Model& m, std::size_t i) {
  const Elements& e = m.elements;
  return e.shape[i] == Shape::polygon
             ? static_cast<int>(m.polygons[static_cast<std::size_t>(m.polygon_of[i])].vertices.size())
             : 0;
}

double reach_of(const Elements& e, std::size_t i, double reach) {
  return e.motion[i] == Motion::free ? reach : e.motion[i] == Motion::fixed ? 0.0 : inf;
}

}  // namespace

StabilityBound polygon_stability_bound(const Model& m, const std::vector<StabilityTerm>& extra) {
  const Elements& e = m.elements;
  const std::size_t n = e.size();
  StabilityBound out;
  out.limit = out.limit_sticking = inf;
  out.assumptions = fmt::format(
      "a case with polygons (P9): every contact point an element can form with every active partner{}, a polygon of V "
      "corners touching a segment wall at V + 2 points, a point wall at 1, a polygon of V' corners at V + V', a "
      "disk at 1; each point's spring at the largest lever (the circumradius); block-Gershgorin bound; shear "
      "springs counted only in the sticking limit",
      std::isfinite(m.numerics.guard_reach) ? fmt::format(" within reach (numerics.guard_reach = {:g} m)", m.numerics.guard_reach)
                                            : std::string{});
  auto a_of = [&](std::size_t i) { return std::sqrt(e.inv_mass[i] + e.radius[i] * e.radius[i] * e.inv_inertia[i]); };
  const double reach = m.numerics.guard_reach;
  for (std::size_t i = 0; i < n; ++i) {
    if (!e.active[i] || e.motion[i] != Motion::free) continue;
    const double ai = a_of(i);
    double lam = 0.0, lam_s = 0.0, c = 0.0, c_s = 0.0, hopf = inf, hopf_s = inf;
    int element_points = 0, wall_points = 0;
    std::vector<std::string> laws;
    auto add = [&](std::int32_t law_index, int points, double aj, double mass_j) {
      const PairLaw& law = m.laws[static_cast<std::size_t>(law_index)];
      const Dashpots d = linear_dashpots(law, e.mass[i], mass_j);
      const double w = points * (ai * ai + ai * aj);
      lam += law.linear.kn * w;
      lam_s += (law.linear.kn + law.linear.ks) * w;
      c += d.eta_n * w;
      c_s += (d.eta_n + d.eta_s) * w;
      if (law.linear.kn > 0.0) hopf = std::min(hopf, d.eta_n / law.linear.kn), hopf_s = std::min(hopf_s, d.eta_n / law.linear.kn);
      if (law.linear.ks > 0.0) hopf_s = std::min(hopf_s, d.eta_s / law.linear.ks);
      const std::string name = fmt::format("contact {}", law_index);
      if (std::find(laws.begin(), laws.end(), name) == laws.end()) laws.push_back(name);
    };
    const int vi = corners_of(m, i);
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || !e.active[j]) continue;
      const std::int32_t law = m.law_index(e.material[i], e.material[j]);
      if (law < 0) continue;
      const double gap = std::hypot(e.x[j] - e.x[i], e.y[j] - e.y[i]) - e.radius[i] - e.radius[j];
      if (gap > reach_of(e, i, reach) + reach_of(e, j, reach)) continue;
      const int vj = corners_of(m, j);
      const int points = vi > 0 && vj > 0 ? vi + vj : 1;
      add(law, points, e.motion[j] == Motion::free ? a_of(j) : 0.0, e.mass[j]);
      element_points += points;
    }
    for (const Wall& w : m.walls) {
      const std::int32_t law = m.law_index(e.material[i], w.material);
      if (law < 0 || w.open) continue;
      const int points = w.kind == WallKind::point ? 1 : (vi > 0 ? vi + 2 : 1);
      add(law, points, 0.0, 0.0);
      wall_points += points;
    }
    for (const StabilityTerm& t : extra) {  // physics beyond the contacts, on the translations
      if (!t.stiffness.empty()) lam += t.stiffness[i], lam_s += t.stiffness[i], hopf = std::min(hopf, t.hopf_ratio), hopf_s = std::min(hopf_s, t.hopf_ratio);
      if (!t.damping.empty()) c += t.damping[i], c_s += t.damping[i];
    }
    const double limit = stable_dt_rates(m.numerics.integrator, lam, c, hopf);
    const double limit_s = stable_dt_rates(m.numerics.integrator, lam_s, c_s, hopf_s);
    if (std::isnan(limit) || std::isnan(limit_s)) {
      out.limit = out.limit_sticking = std::numeric_limits<double>::quiet_NaN();
      out.element = static_cast<std::int64_t>(i);
      out.law = "a non-finite stiffness, damping or mass";
      return out;
    }
    out.limit_sticking = std::min(out.limit_sticking, limit_s);
    if (limit < out.limit) {
      out.limit = limit;
      out.element = static_cast<std::int64_t>(i);
      out.law = fmt::format("{}", fmt::join(laws, ", "));
      out.element_contacts = element_points;
      out.wall_contacts = wall_points;
      out.stiffness_rate = lam;
      out.damping_rate = c;
    }
  }
  out.limit_gershgorin = out.limit, out.limit_gershgorin_sticking = out.limit_sticking;
  return out;
}

}  // namespace dem
