// The eigenvalue guard of a bonded structure (stability_eigen.hpp; docs/model.md (G1)–(G4)).
#include "dem/core/stability_eigen.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <limits>

#include "dem/core/simulation.hpp"

namespace dem {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double kTouch = 1e-9;  // a pair touches at the start if its gap is below this × the radius
// A bonded pair still acts in tension, up to its strength (a strain of ~1e-3 for Matsui's mortar): when the
// guard is evaluated again during a run (G7) it counts a bonded pair apart by up to this × the radii.
constexpr double kBondStretch = 0.05;

/// Bonded as face_geometry.hpp has it: a face law bonding at the start, or one lattice group (j < 0: a wall).
bool bonds_at_start(const Model& m, const PairLaw& law, std::size_t i, std::int64_t j) {
  if (law.kind != LawKind::face) return false;
  const Elements& e = m.elements;
  return law.bond_at_start || (j >= 0 && e.group[i] >= 0 && e.group[i] == e.group[static_cast<std::size_t>(j)]);
}

/// The rows b of a spring acting along the unit vector d at point p between element i (or ground, −1)
/// and element j (or ground): extension = d·(u_j + θ_j k×(p − c_j)) − d·(u_i + θ_i k×(p − c_i)), each
/// DOF scaled by 1/√m or 1/√I (mass-normalised).
NetworkSpring spring_between(const Elements& e, const std::vector<int>& dof, int i, int j, Vec2 p, Vec2 d, double k,
                             double eta) {
  NetworkSpring s;
  s.k = k;
  s.eta = eta;
  auto fill = [&](int body, double sign, double b[3]) {
    const auto u = static_cast<std::size_t>(body);
    const double qx = p.x - e.x[u], qy = p.y - e.y[u];
    b[0] = sign * d.x * std::sqrt(e.inv_mass[u]);
    b[1] = sign * d.y * std::sqrt(e.inv_mass[u]);
    b[2] = sign * (-d.x * qy + d.y * qx) * std::sqrt(e.inv_inertia[u]);
  };
  if (i >= 0 && dof[static_cast<std::size_t>(i)] >= 0) {
    s.dof_a = dof[static_cast<std::size_t>(i)];
    fill(i, -1.0, s.ba);
  }
  if (j >= 0 && dof[static_cast<std::size_t>(j)] >= 0) {
    s.dof_b = dof[static_cast<std::size_t>(j)];
    fill(j, 1.0, s.bb);
  }
  return s;
}

/// The springs of one contact at the start: element i against element j (j < 0: a wall at `wall_point`).
/// Face law: N normal and N shear springs on the face line at aξ (M6, M13, M15.1, M15.2); linear law:
/// a normal spring and, as a Coulomb shear spring, a tangential one at the touching point (K5, K6, K10).
void add_contact(const Model& m, const std::vector<int>& dof, const PairLaw& law, int i, int j, Vec2 normal,
                 StartNetwork& net) {
  const Elements& e = m.elements;
  const auto ui = static_cast<std::size_t>(i);
  const double ri = e.radius[ui];
  const Vec2 t{-normal.y, normal.x};
  const Vec2 face{e.x[ui] + ri * normal.x, e.y[ui] + ri * normal.y};
  auto keep = [&](NetworkSpring s, bool coulomb) {
    if (s.dof_a < 0 && s.dof_b < 0) return;  // between two grounded bodies
    s.coulomb_shear = coulomb;
    if (s.k > 0.0 && s.eta / s.k < (coulomb ? net.hopf_stick : net.hopf)) {
      (coulomb ? net.hopf_stick : net.hopf) = s.eta / s.k;
    }
    net.springs.push_back(s);
  };
  if (law.kind == LawKind::face) {
    const double rj = j >= 0 ? e.radius[static_cast<std::size_t>(j)] : 0.0;
    const double mi = e.mass[ui], mj = j >= 0 ? e.mass[static_cast<std::size_t>(j)] : 0.0;
    const double meff = j >= 0 ? mi * mj / (mi + mj) : mi;
    const FaceConstants fc = face_constants(law, ri, rj, meff, m.thickness);
    for (int s = 0; s < law.face.segments; ++s) {
      const double l = fc.half_length * segment_xi(law.face.positions, law.face.segments, s);
      const Vec2 p{face.x + l * t.x, face.y + l * t.y};
      keep(spring_between(e, dof, i, j, p, normal, fc.kn, fc.eta_n), false);  // (M15.1)
      keep(spring_between(e, dof, i, j, p, t, fc.ks, fc.eta_s), false);       // (M15.2)
    }
    return;
  }
  const Dashpots d = linear_dashpots(law, e.mass[ui], j >= 0 ? e.mass[static_cast<std::size_t>(j)] : 0.0);
  keep(spring_between(e, dof, i, j, face, normal, law.linear.kn, d.eta_n), false);  // (K5.a, K6.a)
  keep(spring_between(e, dof, i, j, face, t, law.linear.ks, d.eta_s), true);        // (K5.b, K10.a)
  if (law.rolling.enabled) {  // (R1–R5): a spring on the relative rotation φ_i − φ_j alone
    const auto uj = static_cast<std::size_t>(j);
    const double rj = j >= 0 ? e.radius[uj] : 0.0;
    NetworkSpring s;
    s.k = rolling_stiffness(law.rolling, law.linear.kn, rolling_radius(ri, rj));
    s.eta = rolling_dashpot(law.rolling, rolling_inertia(e.inertia[ui], e.mass[ui], ri, j >= 0 ? e.inertia[uj] : 0.0,
                                                         j >= 0 ? e.mass[uj] : 0.0, rj), s.k);
    if (dof[ui] >= 0) s.dof_a = dof[ui], s.ba[2] = std::sqrt(e.inv_inertia[ui]);
    if (j >= 0 && dof[uj] >= 0) s.dof_b = dof[uj], s.bb[2] = -std::sqrt(e.inv_inertia[uj]);
    keep(s, false);
  }
}

}  // namespace

StartNetwork start_network(const Model& m, const std::vector<std::uint8_t>* only) {
  const Elements& e = m.elements;
  const std::size_t n = e.size();
  StartNetwork net;
  net.hopf = net.hopf_stick = inf;
  net.bonded.assign(n, 0);
  net.dof.assign(n, -1);
  std::vector<int>& dof = net.dof;
  for (std::size_t i = 0; i < n; ++i)  // checked access: once per guard, O(n)
    if (e.active.at(i) && e.motion.at(i) == Motion::free && (only == nullptr || only->at(i))) dof.at(i) = 3 * (net.dofs++);
  net.dofs *= 3;
  auto bonds = [&](const PairLaw& law, std::size_t i, std::int64_t j) { return bonds_at_start(m, law, i, j); };
  auto mark = [&](std::size_t i) { net.bonded[i] = 1, net.any_bond = true; };
  // element pairs touching at the start (the guard runs this only for models with bonds: O(n²) is fine
  // for lattices; a silo without bonds never gets here)
  for (std::size_t i = 0; i < n; ++i) {
    if (!e.active[i]) continue;
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!e.active[j] || (dof[i] < 0 && dof[j] < 0)) continue;
      const std::int32_t li = m.law_index(e.material[i], e.material[j]);
      if (li < 0) continue;
      const double dx = e.x[j] - e.x[i], dy = e.y[j] - e.y[i], dist = std::hypot(dx, dy);
      const PairLaw& law = m.laws[static_cast<std::size_t>(li)];
      const double touch = bonds(law, i, static_cast<std::int64_t>(j)) ? kBondStretch : kTouch;
      if (dist > (e.radius[i] + e.radius[j]) * (1.0 + touch) || dist == 0.0) continue;
      add_contact(m, dof, law, static_cast<int>(i), static_cast<int>(j), {dx / dist, dy / dist}, net);
      if (bonds(law, i, static_cast<std::int64_t>(j))) mark(i), mark(j);
    }
    if (dof[i] < 0) continue;
    for (const Wall& w : m.walls) {
      const std::int32_t li = m.law_index(e.material[i], w.material);
      if (li < 0 || w.open) continue;
      const Vec2 c{e.x[i], e.y[i]};
      const Vec2 q = closest_point(w, c) - c;
      const double dist = norm(q);
      const PairLaw& law = m.laws[static_cast<std::size_t>(li)];
      if (dist > e.radius[i] * (1.0 + (bonds(law, i, -1) ? kBondStretch : kTouch)) || dist == 0.0) continue;
      add_contact(m, dof, law, static_cast<int>(i), -1, {q.x / dist, q.y / dist}, net);
      if (bonds(law, i, -1)) mark(i);
    }
  }
  net.hopf_stick = std::min(net.hopf_stick, net.hopf);
  return net;
}

namespace {

/// (G6) The least angle at element i of radius r between the directions of two partners touching it,
/// each an element of radius ρ or a segment wall (ρ = +inf), with overlaps up to ε·ρ between them.
double least_separation(double r, double rho_a, double rho_b) {
  constexpr double eps = kGuardOverlap;
  const bool wall_a = !std::isfinite(rho_a), wall_b = !std::isfinite(rho_b);
  if (wall_a && wall_b) return 0.0;  // two walls may meet at a corner
  if (wall_a || wall_b) {
    const double rho = wall_a ? rho_b : rho_a;
    return std::acos(std::clamp((r - (1.0 - eps) * rho) / (r + rho), -1.0, 1.0));
  }
  const double d1 = r + rho_a, d2 = r + rho_b, d12 = (1.0 - eps) * (rho_a + rho_b);
  return std::acos(std::clamp((d1 * d1 + d2 * d2 - d12 * d12) / (2.0 * d1 * d2), -1.0, 1.0));
}

}  // namespace

std::vector<std::uint8_t> angular_room(const Model& m, double new_radius) {
  const Elements& e = m.elements;
  const std::size_t n = e.size();
  const double reach = m.numerics.guard_reach;
  constexpr double wall = std::numeric_limits<double>::infinity();
  // how far a wall may travel in the run: its drive's fastest speed over the duration (static: 0)
  std::vector<double> travel(m.walls.size(), 0.0);
  for (std::size_t w = 0; w < m.walls.size(); ++w)
    if (const std::int32_t d = m.walls[w].drive; d >= 0)
      for (const Vec2 v : m.drives[static_cast<std::size_t>(d)].v) travel[w] = std::max(travel[w], norm(v) * m.numerics.duration);
  std::vector<std::uint8_t> room(n, 0);
  std::vector<std::pair<double, double>> around;  // (direction, partner radius or +inf for a wall)
  std::vector<double> kinds;                      // the new partners' radii: +inf a wall's face, 0 a point
  for (std::size_t i = 0; i < n; ++i) {
    if (!e.active[i]) continue;
    around.clear();
    const Vec2 c{e.x[i], e.y[i]};
    // what keeps its place beside i: its bonded partners and the fixed elements and static walls it touches
    // (an unbonded free or a driven partner, a moving wall may leave and make room)
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || !e.active[j]) continue;
      const std::int32_t li = m.law_index(e.material[i], e.material[j]);
      if (li < 0) continue;
      const bool bonded = bonds_at_start(m, m.laws[static_cast<std::size_t>(li)], i, static_cast<std::int64_t>(j));
      if (!bonded && e.motion[j] != Motion::fixed) continue;
      const double dx = e.x[j] - c.x, dy = e.y[j] - c.y, dist = std::hypot(dx, dy);
      if (dist > (e.radius[i] + e.radius[j]) * (1.0 + (bonded ? kBondStretch : kTouch)) || dist == 0.0) continue;
      around.emplace_back(std::atan2(dy, dx), e.radius[j]);
    }
    kinds.clear();
    if (std::isfinite(new_radius)) kinds.push_back(new_radius);
    const double own = std::isfinite(reach) ? reach : wall;
    for (std::size_t w = 0; w < m.walls.size(); ++w) {
      const Wall& wl = m.walls[w];
      if (wl.open || m.law_index(e.material[i], wl.material) < 0) continue;
      const Vec2 q = closest_point(wl, c) - c;
      const double dist = norm(q), within = e.radius[i] + own + travel[w];
      if (wl.drive < 0 && dist <= e.radius[i] * (1.0 + kTouch) && dist > 0.0)
        around.emplace_back(std::atan2(q.y, q.x), wall);  // a static wall it touches
      if (dist > within) continue;  // out of reach (G7)
      // a segment's face (its direction fixed: drives translate) and its ends, a point wall: points
      if (wl.kind == WallKind::segment) kinds.push_back(wall);
      for (const Vec2 p : wl.kind == WallKind::segment ? std::vector<Vec2>{wl.a, wl.b} : std::vector<Vec2>{wl.a})
        if (norm(p - c) <= within) kinds.push_back(0.0);
    }
    if (kinds.empty()) continue;
    if (around.empty()) {
      room[i] = 1;
      continue;
    }
    std::sort(around.begin(), around.end());
    const double r = e.radius[i];
    for (std::size_t k = 0; k < around.size() && !room[i]; ++k) {
      const auto& [ta, ra] = around[k];
      const auto& [tb, rb] = around[(k + 1) % around.size()];
      const double gap = k + 1 < around.size() ? tb - ta : tb - ta + 2.0 * std::numbers::pi;  // one alone: 2π
      for (const double rn : kinds)
        if (gap + 2.0 * kStartTurn >= least_separation(r, ra, rn) + least_separation(r, rn, rb)) room[i] = 1;
    }
  }
  return room;
}

namespace {

/// Largest eigenvalue of a symmetric tridiagonal matrix (diagonal a, off-diagonal b) by Sturm-sequence
/// bisection (to roundoff), and its unit eigenvector by inverse iteration (Thomas algorithm).
std::pair<double, std::vector<double>> tridiagonal_max(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t m = a.size();
  double lo = inf, hi = -inf;
  for (std::size_t i = 0; i < m; ++i) {
    const double r = (i > 0 ? std::abs(b[i - 1]) : 0.0) + (i + 1 < m ? std::abs(b[i]) : 0.0);
    lo = std::min(lo, a[i] - r), hi = std::max(hi, a[i] + r);
  }
  auto below = [&](double x) {  // eigenvalues below x
    std::size_t count = 0;
    double q = a[0] - x;
    for (std::size_t i = 0;; ++i) {
      if (q < 0.0) ++count;
      if (i + 1 == m) break;
      if (q == 0.0) q = 1e-300;
      q = a[i + 1] - x - b[i] * b[i] / q;
    }
    return count;
  };
  for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(std::abs(lo), std::abs(hi)); ++it) {
    const double mid = 0.5 * (lo + hi);
    (below(mid) >= m ? hi : lo) = mid;
  }
  const double lambda = hi;
  std::vector<double> s(m, 1.0 / std::sqrt(double(m))), d(m);
  const double scale = std::max(std::abs(lo), std::abs(hi));
  if (m == 1 || !(scale > 0.0)) return {lambda, s};  // a zero operator: any unit vector
  // inverse iteration with the shift just above λ: (T − σI) y = s
  const double sigma = lambda + 1e-10 * scale;
  for (int it = 0; it < 3; ++it) {
    d[0] = a[0] - sigma;
    std::vector<double> y = s;
    for (std::size_t i = 1; i < m; ++i) {  // forward elimination (checked access: m ≤ 100, not hot)
      const double f = b.at(i - 1) / (d.at(i - 1) == 0.0 ? 1e-300 : d.at(i - 1));
      d.at(i) = a.at(i) - sigma - f * b.at(i - 1);
      y.at(i) -= f * y.at(i - 1);
    }
    s[m - 1] = y[m - 1] / (d[m - 1] == 0.0 ? 1e-300 : d[m - 1]);
    for (std::size_t i = m - 1; i-- > 0;) s[i] = (y[i] - b[i] * s[i + 1]) / (d[i] == 0.0 ? 1e-300 : d[i]);
    double n2 = 0.0;
    for (double x : s) n2 += x * x;
    for (double& x : s) x /= std::sqrt(n2);
  }
  for (double x : s)
    if (!std::isfinite(x)) return {lambda, std::vector<double>(m, 1.0 / std::sqrt(double(m)))};
  return {lambda, s};
}

/// λ_max of a symmetric positive semi-definite operator on n values: Lanczos with full
/// reorthogonalisation, at most 100 steps; returns the largest Ritz value plus its residual β|s_m|.
/// `start`: the start vector (empty: a fixed one with no symmetry of a lattice); replaced by the Ritz
/// vector on return (a warm start for the next, nearby operator).
double lanczos_max(int n, const std::function<void(const std::vector<double>&, std::vector<double>&)>& apply,
                   std::vector<double>& start) {
  if (n == 0) return 0.0;
  const int steps = std::min(n, 100);
  const auto un = static_cast<std::size_t>(n);
  std::vector<std::vector<double>> basis;
  std::vector<double> alpha, beta, v(un), w(un);
  double norm0 = 0.0;
  for (std::size_t i = 0; i < un; ++i) {  // a start vector with no symmetry of the lattice, or the given one
    const double fixed = 1.0 + 0.5 * std::sin(1.7 * double(i) + 0.013 * double(i) * double(i));
    v[i] = start.size() == un ? start[i] + 1e-3 * fixed : fixed;  // keep every direction in the start
    norm0 += v[i] * v[i];
  }
  for (double& x : v) x /= std::sqrt(norm0);
  double residual = 0.0;
  for (int k = 0; k < steps; ++k) {
    basis.push_back(v);
    apply(v, w);
    double a = 0.0;
    for (std::size_t i = 0; i < un; ++i) a += w[i] * v[i];
    alpha.push_back(a);
    for (int pass = 0; pass < 2; ++pass)  // w ⟂ every basis vector (full reorthogonalisation, twice)
      for (const auto& q : basis) {
        double h = 0.0;
        for (std::size_t i = 0; i < un; ++i) h += w[i] * q[i];
        for (std::size_t i = 0; i < un; ++i) w[i] -= h * q[i];
      }
    double b = 0.0;
    for (double x : w) b += x * x;
    b = std::sqrt(b);
    const bool last_step = b <= 1e-14 * std::abs(a) || k + 1 == steps;
    if (last_step || (k >= 9 && (k + 1) % 10 == 0)) {  // the Ritz value every 10 steps (Jacobi is m³)
      const auto [theta, ritz] = tridiagonal_max(alpha, beta);
      residual = b * std::abs(ritz.back());
      if (last_step || residual <= 1e-7 * theta) {  // the residual is added: still an upper estimate
        start.assign(un, 0.0);
        for (std::size_t j = 0; j < basis.size(); ++j)
          for (std::size_t i = 0; i < un; ++i) start[i] += ritz[j] * basis[j][i];
        return theta + residual;
      }
    }
    beta.push_back(b);
    for (std::size_t i = 0; i < un; ++i) v[i] = w[i] / b;
  }
  return 0.0;  // not reached
}

/// λ_max of Σ (wk k + wc η) b bᵀ plus the diagonal wk·diag_k + wc·diag_c (G2, G5).
double apply_weighted(const StartNetwork& net, bool sticking, double wk, double wc, std::vector<double>& start) {
  const std::vector<double>& dk = sticking ? net.diag_k_stick : net.diag_k;
  const std::vector<double>& dc = sticking ? net.diag_c_stick : net.diag_c;
  return lanczos_max(net.dofs, [&](const std::vector<double>& x, std::vector<double>& y) {
    std::fill(y.begin(), y.end(), 0.0);
    for (const NetworkSpring& s : net.springs) {
      if (s.coulomb_shear && !sticking) continue;
      const double wgt = wk * s.k + wc * s.eta;
      if (wgt == 0.0) continue;
      double e = 0.0;
      for (int c = 0; c < 3; ++c) {
        if (s.dof_a >= 0) e += s.ba[c] * x[static_cast<std::size_t>(s.dof_a + c)];
        if (s.dof_b >= 0) e += s.bb[c] * x[static_cast<std::size_t>(s.dof_b + c)];
      }
      e *= wgt;
      for (int c = 0; c < 3; ++c) {
        if (s.dof_a >= 0) y[static_cast<std::size_t>(s.dof_a + c)] += s.ba[c] * e;
        if (s.dof_b >= 0) y[static_cast<std::size_t>(s.dof_b + c)] += s.bb[c] * e;
      }
    }
    for (std::size_t d = 0; d < dk.size() && d < y.size(); ++d) y[d] += wk * dk[d] * x[d];
    for (std::size_t d = 0; d < dc.size() && d < y.size(); ++d) y[d] += wc * dc[d] * x[d];
  }, start);
}

double rate_from(const StartNetwork& net, double dt, bool sticking, std::vector<double>& start) {
  return apply_weighted(net, sticking, dt * dt, 2.0 * dt, start);  // (G2)
}

}  // namespace

double network_rate(const StartNetwork& net, double dt, bool sticking) {
  std::vector<double> start;
  return rate_from(net, dt, sticking, start);
}

double network_eigenvalue(const StartNetwork& net, bool damping, bool sticking) {
  std::vector<double> start;
  return apply_weighted(net, sticking, damping ? 0.0 : 1.0, damping ? 1.0 : 0.0, start);
}

double eigen_limit(const StartNetwork& net, Integrator integrator, bool sticking, double lambda_new, double c_new,
                   double hopf_new, int* solves) {
  const double kappa = integrator == Integrator::k18 ? 4.0 : 12.0;  // (G3)
  const double lam = network_eigenvalue(net, false, sticking), c = network_eigenvalue(net, true, sticking);
  // bracket: both maxima taken apart (a safe, smaller Δt) and the stiffness alone (a larger one)
  double lo = stable_dt_rates(integrator, lam + lambda_new, c + c_new, inf);
  double hi = lam + lambda_new > 0.0 ? std::sqrt(kappa / (lam + lambda_new)) : kappa / (2.0 * (c + c_new));
  if (!std::isfinite(lo)) return inf;
  std::vector<double> warm;  // the top vector of the last operator: the next Lanczos starts there
  auto excess = [&](double dt) {
    if (solves) ++*solves;
    return rate_from(net, dt, sticking, warm) + dt * dt * lambda_new + 2.0 * dt * c_new - kappa;
  };
  // Illinois regula falsi on the bracket (excess(lo) ≤ 0 ≤ excess(hi)); the stable end lo is returned
  double g_lo = excess(lo), g_hi = excess(hi);
  if (g_hi < 0.0) return integrator == Integrator::k19 ? std::min(hi, std::min(sticking ? net.hopf_stick : net.hopf, hopf_new)) : hi;
  if (g_lo == 0.0) hi = lo;  // lo is the root (proportional damping at the top mode): nothing to bracket
  else if (g_lo > 0.0) lo = 0.0, g_lo = -kappa;  // (Lanczos roundoff above the safe bracket end)
  int side = 0;
  for (int it = 0; it < 60 && hi - lo > 1e-4 * hi; ++it) {
    double x = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const double g = excess(x);
    if (g < 0.0) {
      lo = x, g_lo = g;
      if (side == -1) g_hi *= 0.5;
      side = -1;
    } else {
      hi = x, g_hi = g;
      if (side == 1) g_lo *= 0.5;
      side = 1;
    }
  }
  const double hopf = std::min(sticking ? net.hopf_stick : net.hopf, hopf_new);
  return integrator == Integrator::k19 ? std::min(lo, hopf) : lo;  // (G4)
}

}  // namespace dem
