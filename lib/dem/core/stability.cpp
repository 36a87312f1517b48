#include "dem/core/stability.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <unordered_map>

#include <fmt/format.h>

#include "dem/core/base_friction.hpp"
#include "dem/core/simulation.hpp"
#include "dem/core/stability_eigen.hpp"

namespace dem {

double stable_w(Integrator integrator, double zeta) {
  if (integrator == Integrator::k18) return 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta);  // refs §1.5
  return std::min(2.0 * zeta, 2.0 * (std::sqrt(zeta * zeta + 3.0) - zeta));               // refs §1.5
}

double stable_dt(Integrator integrator, double mass, double stiffness, double eta) {
  const double omega = std::sqrt(stiffness / mass);
  const double zeta = eta / (2.0 * std::sqrt(mass * stiffness));
  return stable_w(integrator, zeta) / omega;
}

// An assembly's modes are bounded by Gershgorin's theorem: ω_max² ≤ max_i λ_i with λ_i the absolute
// row sum of the mass-normalised stiffness matrix. With the damping row c_i, the mode is given the
// damping ratio ζ = c_i/(2√λ_i) (exact for one contact; for stiffness-proportional damping c_i/λ_i =
// η/K, the K19 Hopf bound Δt < η/K, is then exact for every mode).
double stable_dt_gershgorin(Integrator integrator, double stiffness_row, double damping_row) {
  if (stiffness_row <= 0.0) return std::numeric_limits<double>::infinity();
  const double omega = std::sqrt(stiffness_row);
  const double zeta = damping_row / (2.0 * omega);
  return stable_w(integrator, zeta) / omega;
}

double stable_dt_rates(Integrator integrator, double lambda, double c, double hopf_ratio) {
  if (std::isnan(lambda) || std::isnan(c) || std::isnan(hopf_ratio)) return std::numeric_limits<double>::quiet_NaN();
  if (lambda <= 0.0 && c <= 0.0) return std::numeric_limits<double>::infinity();
  if (integrator == Integrator::k18) return 4.0 / (std::sqrt(c * c + 4.0 * lambda) + c);  // refs §1.5
  const double flip = 12.0 / (std::sqrt(c * c + 12.0 * lambda) + c);                      // refs §1.5
  return lambda > 0.0 ? std::min(hopf_ratio, flip) : flip;
}

std::vector<StabilityTerm> registered_stability_terms(const Model& m) {
  // Physics beyond the contacts registers its terms here.
  std::vector<StabilityTerm> terms;
  if (m.base_plate.enabled) {
    // Base friction (M21) below its regularisation speed is a dashpot towards the plate velocity of
    // rate μ_B g_B / v_ε (translation) and its rotational analogue: added to every element's damping.
    StabilityTerm t;
    t.source = "base friction (M21), regularised below v_eps";
    t.damping.resize(m.elements.size(), 0.0);
    for (std::size_t i = 0; i < m.elements.size(); ++i) {
      const BaseFrictionRates r = base_friction_rates(m.base_plate, m.elements, i);
      t.damping[i] = std::max(r.translation, r.rotation);
    }
    terms.push_back(std::move(t));
  }
  return terms;
}

// ---------------------------------------------------------------------------------------------------
// The bound over every contact the case can form.
//
// Mass-normalised, the stiffness matrix of the assembly is a sum of rank-one spring terms k b bᵀ over
// the (x, y, φ) of the two bodies (b scaled by 1/√m, 1/√I). Block Gershgorin (Feingold–Varga, for a
// symmetric matrix with 3 × 3 blocks per element) bounds every eigenvalue by
//     λ ≤ max_i [ λ_max(A_ii) + Σ_j ‖A_ij‖₂ ].
// Per contact of element i:
//   - the normal springs put (Σk/m_i) n nᵀ into the translational part of A_ii. Their sum over the
//     contacts is bounded by max_u Σ_c w_c cos²(θ_c − u), maximised over every ARRANGEMENT of contact
//     directions θ_c the geometry allows (below);
//   - a face law's moment levers add Σ k ℓ²/I_i (its lever terms cancel in the x–φ coupling: the segment
//     positions are symmetric), shear springs add at most k_s(1/m_i + r_i²/I_i) each (the norm of
//     their rank-one term);
//   - with another element j, ‖A_ij‖ = k/√(m_i m_j) for the normal spring; the shear term's left and
//     right vectors are orthogonal to the normal one's for a disk law, so the block norm is the larger
//     of the two (the sum for a face law). A wall is not a degree of freedom: no A_ij.
// The same bound with the dashpots gives c. The limit of each element is then the exact single-DOF
// limit at (λ, c), decreasing in both (stable_dt_rates), with K19's Hopf branch Δt < η/K taken from the
// smallest η/K of the springs (a mode's c/λ is a Rayleigh quotient, at least that).
//
// Arrangements: contacts sit at directions θ_c around the element; two element contacts are at
// least 2 asin((1−ε)ρ/(r+ρ)) apart (ρ the smallest partner radius, r the largest radius of the
// element's material, ε = 1 % overlap: a packed bed at equilibrium overlaps far less, about 1e-4 r
// per layer in Kiyama's silo, refs §1.7), so at most 6 for equal disks; an element contact is at least
// acos((r − (1−ε)ρ)/(r+ρ)) from a segment wall's contact (the wall blocks the half-plane behind it:
// 90° for equal disks), any angle from a point wall's; wall contacts may coincide (a joint, a slit
// corner). An element touches at most the walls of the largest set that lie pairwise within 2r of each
// other, each wall once. The maximum over arrangements is found on a 0.5° grid with every gap rounded
// down (so each real arrangement rounds to one on it), each grid point valued at the largest w cos²θ
// within δ/2 of it: the grid maximum bounds the true one (and equals it for contacts along the axes).
//
// Shear springs of Coulomb (linear-law) contacts are counted only in `limit_sticking`: a shear mode
// cannot grow past the slider's limit |f_s| = μ f_n, where its dashpot is switched off (K13). A face
// law's shear (bonded lattices) always counts.

namespace {

constexpr double kOverlap = kGuardOverlap;
constexpr int kGrid = 720;
constexpr double inf = std::numeric_limits<double>::infinity();

struct Weights {  // the objective per contact: w cos²θ + b
  double w = 0.0, b = 0.0;
};

/// One kind of contact of an element class: stiffness and damping weights, without (slip) and with
/// (stick) the shear of Coulomb contacts.
struct Kind {
  bool present = false;
  Weights k, c, k_stick, c_stick;
  double hopf = inf, hopf_stick = inf;
  std::vector<std::string> laws;
  void merge(const Kind& o) {
    if (!o.present) return;
    auto up = [](double& a, double b) {  // the larger, and a NaN stays a NaN
      if (std::isnan(b) || b > a) a = b;
    };
    auto mx = [&](Weights& a, const Weights& b) {
      up(a.w, b.w);
      up(a.b, b.b);
    };
    mx(k, o.k);
    mx(c, o.c);
    mx(k_stick, o.k_stick);
    mx(c_stick, o.c_stick);
    hopf = std::isnan(o.hopf) ? o.hopf : std::min(hopf, o.hopf);
    hopf_stick = std::isnan(o.hopf_stick) ? o.hopf_stick : std::min(hopf_stick, o.hopf_stick);
    for (const auto& l : o.laws)
      if (std::find(laws.begin(), laws.end(), l) == laws.end()) laws.push_back(l);
    present = true;
  }
};

struct Stats {  // of the active elements of one material
  int count = 0, free_count = 0;
  double r_min = inf, r_max = 0.0, m_min = inf, m_max = 0.0, i_min = inf, vs2_max = 0.0;
  // the free ones (the degrees of freedom whose bound is computed)
  double fr_min = inf, fr_max = 0.0, fm_min = inf, fm_max = 0.0, fi_min = inf, fi_max = 0.0, fvs2_max = 0.0;
  std::int64_t lightest = -1;
};

struct Arrangement {
  double value = 0.0;
  int d = 0, s = 0, p = 0;  // element, segment-wall and point-wall contacts
};

/// max Σ_c (w_c cos²θ_c + b_c) over arrangements (see above). types 0 = element, 1 = segment wall,
/// 2 = point wall; gaps[a][b] in radians between consecutive contacts of types a, b.
///
/// Search space (exact, no arrangement is lost): the grid values f_t(p) are symmetric under p → −p and
/// p → p + kGrid/2 (cos² and the rounding interval are), and so are the gap rules. Take the contact
/// nearest the axis {0, π}, at grid distance α ≤ kGrid/4; a turn by π and a reflection bring it to
/// position α and leave every other contact at least α from the axis. So a dynamic programme over
/// "first contact at s0 = α, every contact at least s0 from the axis" for s0 = 0 … kGrid/4 visits an
/// equal-valued image of every arrangement. Since w ≥ 0, f_t(p) ≤ f_t(s0) there, and no arrangement
/// from s0 can exceed B(s0) = Σ_t max_count[t]·f_t(s0) + the point walls: B falls with s0, and the
/// search stops when B(s0) ≤ the best found (it cannot beat it, ties included).
Arrangement arrangement_search(const Weights wt[3], const int max_count[3], const std::vector<std::pair<int, int>>& wall_sets,
                            const double gaps[3][3]) {
  // Point walls have no gap to anything, so they do not constrain the others: each sits at the
  // direction of the largest value (w + b) and is added to the arrangement of the element and segment
  // contacts (which the sequence below handles: a gap between consecutive contacts implies the gaps
  // between all, as the segment–element gap is at least half the element–element gap).
  auto points_with = [&](int s) {  // the most point walls that can join s segment walls
    int best = s == 0 ? 0 : -1;
    for (const auto& [ws, wp] : wall_sets)
      if (s <= ws) best = std::max(best, wp);
    return best;  // −1: s segment walls cannot touch at once
  };
  const double point_value = wt[2].w + wt[2].b;
  const double delta = 2.0 * std::numbers::pi / kGrid;
  int g[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) g[a][b] = std::max(0, static_cast<int>(std::ceil(gaps[a][b] / delta - 1e-12)) - 1);
  std::vector<double> f[3];
  const int quarter = kGrid / 4, half = kGrid / 2;
  for (int t = 0; t < 3; ++t) {
    f[t].resize(kGrid);
    for (int p = 0; p <= quarter; ++p) {
      // the largest value over the directions that round to this grid point, |θ − pδ| ≤ δ/2
      const double lo = (p - 0.5) * delta, hi = (p + 0.5) * delta;
      const double c1 = std::cos(lo), c2 = std::cos(hi);
      const double cos2 = p == 0 ? 1.0 : std::max(c1 * c1, c2 * c2);
      const double v = wt[t].w * cos2 + wt[t].b;
      // exactly symmetric about the axis {0, π} and the normal {π/2, 3π/2}
      for (int q : {p, half - p, half + p, kGrid - p})
        if (q < kGrid) f[t][static_cast<std::size_t>(q)] = v;
    }
  }
  const int nd = max_count[0] + 1, ns = max_count[1] + 1;
  const int states = nd * ns * 2;
  auto idx = [&](int d, int s, int t) { return (d * ns + s) * 2 + t; };
  std::vector<int> points(static_cast<std::size_t>(ns));
  for (int s = 0; s < ns; ++s) points[static_cast<std::size_t>(s)] = points_with(s);
  const double none = -inf;
  std::vector<double> pm(static_cast<std::size_t>(kGrid) * states);  // prefix max over positions ≤ p
  Arrangement out;
  if (max_count[2] > 0 && points_with(0) > 0) out = {points_with(0) * point_value, 0, 0, points_with(0)};
  int most_points = 0;
  for (int s = 0; s < ns; ++s) most_points = std::max(most_points, points[static_cast<std::size_t>(s)]);
  const double points_bound = max_count[2] > 0 ? most_points * point_value : 0.0;
  for (int s0 = 0; s0 <= quarter; ++s0) {
    double bound = points_bound;
    for (int t = 0; t < 2; ++t) bound += max_count[t] * std::max(0.0, f[t][static_cast<std::size_t>(s0)]);
    if (bound <= out.value) break;  // f_t(s0) falls with s0: no later start can do better
    // the positions at least s0 from the axis {0, π}, p ≥ s0: [s0, half − s0] ∪ [half + s0, kGrid − s0]
    auto allowed = [&](int p) { return p <= half - s0 || (p >= half + s0 && p <= kGrid - s0); };
    for (int t0 = 0; t0 < 2; ++t0) {
      if (max_count[t0] == 0) continue;
      for (int p = s0; p <= std::min(kGrid - 1, kGrid - s0); ++p) {
        double* mp = &pm[static_cast<std::size_t>(p) * states];
        if (p > s0) std::copy(mp - states, mp, mp);  // prefix max up to p − 1
        else std::fill(mp, mp + states, none);
        if (!allowed(p)) continue;
        for (int d = 0; d < nd; ++d)
          for (int s = 0; s < ns; ++s) {
            const int pts = points[static_cast<std::size_t>(s)];
            if (pts < 0) continue;
            for (int t = 0; t < 2; ++t) {
              const int cnt[2] = {d, s};
              if (cnt[t] == 0) continue;
              const double ft = f[t][static_cast<std::size_t>(p)];
              double v = none;
              if (d + s == 1) {
                if (t == t0 && p == s0) v = ft;
              } else {
                int prev[2] = {d, s};
                --prev[t];
                for (int tp = 0; tp < 2; ++tp) {
                  // a gap of 0 (walls) allows the same position: its predecessors have fewer
                  // contacts and are already final at p
                  const int pp = p - g[tp][t];
                  if (pp < s0) continue;
                  const double mv = pm[static_cast<std::size_t>(pp) * states + idx(prev[0], prev[1], tp)];
                  if (mv > none) v = std::max(v, mv + ft);
                }
              }
              if (v > none) {
                double& m = mp[idx(d, s, t)];
                m = std::max(m, v);
                const bool single = d + s == 1;
                if (single || s0 + kGrid - p >= g[t][t0]) {
                  const double total = v + (max_count[2] > 0 ? pts * point_value : 0.0);
                  if (total > out.value) out = {total, d, s, max_count[2] > 0 ? pts : 0};
                }
              }
            }
          }
      }
    }
  }
  return out;
}

/// arrangement_search with its answers kept: the search is a pure function of its arguments and takes
/// most of a check, and a study's runs, a sweep's and the fuzzer's inputs ask for the same classes again
/// and again. The key is the arguments' exact bits, so a kept answer is the one the search would give.
Arrangement arrangement_max(const Weights wt[3], const int max_count[3], const std::vector<std::pair<int, int>>& wall_sets,
                            const double gaps[3][3]) {
  std::string key(sizeof(Weights) * 3 + sizeof(int) * 3 + sizeof(double) * 9, '\0');
  char* k = key.data();
  std::memcpy(k, wt, sizeof(Weights) * 3), k += sizeof(Weights) * 3;
  std::memcpy(k, max_count, sizeof(int) * 3), k += sizeof(int) * 3;
  std::memcpy(k, gaps, sizeof(double) * 9);
  for (const auto& [ws, wp] : wall_sets) key.append(reinterpret_cast<const char*>(&ws), sizeof ws).append(reinterpret_cast<const char*>(&wp), sizeof wp);
  static std::mutex mutex;
  static std::unordered_map<std::string, Arrangement> kept;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = kept.find(key); it != kept.end()) return it->second;
  }
  const Arrangement a = arrangement_search(wt, max_count, wall_sets, gaps);
  const std::lock_guard<std::mutex> lock(mutex);
  if (kept.size() >= 4096) kept.clear();  // bounded memory
  kept.emplace(std::move(key), a);
  return a;
}

double segment_distance(const Wall& a, const Wall& b) {
  auto pd = [](Vec2 p, const Wall& w) { return norm(closest_point(w, p) - p); };
  double d = std::min({pd(a.a, b), pd(a.b, b), pd(b.a, a), pd(b.b, a)});
  if (a.kind == WallKind::segment && b.kind == WallKind::segment) {  // crossing segments
    const Vec2 r = a.b - a.a, s = b.b - b.a;
    const double den = r.x * s.y - r.y * s.x;
    if (den != 0.0) {
      const Vec2 qp = b.a - a.a;
      const double t = (qp.x * s.y - qp.y * s.x) / den, u = (qp.x * r.y - qp.y * r.x) / den;
      if (t >= 0 && t <= 1 && u >= 0 && u <= 1) d = 0.0;
    }
  }
  return d;
}

/// The sets of walls that lie pairwise within `reach` of each other (an element of radius reach/2 can
/// touch at most one such set at once), as (segment walls, point walls) counts of each maximal set.
std::vector<std::pair<int, int>> wall_sets(const std::vector<const Wall*>& walls, double reach) {
  const std::size_t n = walls.size();
  std::vector<std::pair<int, int>> out;
  auto composition = [&](std::uint32_t set) {
    int sg = 0, pt = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (set >> k & 1u) ++(walls[k]->kind == WallKind::segment ? sg : pt);
    return std::pair<int, int>{sg, pt};
  };
  if (n == 0) return out;
  if (n > 24) {  // too many to enumerate: every wall at once (conservative)
    int sg = 0, pt = 0;
    for (const Wall* w : walls) ++(w->kind == WallKind::segment ? sg : pt);
    return {{sg, pt}};
  }
  std::vector<std::uint32_t> adj(n, 0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b)
      if (a != b && segment_distance(*walls[a], *walls[b]) <= reach) adj[a] |= 1u << b;
  // Bron–Kerbosch without pivoting (n ≤ 24): every maximal set
  auto rec = [&](auto&& self, std::uint32_t r, std::uint32_t p, std::uint32_t x) -> void {
    if (!p && !x) {
      out.push_back(composition(r));
      return;
    }
    while (p) {
      const int v = std::countr_zero(p);
      self(self, r | (1u << v), p & adj[static_cast<std::size_t>(v)], x & adj[static_cast<std::size_t>(v)]);
      p &= ~(1u << v);
      x |= 1u << v;
    }
  };
  rec(rec, 0u, (1u << n) - 1u, 0u);
  return out;
}

/// A second bound on the same maximum (the smaller of the two is taken): the element contacts split by
/// the partner's class, each class at most as many contacts as it has elements. The contacts of one
/// class form an arrangement of their own, so the sum over classes of each class's largest arrangement
/// (the walls added to the class with the most partners) bounds every mixed arrangement; a light disk
/// among PREs with two stiff steel partners is no longer counted as pressed by six steel ones.
Arrangement split_by_partner(const std::vector<std::pair<Kind, int>>& by_class, Weights Kind::*field, const Weights& seg,
                             const Weights& pt, const int counts[3], const std::vector<std::pair<int, int>>& sets,
                             const double gaps[3][3]) {
  Arrangement total;
  if (by_class.size() < 2) {
    total.value = inf;
    return total;
  }
  std::size_t most = 0;
  for (std::size_t i = 1; i < by_class.size(); ++i)
    if (by_class[i].second > by_class[most].second) most = i;
  for (std::size_t i = 0; i < by_class.size(); ++i) {
    const bool walls = i == most;
    const Weights w[3] = {by_class[i].first.*field, walls ? seg : Weights{}, walls ? pt : Weights{}};
    const int c[3] = {std::min(counts[0], by_class[i].second), walls ? counts[1] : 0, walls ? counts[2] : 0};
    const Arrangement a = arrangement_max(w, c, sets, gaps);
    total.value += a.value, total.d += a.d, total.s += a.s, total.p += a.p;
  }
  return total;
}

std::string law_name(const Model& m, std::int32_t law) {
  const std::size_t nm = m.materials.size();
  for (std::size_t a = 0; a < nm; ++a)
    for (std::size_t b = a; b < nm; ++b)
      if (m.law_of_pair[a * nm + b] == law)
        return fmt::format("contact {} ({}–{})", law, m.materials[a].name, m.materials[b].name);
  return fmt::format("contact {}", law);
}

/// A rolling spring (R2) and dashpot (R5) on the relative rotation add the rank-one term k_r b bᵀ with
/// b = (1/√I_i, −1/√I_j) over the two rotations: k_r/I_i to the diagonal block, k_r/√(I_i I_j) to the
/// coupling (the sum, not the larger, as it shares the rotations with the shear term), counted in both the
/// sliding and the sticking bound (the rolling limit, like the slider, caps it; the bound does not rely on
/// that). k_r grows with R_r (the largest radii); C_r with I_r ≤ I_i + m_i r_i² (the largest); the Hopf ratio
/// C_r/k_r = 2ζ_r √(I_r/k_r) is taken at the smallest I_r and the largest k_r.
void add_rolling(const PairLaw& law, const Stats& self, const Stats* other, Kind& k) {
  const bool wall = other == nullptr;
  const double r_r = rolling_radius(self.fr_max, wall ? 0.0 : other->r_max);
  const double kr = rolling_stiffness(law.rolling, law.linear.kn, r_r);
  const double i_big = self.fi_max + self.fm_max * self.fr_max * self.fr_max;
  const double i_small = rolling_inertia(self.fi_min, self.fm_min, self.fr_min, wall ? 0.0 : other->i_min,
                                         wall ? 0.0 : other->m_min, wall ? 0.0 : other->r_min);
  const double cr = rolling_dashpot(law.rolling, i_big, kr);
  const double ii = self.fi_min, ij = wall ? 0.0 : other->i_min;
  const double kb = kr / ii + (wall ? 0.0 : kr / std::sqrt(ii * ij));
  const double cb = cr / ii + (wall ? 0.0 : cr / std::sqrt(ii * ij));
  k.k.b += kb, k.k_stick.b += kb;
  k.c.b += cb, k.c_stick.b += cb;
  if (kr > 0.0) {
    const double hopf = rolling_dashpot(law.rolling, i_small, kr) / kr;
    k.hopf = std::min(k.hopf, hopf), k.hopf_stick = std::min(k.hopf_stick, hopf);
  }
}

/// The gap springs of a law between two classes (B2, B3), as the largest rates; all zero without them.
struct GapRates {
  double kn = 0.0, ks = 0.0;        // the springs
  double eta_n = 0.0, eta_s = 0.0;  // their dashpots at the largest reduced mass
  double hopf = inf;                // the smallest η_n/k_n (K19's Hopf room)
};
GapRates gap_spring_rates(const PairLaw& law, const Stats& self, const Stats& other) {
  GapRates g;
  if (!law.gap.enabled) return g;
  const double m_big = self.fm_max * other.m_max / (self.fm_max + other.m_max);
  const double m_small = self.fm_min * other.m_min / (self.fm_min + other.m_min);
  g.kn = law.gap.kn, g.ks = law.gap.ks;
  g.eta_n = 2.0 * law.gap.damping_ratio * std::sqrt(m_big * law.gap.kn);
  g.eta_s = 2.0 * law.gap.damping_ratio * std::sqrt(m_big * law.gap.ks);
  g.hopf = 2.0 * law.gap.damping_ratio * std::sqrt(m_small / law.gap.kn);
  return g;
}

/// What the bound assumes of the linear law's options present in the model (rolling, gap springs).
std::string option_assumptions(const Model& m) {
  std::string out;
  if (std::any_of(m.laws.begin(), m.laws.end(), [](const PairLaw& l) { return l.kind == LawKind::linear && l.rolling.enabled; }))
    out += "; rolling springs and dashpots (R2, R5) on the rotations, in both limits (add_rolling)";
  if (std::any_of(m.laws.begin(), m.laws.end(), [](const PairLaw& l) { return l.kind == LawKind::linear && l.gap.enabled; }))
    out += "; gap springs and dashpots (B2, B3) in parallel with every element contact of their law, their shear in the sliding limit too";
  return out;
}

/// The weights of one contact of an element of class `self` with a partner of class `other` (nullptr
/// for a wall) under `law`.
Kind contact_kind(const Model& m, std::int32_t law_index, const Stats& self, const Stats* other) {
  const PairLaw& law = m.laws[static_cast<std::size_t>(law_index)];
  Kind k;
  k.present = true;
  k.laws.push_back(law_name(m, law_index));
  const double mi = self.fm_min, ii = self.fi_min, vsi = self.fvs2_max;
  const bool wall = other == nullptr;
  const double mj = wall ? 0.0 : other->m_min, ij = wall ? 0.0 : other->i_min, vsj = wall ? 0.0 : other->vs2_max;
  if (law.kind == LawKind::linear) {
    // dashpots: the largest over the partner masses present (η grows with the masses)
    const double kn = law.linear.kn, ks = law.linear.ks;
    double en = 0.0, es = 0.0, hn = inf, hs = inf;
    const std::vector<double> partner_masses = wall ? std::vector<double>{0.0} : std::vector<double>{other->m_min, other->m_max};
    for (double a : {self.fm_min, self.fm_max})
      for (double b : partner_masses) {
        const Dashpots d = linear_dashpots(law, a, b);
        en = std::max(en, d.eta_n);
        es = std::max(es, d.eta_s);
        if (kn > 0.0) hn = std::min(hn, d.eta_n / kn);
        if (ks > 0.0) hs = std::min(hs, d.eta_s / ks);
      }
    // Gap springs (B2, B3) between two elements: in parallel with the contact's springs, and their shear
    // spring does not slide (it breaks), so it counts in the sliding bound too.
    const GapRates gap = wall ? GapRates{} : gap_spring_rates(law, self, *other);
    const double kn_t = kn + gap.kn, en_t = en + gap.eta_n;
    k.k.w = kn_t / mi;
    k.c.w = en_t / mi;
    if (!wall) {
      k.k.b = gap.ks * vsi + std::max(kn_t / std::sqrt(mi * mj), gap.ks * std::sqrt(vsi * vsj));
      k.c.b = gap.eta_s * vsi + std::max(en_t / std::sqrt(mi * mj), gap.eta_s * std::sqrt(vsi * vsj));
      hn = std::min(hn, gap.hopf);
    }
    k.hopf = hn;
    const double ks_t = ks + gap.ks, es_t = es + gap.eta_s;
    k.k_stick = {k.k.w, ks_t * vsi + (wall ? 0.0 : std::max(kn_t / std::sqrt(mi * mj), ks_t * std::sqrt(vsi * vsj)))};
    k.c_stick = {k.c.w, es_t * vsi + (wall ? 0.0 : std::max(en_t / std::sqrt(mi * mj), es_t * std::sqrt(vsi * vsj)))};
    k.hopf_stick = std::min(hn, hs);
    if (law.rolling.enabled) add_rolling(law, self, other, k);
    return k;
  }
  // face law: the constants depend on both radii and the reduced mass: take the largest of each
  const int n = law.face.segments;
  double kn = 0.0, ks = 0.0, en = 0.0, es = 0.0, a = 0.0, hopf = inf;
  for (double ri : {self.fr_min, self.fr_max}) {
    std::vector<double> rjs = wall ? std::vector<double>{0.0}
                                   : std::vector<double>{other->r_min, other->r_max, std::clamp(ri, other->r_min, other->r_max)};
    for (double rj : rjs)
      for (double ma : {self.fm_min, self.fm_max})
        for (double mb : wall ? std::vector<double>{0.0} : std::vector<double>{other->m_min, other->m_max}) {
          const double meff = wall ? ma : ma * mb / (ma + mb);
          const FaceConstants fc = face_constants(law, ri, rj, meff, m.thickness);
          kn = std::max(kn, fc.kn);
          ks = std::max(ks, fc.ks);
          en = std::max(en, fc.eta_n);
          es = std::max(es, fc.eta_s);
          a = std::max(a, fc.half_length);
          if (fc.kn > 0.0) hopf = std::min(hopf, fc.eta_n / fc.kn);
          if (fc.ks > 0.0) hopf = std::min(hopf, fc.eta_s / fc.ks);
        }
  }
  double lever2 = 0.0;  // Σ ξ² a²
  for (int s = 0; s < n; ++s) {
    const double l = a * segment_xi(law.face.positions, n, s);
    lever2 += l * l;
  }
  auto weights = [&](double kn_, double ks_) {
    Weights w;
    w.w = n * kn_ / mi;
    w.b = kn_ * lever2 / ii + n * ks_ * vsi;
    if (!wall) w.b += std::max(n * kn_ / std::sqrt(mi * mj), kn_ * lever2 / std::sqrt(ii * ij)) + n * ks_ * std::sqrt(vsi * vsj);
    return w;
  };
  k.k = k.k_stick = weights(kn, ks);
  k.c = k.c_stick = weights(en, es);
  k.hopf = k.hopf_stick = hopf;
  return k;
}

/// The sizes, masses and inertias of each material's active elements, and of its free ones.
std::vector<Stats> material_stats(const Elements& e, std::size_t nm) {
  std::vector<Stats> st(nm);
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i]) continue;
    Stats& s = st[static_cast<std::size_t>(e.material[i])];
    const double vs2 = e.inv_mass[i] + e.radius[i] * e.radius[i] * e.inv_inertia[i];
    ++s.count;
    s.r_min = std::min(s.r_min, e.radius[i]);
    s.r_max = std::max(s.r_max, e.radius[i]);
    s.m_min = std::min(s.m_min, e.mass[i]);
    s.m_max = std::max(s.m_max, e.mass[i]);
    s.i_min = std::min(s.i_min, e.inertia[i]);
    s.vs2_max = std::max(s.vs2_max, vs2);
    if (e.motion[i] != Motion::free) continue;
    ++s.free_count;
    s.fr_min = std::min(s.fr_min, e.radius[i]);
    s.fr_max = std::max(s.fr_max, e.radius[i]);
    if (e.mass[i] < s.fm_min || s.lightest < 0) s.lightest = static_cast<std::int64_t>(i);
    s.fm_min = std::min(s.fm_min, e.mass[i]);
    s.fm_max = std::max(s.fm_max, e.mass[i]);
    s.fi_min = std::min(s.fi_min, e.inertia[i]);
    s.fi_max = std::max(s.fi_max, e.inertia[i]);
    s.fvs2_max = std::max(s.fvs2_max, vs2);
  }
  return st;
}

/// (G7) How far element i may move for the guard: a free one `reach`, a fixed one 0, a driven one any distance.
double element_reach(const Elements& e, std::size_t i, double reach) {
  return e.motion[i] == Motion::free ? reach : e.motion[i] == Motion::fixed ? 0.0 : inf;
}

/// (G7) Per class pair (a, b), row a·nm + b: how many class-b elements a free class-a element may touch.
/// Without numerics.guard_reach every active one; with it R, those within reach of some free class-a
/// element: gap ≤ R_i + R_j, a free element moving at most R, a fixed one 0, a driven one any distance.
/// (The run evaluates the guard again when a free element moves farther than R: run.cpp.)
std::vector<int> partner_counts(const Model& m, const std::vector<Stats>& st, std::string& assumptions) {
  const std::size_t nm = st.size();
  const Elements& e = m.elements;
  std::vector<int> counts(nm * nm, 0);
  const double reach = m.numerics.guard_reach;
  if (!std::isfinite(reach)) {
    for (std::size_t a = 0; a < nm; ++a)
      for (std::size_t b = 0; b < nm; ++b) counts[a * nm + b] = st[b].count;
    return counts;
  }
  assumptions += fmt::format("; element partners only within reach, each free element moving at most numerics.guard_reach = "
                             "{:.4g} m, a fixed one not at all (G7; the run evaluates the guard again past it)", reach);
  auto own_reach = [&](std::size_t i) { return element_reach(e, i, reach); };
  std::vector<std::uint8_t> near(e.size() * nm, 0);  // element j may touch a free element of class a
  std::vector<std::size_t> order;
  double r_max = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i]) continue;
    r_max = std::max(r_max, e.radius[i]);
    if (e.motion[i] == Motion::driven) {  // within reach of everything
      for (std::size_t a = 0; a < nm; ++a) near[i * nm + a] = 1;
    } else {
      order.push_back(i);
    }
  }
  std::vector<std::uint8_t> free_class(nm, 0);  // classes with a free element
  for (std::size_t i : order) free_class[static_cast<std::size_t>(e.material[i])] |= e.motion[i] == Motion::free ? 1 : 0;
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return e.x[p] < e.x[q]; });
  for (std::size_t k = 0; k < order.size(); ++k)  // pairs within 2 r_max + 2R in x, sorted sweep
    for (std::size_t l = k + 1; l < order.size() && e.x[order[l]] - e.x[order[k]] <= 2.0 * (r_max + reach); ++l) {
      const std::size_t i = order[k], j = order[l];
      const double gap = std::hypot(e.x[j] - e.x[i], e.y[j] - e.y[i]) - e.radius[i] - e.radius[j];
      if (gap > own_reach(i) + own_reach(j)) continue;
      if (e.motion[i] == Motion::free) near[j * nm + static_cast<std::size_t>(e.material[i])] = 1;
      if (e.motion[j] == Motion::free) near[i * nm + static_cast<std::size_t>(e.material[j])] = 1;
    }
  for (std::size_t j = 0; j < e.size(); ++j)
    if (e.active[j])
      for (std::size_t a = 0; a < nm; ++a)
        if (near[j * nm + a] && free_class[a]) ++counts[a * nm + static_cast<std::size_t>(e.material[j])];
  // a class's own elements: an element is not its own partner (the union above may count it)
  for (std::size_t a = 0; a < nm; ++a) counts[a * nm + a] = std::min(counts[a * nm + a], st[a].count - 1) + 1;
  return counts;
}

/// The rates of the contacts that can still form (G4): the largest Gershgorin rates over the classes
/// that have free elements not bonded at the start.
struct ClassRates {
  double lam = 0.0, c = 0.0, hopf = inf, lam_s = 0.0, c_s = 0.0, hopf_s = inf;
  void add(double l, double cc, double h, double ls, double cs, double hs) {
    lam = std::max(lam, l), c = std::max(c, cc), hopf = std::min(hopf, h);
    lam_s = std::max(lam_s, ls), c_s = std::max(c_s, cs), hopf_s = std::min(hopf_s, hs);
  }
};

StartNetwork start_network_if_bonded(const Model& m) {
  bool face = false, bond = false;
  for (const PairLaw& law : m.laws) face = face || law.kind == LawKind::face, bond = bond || (law.kind == LawKind::face && law.bond_at_start);
  for (std::size_t i = 0; i < m.elements.size() && face && !bond; ++i) bond = m.elements.group[i] >= 0;
  return bond ? start_network(m) : StartNetwork{};
}

bool has_bonded_free(const Elements& e, const StartNetwork& net, std::size_t material) {
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i] && e.motion[i] == Motion::free && static_cast<std::size_t>(e.material[i]) == material && net.bonded[i])
      return true;
  return false;
}

int count_unbonded_free(const Elements& e, const StartNetwork& net, std::size_t material) {
  int n = 0;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i] && e.motion[i] == Motion::free && static_cast<std::size_t>(e.material[i]) == material && !net.bonded[i])
      ++n;
  return n;
}

/// A bonded structure: the limit from the eigenvalues of the start network (G3) plus the contacts that
/// can still form (G4); never above what the row sums allow by more than they are conservative.
void apply_eigen_bound(const Model& m, const StartNetwork& net, const ClassRates& u, StabilityBound& out) {
  const Integrator it = m.numerics.integrator;
  out.eigen = true;
  out.lambda_max = network_eigenvalue(net, false, false);
  out.c_max = network_eigenvalue(net, true, false);
  // both bounds are safe: the larger Δt of the two (a start contact is counted twice in the eigenvalue
  // bound when the row sums of its element's walls are added, as for one PRE resting on a wall)
  out.limit = std::max(out.limit_gershgorin, eigen_limit(net, it, false, u.lam, u.c, u.hopf));
  out.limit_start = eigen_limit(net, it, false, 0.0, 0.0, inf);
  out.limit_sticking = std::min(out.limit, std::max(out.limit_gershgorin_sticking, eigen_limit(net, it, true, u.lam_s, u.c_s, u.hopf_s)));
  out.assumptions += fmt::format(
      "; bonded structure: Δt from the largest eigenvalue of Δt²K + 2ΔtC (mass-normalised, {} DOF, {} springs of "
      "the contacts present at the start, Lanczos) plus the row-sum rates of the unbonded free elements' "
      "classes (λ = {:.4g} 1/s², c = {:.4g} 1/s); a bonded element is assumed to form no contact beyond "
      "its start neighbours (the row-sum limit without this: {:.6g} s)",
      net.dofs, net.springs.size(), u.lam, u.c, out.limit_gershgorin);
}

/// What (G5) needs of one element class, gathered by the row-sum loop.
struct BlockClass {
  int unbonded_free = 0;  // free elements not bonded at the start: each a block of its own
  bool bonded_free = false;
  int zd = 0;                          // the most element contacts one of its elements can have
  double limit = inf, limit_s = inf;   // its row-sum limits (the block of an unbonded element)
  ClassRates walls;                    // a bonded element's wall contacts and extra terms (G4)
  double xk = 0.0, xc = 0.0;           // the extra terms alone (base friction): every element has them
};

/// Per element (bonded free ones; the others get nothing): the rates it can add by the contacts it can
/// still form (G4, G5): its class's wall contacts and extra terms, and one contact with each partner it
/// can reach that is not a bonded free element (an unbonded free element, a fixed or a driven one: within
/// reach as G7 has it), at most its class's coordination of them, each counted as that contact's whole
/// row share w + b (the largest over the partners' classes).
std::vector<ClassRates> element_growth(const Model& m, const StartNetwork& net, const std::vector<Stats>& st,
                                       const std::vector<BlockClass>& info) {
  const std::size_t nm = m.materials.size();
  const Elements& e = m.elements;
  const double reach = m.numerics.guard_reach;
  auto own_reach = [&](std::size_t i) { return element_reach(e, i, reach); };
  std::vector<std::size_t> others;  // the partners that can still come: not bonded free elements
  for (std::size_t j = 0; j < e.size(); ++j)
    if (e.active[j] && !(e.motion[j] == Motion::free && net.bonded[j])) others.push_back(j);
  std::vector<Kind> kinds(nm * nm);  // contact_kind per (class of i, class of j), made when first needed
  std::vector<ClassRates> out(e.size());
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i] || e.motion[i] != Motion::free || !net.bonded[i]) continue;
    const auto a = static_cast<std::size_t>(e.material[i]);
    Kind touch;
    int n = 0;
    for (std::size_t j : others) {
      const auto b = static_cast<std::size_t>(e.material[j]);
      const std::int32_t law = m.law_of_pair[a * nm + b];
      if (law < 0) continue;
      const double gap = std::hypot(e.x[j] - e.x[i], e.y[j] - e.y[i]) - e.radius[i] - e.radius[j];
      if (gap <= 1e-9 * (e.radius[i] + e.radius[j])) continue;  // touching at the start: in the start network already
      if (std::isfinite(reach) && gap > own_reach(i) + own_reach(j)) continue;  // (G7)
      Kind& k = kinds[a * nm + b];
      if (!k.present) k = contact_kind(m, law, st[a], &st[b]);
      touch.merge(k);
      ++n;
    }
    const double c = std::min(info[a].zd, n);
    const ClassRates& w = info[a].walls;
    out[i].add(w.lam + c * (touch.k.w + touch.k.b), w.c + c * (touch.c.w + touch.c.b), std::min(w.hopf, touch.hopf),
               w.lam_s + c * (touch.k_stick.w + touch.k_stick.b), w.c_s + c * (touch.c_stick.w + touch.c_stick.b),
               std::min(w.hopf_s, touch.hopf_stick));
  }
  return out;
}

/// (G4) The new contacts' matrix has rows on both sides: to the unbonded classes' row sums `u` add the
/// largest row of a bonded element (its wall contacts and its contacts with the partners it can reach).
ClassRates with_bonded_growth(const std::vector<ClassRates>& grows, ClassRates u) {
  for (const ClassRates& g : grows) u.add(g.lam, g.c, g.hopf, g.lam_s, g.c_s, g.hopf_s);
  return u;
}

/// (G5) A block bound for a bonded structure with unbonded free elements (a load disk): the bonded
/// free elements form one block L, each unbonded free element u a block of its own. Feingold–Varga:
///   λ_max ≤ max( λ_max(A_LL) + Σ_u ‖A_Lu‖,  max_u [λ_max(A_uu) + Σ_j ‖A_uj‖] ).
/// The u rows are the row-sum bounds of u's class. A_LL is the start network with every other body
/// grounded (their springs act on L alone), plus, as a diagonal on each bonded element with angular room
/// (G6), the rates of the contacts it can still form (element_growth); ‖A_Lu‖ ≤ √(z_u)·b, as each bonded element touches u
/// at most once and u touches at most z_u of them (‖Σ_c B_c‖² ≤ Σ_c ‖B_c‖² for blocks on disjoint
/// rows). Unlike (G4)'s Weyl sum, the lattice's and the load disk's largest rates are not added.
void apply_block_bound(const Model& m, const StartNetwork& net, const std::vector<Stats>& st,
                       const std::vector<BlockClass>& info, const std::vector<ClassRates>& grows, StabilityBound& out) {
  const std::size_t nm = m.materials.size();
  int free_unbonded = 0, bonded_count = 0;
  double limit_u = inf, limit_u_s = inf;
  for (const BlockClass& c : info) {
    free_unbonded += c.unbonded_free;
    if (c.unbonded_free > 0) limit_u = std::min(limit_u, c.limit), limit_u_s = std::min(limit_u_s, c.limit_s);
  }
  for (std::size_t i = 0; i < net.bonded.size(); ++i) bonded_count += net.bonded[i] ? 1 : 0;
  if (free_unbonded == 0) return;  // (G4) is then the same bound
  ClassRates grown;     // the largest rates any bonded element can add to A_LL's row
  ClassRates coupling;  // Σ_u ‖A_Lu‖ (lam, c, lam_s, c_s; hopf unused)
  for (std::size_t u = 0; u < nm; ++u) {
    if (info[u].unbonded_free == 0) continue;
    double b[4] = {0, 0, 0, 0};
    for (std::size_t a = 0; a < nm; ++a) {
      const std::int32_t law = m.law_of_pair[u * nm + a];
      if (law < 0 || !info[a].bonded_free) continue;
      const Kind k = contact_kind(m, law, st[u], &st[a]);
      b[0] = std::max(b[0], k.k.b), b[1] = std::max(b[1], k.c.b), b[2] = std::max(b[2], k.k_stick.b), b[3] = std::max(b[3], k.c_stick.b);
    }
    const double z = std::sqrt(static_cast<double>(std::min(info[u].zd, bonded_count)));
    coupling.lam += info[u].unbonded_free * z * b[0], coupling.c += info[u].unbonded_free * z * b[1];
    coupling.lam_s += info[u].unbonded_free * z * b[2], coupling.c_s += info[u].unbonded_free * z * b[3];
  }
  for (const ClassRates& g : grows) grown.add(g.lam, g.c, g.hopf, g.lam_s, g.c_s, g.hopf_s);
  // (G6) the new contacts as a diagonal on the DOFs of the bonded elements with angular room for one; the
  // others keep only the extra terms (base friction)
  const Elements& e = m.elements;
  double new_radius = inf;  // the smallest element that can still come: not a bonded free one
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i] && !(e.motion[i] == Motion::free && net.bonded[i])) new_radius = std::min(new_radius, e.radius[i]);
  const std::vector<std::uint8_t> room = angular_room(m, new_radius);
  StartNetwork bonded = start_network(m, &net.bonded);
  for (auto* d : {&bonded.diag_k, &bonded.diag_c, &bonded.diag_k_stick, &bonded.diag_c_stick}) d->assign(static_cast<std::size_t>(bonded.dofs), 0.0);
  int with_room = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (bonded.dof[i] < 0) continue;
    const auto a = static_cast<std::size_t>(e.material[i]);
    const ClassRates& g = grows[i];
    const double v[4] = {room[i] ? g.lam : info[a].xk, room[i] ? g.c : info[a].xc, room[i] ? g.lam_s : info[a].xk, room[i] ? g.c_s : info[a].xc};
    with_room += room[i] ? 1 : 0;
    for (int k = 0; k < 3; ++k) {
      const auto d = static_cast<std::size_t>(bonded.dof[i] + k);
      bonded.diag_k[d] = v[0], bonded.diag_c[d] = v[1], bonded.diag_k_stick[d] = v[2], bonded.diag_c_stick[d] = v[3];
    }
  }
  const Integrator it = m.numerics.integrator;
  const double block = std::min(limit_u, eigen_limit(bonded, it, false, coupling.lam, coupling.c, grown.hopf));
  const double block_s = std::min(limit_u_s, eigen_limit(bonded, it, true, coupling.lam_s, coupling.c_s, grown.hopf_s));
  out.limit_block = block;
  out.limit = std::max(out.limit, block);
  out.limit_sticking = std::min(out.limit, std::max(out.limit_sticking, block_s));
  out.assumptions += fmt::format(
      "; block bound (G5): the bonded elements as one block ({} DOF, the other bodies grounded, Lanczos) and each of "
      "the {} unbonded free elements a block of its own (its row sums): {:.6g} s; the contacts the bonded "
      "elements can still form on the {} of them with angular room for one (G6), a diagonal term",
      bonded.dofs, free_unbonded, block, with_room);
}

/// A bonded structure's two sharper bounds, (G4) and (G5), with the contacts its elements can still form
/// (element_growth) computed once for both.
void apply_bonded_bounds(const Model& m, const StartNetwork& net, const std::vector<Stats>& st,
                         const std::vector<BlockClass>& info, const ClassRates& unbonded, StabilityBound& out) {
  const std::vector<ClassRates> grows = element_growth(m, net, st, info);
  apply_eigen_bound(m, net, with_bonded_growth(grows, unbonded), out);
  apply_block_bound(m, net, st, info, grows, out);
}

/// The rates the extra terms (base friction, …) add to the free elements of one class.
struct ExtraRates {
  double k = 0.0, c = 0.0, hopf = inf;
  std::string sources;
};
ExtraRates extra_rates(const Elements& e, const std::vector<StabilityTerm>& extra, std::size_t material) {
  ExtraRates x;
  for (const StabilityTerm& t : extra) {
    double tk = 0.0, tc = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      if (!e.active[i] || e.motion[i] != Motion::free || static_cast<std::size_t>(e.material[i]) != material) continue;
      if (i < t.stiffness.size()) tk = std::max(tk, t.stiffness[i]);
      if (i < t.damping.size()) tc = std::max(tc, t.damping[i]);
    }
    if (tk > 0.0 || tc > 0.0) x.sources += (x.sources.empty() ? "" : ", ") + t.source;
    x.k += tk;
    x.c += tc;
    if (tk > 0.0) x.hopf = std::min(x.hopf, t.hopf_ratio);
  }
  return x;
}

}  // namespace

/// The bound of a model of disks and PREs (a model with polygons: polygon_stability.cpp).
static StabilityBound disk_and_pre_bound(const Model& m, const std::vector<StabilityTerm>& extra) {
  const Elements& e = m.elements;
  const std::size_t nm = m.materials.size();
  const std::vector<Stats> st = material_stats(e, nm);
  StabilityBound out;
  out.limit = out.limit_sticking = inf;
  out.assumptions = fmt::format(
      "every contact the case can form: equal-size neighbours at most 6 per element (fewer if the case has "
      "fewer elements; 2 asin((1-e)rho/(r+rho)) apart, overlaps e <= {:.0f} % of a radius), a segment wall's "
      "contact blocks the half-plane behind it, a point wall nothing, walls that lie within 2r of each other "
      "may all touch at once; "
      "worst directions on a 0.5 deg grid (each grid point taking the largest value within a quarter degree); "
      "block-Gershgorin bound, exact for one contact; shear springs of Coulomb contacts counted only in the sticking limit",
      100 * kOverlap);
  out.assumptions += option_assumptions(m);
  bool first = true;
  const StartNetwork net = start_network_if_bonded(m);
  ClassRates unbonded;  // the Gershgorin rates of the classes with free elements not bonded at the start
  std::vector<BlockClass> info(nm);  // for the block bound (G5)
  const std::vector<int> reachable = partner_counts(m, st, out.assumptions);  // (G7)
  for (std::size_t a = 0; a < nm; ++a) {
    const Stats& s = st[a];
    if (s.free_count == 0) continue;
    Kind elem;  // element partners
    std::vector<std::pair<Kind, int>> by_class;  // per partner class: its contact kind, how many partners
    double rho_min = inf;
    int partners = 0;
    for (std::size_t b = 0; b < nm; ++b) {
      const std::int32_t law = m.law_of_pair[a * nm + b];
      const int others = reachable[a * nm + b] - (a == b ? 1 : 0);
      if (law < 0 || others <= 0) continue;
      by_class.emplace_back(contact_kind(m, law, s, &st[b]), others);
      elem.merge(by_class.back().first);
      rho_min = std::min(rho_min, st[b].r_min);
      partners += others;
    }
    // wall partners
    Kind seg, pt;
    std::vector<const Wall*> walls;
    int n_seg = 0, n_pt = 0;
    for (const Wall& w : m.walls) {
      const std::int32_t law = m.law_of_pair[a * nm + static_cast<std::size_t>(w.material)];
      if (law < 0 || w.open) continue;
      walls.push_back(&w);
      (w.kind == WallKind::segment ? seg : pt).merge(contact_kind(m, law, s, nullptr));
      ++(w.kind == WallKind::segment ? n_seg : n_pt);
    }
    // Moving walls may come closer than they start: then every wall counts.
    bool moving = false;
    for (const Wall* w : walls) moving = moving || w->drive >= 0;
    const std::vector<std::pair<int, int>> sets =
        moving ? std::vector<std::pair<int, int>>{{n_seg, n_pt}} : wall_sets(walls, 2.0 * s.fr_max * (1.0 + 1e-9));
    const double r = s.fr_max;
    int zd = 0;
    double gap_dd = 0.0, gap_sd = 0.0;
    if (partners > 0) {
      gap_dd = 2.0 * std::asin((1.0 - kOverlap) * rho_min / (r + rho_min));
      gap_sd = std::acos(std::clamp((r - (1.0 - kOverlap) * rho_min) / (r + rho_min), -1.0, 1.0));
      zd = std::min(partners, static_cast<int>(std::floor(2.0 * std::numbers::pi / gap_dd + 1e-9)));
      zd = std::min(zd, 12);
    }
    auto finite = [](const Kind& k) {
      for (const Weights* w : {&k.k, &k.c, &k.k_stick, &k.c_stick})
        if (!std::isfinite(w->w) || !std::isfinite(w->b)) return false;
      return !std::isnan(k.hopf) && !std::isnan(k.hopf_stick);
    };
    if (!finite(elem) || !finite(seg) || !finite(pt)) {
      out.limit = out.limit_sticking = std::numeric_limits<double>::quiet_NaN();
      out.element = s.lightest;
      out.law = "a stiffness, dashpot, mass or inertia that is not a finite number";
      return out;
    }
    int max_seg = 0, max_pt = 0;
    for (const auto& [ws, wp] : sets) max_seg = std::max(max_seg, ws), max_pt = std::max(max_pt, wp);
    const int counts[3] = {zd, max_seg, max_pt};
    const double gaps[3][3] = {{gap_dd, gap_sd, 0.0}, {gap_sd, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    auto run = [&](Weights Kind::*field) {
      const Weights w[3] = {elem.*field, seg.*field, pt.*field};
      const Arrangement merged = arrangement_max(w, counts, sets, gaps);
      const Arrangement split = split_by_partner(by_class, field, seg.*field, pt.*field, counts, sets, gaps);
      return split.value < merged.value ? split : merged;
    };
    // the sticking weights equal the slipping ones when no Coulomb shear spring is involved (face
    // laws, K_s = 0): the arrangement search is then not repeated
    auto same = [&](Weights Kind::*a, Weights Kind::*b) {
      std::vector<const Kind*> kinds{&elem, &seg, &pt};
      for (const auto& [k, n] : by_class) kinds.push_back(&k);
      for (const Kind* k : kinds)
        if ((k->*a).w != (k->*b).w || (k->*a).b != (k->*b).b) return false;
      return true;
    };
    const Arrangement ak = run(&Kind::k), ac = run(&Kind::c);
    const Arrangement aks = same(&Kind::k, &Kind::k_stick) ? ak : run(&Kind::k_stick);
    const Arrangement acs = same(&Kind::c, &Kind::c_stick) ? ac : run(&Kind::c_stick);
    const ExtraRates x = extra_rates(e, extra, a);
    const double xk = x.k, xc = x.c, xhopf = x.hopf;
    const double hopf = std::min({elem.present ? elem.hopf : inf, seg.present ? seg.hopf : inf, pt.present ? pt.hopf : inf, xhopf});
    const double hopf_s = std::min({elem.present ? elem.hopf_stick : inf, seg.present ? seg.hopf_stick : inf,
                                    pt.present ? pt.hopf_stick : inf, xhopf});
    const double lam = ak.value + xk, c = ac.value + xc;
    const double limit = stable_dt_rates(m.numerics.integrator, lam, c, hopf);
    const double limit_s = stable_dt_rates(m.numerics.integrator, aks.value + xk, acs.value + xc, hopf_s);
    if (std::isnan(limit) || std::isnan(limit_s)) {
      out.limit = out.limit_sticking = std::numeric_limits<double>::quiet_NaN();
      out.element = s.lightest;
      out.law = "a non-finite stiffness, damping or mass";
      return out;
    }
    info[a].zd = zd;
    if (const int unbonded_free = net.any_bond ? count_unbonded_free(e, net, a) : 0; unbonded_free > 0) {
      unbonded.add(lam, c, hopf, aks.value + xk, acs.value + xc, hopf_s);
      info[a].unbonded_free = unbonded_free;
      info[a].limit = limit, info[a].limit_s = limit_s;
    }
    if (net.any_bond && has_bonded_free(e, net, a)) {
      // bonded elements: the wall contacts they can still form and the extra terms (base friction), (G4)
      const int wall_counts[3] = {0, max_seg, max_pt};
      auto walls_only = [&](Weights Kind::*field) {
        const Weights w[3] = {elem.*field, seg.*field, pt.*field};
        return arrangement_max(w, wall_counts, sets, gaps).value;
      };
      info[a].bonded_free = true;
      info[a].xk = xk, info[a].xc = xc;
      info[a].walls.add(walls_only(&Kind::k) + xk, walls_only(&Kind::c) + xc, hopf, walls_only(&Kind::k_stick) + xk,
                        walls_only(&Kind::c_stick) + xc, hopf_s);
    }
    out.limit_sticking = std::min(out.limit_sticking, limit_s);
    if (first || limit < out.limit) {
      first = false;
      out.limit = limit;
      out.element = s.lightest;
      std::vector<std::string> laws;
      if (ak.d > 0) laws = elem.laws;
      if (ak.s > 0) laws.insert(laws.end(), seg.laws.begin(), seg.laws.end());
      if (ak.p > 0) laws.insert(laws.end(), pt.laws.begin(), pt.laws.end());
      std::sort(laws.begin(), laws.end());
      laws.erase(std::unique(laws.begin(), laws.end()), laws.end());
      out.law = fmt::format("{}", fmt::join(laws, ", "));
      if (!x.sources.empty()) out.law += (out.law.empty() ? "" : " + ") + x.sources;
      out.element_contacts = ak.d;
      out.wall_contacts = ak.s + ak.p;
      out.stiffness_rate = lam;
      out.damping_rate = c;
    }
  }
  out.limit_gershgorin = out.limit, out.limit_gershgorin_sticking = out.limit_sticking;
  if (net.any_bond) apply_bonded_bounds(m, net, st, info, unbonded, out);
  return out;
}

StabilityBound assembly_stability_bound(const Model& m, const std::vector<StabilityTerm>& extra) {
  const std::vector<Shape>& shape = m.elements.shape;
  if (std::find(shape.begin(), shape.end(), Shape::polygon) != shape.end()) return polygon_stability_bound(m, extra);
  return disk_and_pre_bound(m, extra);
}

}  // namespace dem
