#include "dem/core/simulation.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "dem/core/stability.hpp"

namespace dem {

namespace {

inline std::uint64_t key(std::uint32_t i, std::uint32_t j) { return (std::uint64_t{i} << 32) | j; }

/// Merges the old (sorted) slots into the new (sorted) candidate keys: a candidate keeps its old
/// history if it had one; an old slot that must outlive the rebuild is kept even without candidate.
template <class Slot, class Candidates>
void merge(std::vector<Slot>& slots, std::vector<Slot>& scratch, const Candidates& cand) {
  scratch.clear();
  std::size_t o = 0;
  for (const Slot& c : cand) {
    const std::uint64_t kc = key(c.i, c.j);
    while (o < slots.size() && key(slots[o].i, slots[o].j) < kc) {
      if (must_keep(slots[o])) scratch.push_back(slots[o]);
      ++o;
    }
    if (o < slots.size() && key(slots[o].i, slots[o].j) == kc) {
      scratch.push_back(slots[o++]);
    } else {
      scratch.push_back(c);
    }
  }
  for (; o < slots.size(); ++o)
    if (must_keep(slots[o])) scratch.push_back(slots[o]);
  slots.swap(scratch);
}

/// Ends a contact: the slot stays (it is a candidate pair) but forgets its history.
template <class Slot>
void reset_slot(Slot& s) {
  Slot fresh;
  fresh.i = s.i;
  fresh.j = s.j;
  fresh.law = s.law;
  s = fresh;
}

inline double reduced_mass(double a, double b) { return a * b / (a + b); }

// Element loops of the hot path as functions of restrict-qualified parameters, so that the compiler
// vectorises them (it does not trust restrict on local pointers). Every lane performs the scalar code's
// operations in the same order, and nothing is contracted into FMAs: results are bit-identical.

/// One degree of freedom of free elements: v += (h f) w (K17, w = 1/m or 1/I), then the increment
/// d = v Δt (K18) or d = (d + v Δt)/2 (K19), then x += d.
template <bool K19>
void integrate_free(double* __restrict v, const double* __restrict f, const double* __restrict w,
                    double* __restrict d, double* __restrict x, double h, double dt, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    v[i] += h * f[i] * w[i];
    d[i] = K19 ? 0.5 * (d[i] + v[i] * dt) : v[i] * dt;
    x[i] += d[i];
  }
}
/// Whether an element moved by at least √limit2 from its reference position: d² − limit2 ≥ 0 has a clear
/// sign bit (an AND of the bit patterns, which the compiler vectorises; a comparison it does not).
bool any_displaced(const double* __restrict x, const double* __restrict y, const double* __restrict xr,
                   const double* __restrict yr, double limit2, std::size_t n) {
  std::uint64_t all_negative = ~std::uint64_t{0};
  for (std::size_t i = 0; i < n; ++i) {
    const double ddx = x[i] - xr[i], ddy = y[i] - yr[i];
    all_negative &= std::bit_cast<std::uint64_t>(ddx * ddx + ddy * ddy - limit2);
  }
  return (all_negative >> 63) == 0;
}
/// f = m g (K15).
void weight(double* __restrict f, const double* __restrict m, double g, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) f[i] = m[i] * g;
}

}  // namespace

Simulation::Simulation(Model model) : m_(std::move(model)) {
  const Elements& e = m_.elements;
  if (m_.numerics.dt <= 0.0) throw std::invalid_argument("numerics.dt must be positive");
  double rmin = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < e.size(); ++i) rmin = std::min(rmin, e.radius[i]);
  skin_ = m_.numerics.skin > 0.0 ? m_.numerics.skin : (e.size() ? 0.25 * rmin : 0.0);
  // Initial increments (docs/references.md §1.4, "plain" start): Δx_0 = v(0)Δt.
  Elements& w = m_.elements;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w.motion[i] == Motion::fixed) {
      w.vx[i] = w.vy[i] = w.omega[i] = 0.0;
    } else if (w.motion[i] == Motion::driven) {
      const Vec2 v = m_.drives[static_cast<std::size_t>(w.drive[i])].at(0.0);
      w.vx[i] = v.x;
      w.vy[i] = v.y;
      w.omega[i] = 0.0;
    }
    w.dx[i] = w.vx[i] * m_.numerics.dt;
    w.dy[i] = w.vy[i] * m_.numerics.dt;
    w.dphi[i] = w.omega[i] * m_.numerics.dt;
  }
  for (Wall& wl : m_.walls)
    wl.increment = wl.drive >= 0 ? m_.drives[static_cast<std::size_t>(wl.drive)].at(0.0) * m_.numerics.dt
                                 : Vec2{};
  rebuild();
  if (!m_.preloads.empty()) apply_preloads();
}

void Simulation::apply_preloads() {
  Elements& e = m_.elements;
  // The preload is the increment of a static zeroth step: contacts are formed and loaded by it with
  // 1/Δt = 0 (no dashpot forces); nothing is integrated. The increments of step 0 are then restored.
  std::vector<double> keep_dx = e.dx, keep_dy = e.dy, keep_dphi = e.dphi;
  std::fill(e.dx.begin(), e.dx.end(), 0.0);
  std::fill(e.dy.begin(), e.dy.end(), 0.0);
  std::fill(e.dphi.begin(), e.dphi.end(), 0.0);
  for (const Preload& p : m_.preloads) {
    const std::size_t i = p.element;
    const Vec2 c{e.x[i], e.y[i]}, d = c - p.about;
    const double cs = std::cos(p.rotation), sn = std::sin(p.rotation);
    const Vec2 moved = p.about + Vec2{cs * d.x - sn * d.y, sn * d.x + cs * d.y};
    e.dx[i] = moved.x - c.x;
    e.dy[i] = moved.y - c.y;
    e.dphi[i] = p.rotation;
    e.x[i] = moved.x;
    e.y[i] = moved.y;
    e.phi[i] += p.rotation;
  }
  for (Wall& w : m_.walls) w.force = {};
  std::vector<Vec2> wall_inc;
  for (Wall& w : m_.walls) {
    wall_inc.push_back(w.increment);
    w.increment = {};
  }
  preloading_ = true;
  sweep_linear_pairs(0.0);
  sweep_face_pairs(0.0);
  sweep_linear_walls(0.0);
  sweep_face_walls(0.0);
  preloading_ = false;
  for (std::size_t k = 0; k < m_.walls.size(); ++k) m_.walls[k].increment = wall_inc[k];
  e.dx = keep_dx;
  e.dy = keep_dy;
  e.dphi = keep_dphi;
  rebuild();
}

bool Simulation::needs_rebuild() const {
  // Rebuild once an element may have moved half the skin since the last rebuild, or its displacement
  // plus the walls' reaches the skin: d ≥ min(skin/2, skin − max_w). Compared on squared displacements
  // (no square root, a loop the compiler vectorises), with a 1e-12 relative margin so that the test never
  // fires later than the exact one. When a rebuild happens does not change results: every touching pair
  // is a candidate either way, and a candidate that does not touch contributes nothing.
  double max_w = 0.0;
  for (std::size_t k = 0; k < m_.walls.size(); ++k) {
    max_w = std::max(max_w, norm(m_.walls[k].a - wall_ref_[k]));
  }
  const double limit = std::min(0.5 * skin_, skin_ - max_w);
  if (!(limit > 0.0)) return true;
  const double limit2 = limit * limit * (1.0 - 1e-12);
  const Elements& e = m_.elements;
  return any_displaced(e.x.data(), e.y.data(), x_ref_.data(), y_ref_.data(), limit2, e.size());
}

void Simulation::rebuild() {
  ++rebuilds_;
  const Elements& e = m_.elements;
  search_.build(e, skin_, candidates_);
  // Fresh slots for every candidate, routed by the pair's law.
  std::vector<LinearSlot>& lin = linear_fresh_;  // fresh slots for the candidates, routed by law
  std::vector<FaceSlot>& face = face_fresh_;
  lin.clear();
  face.clear();
  for (const CandidatePair& p : candidates_) {
    const std::int32_t law = m_.law_index(e.material[p.i], e.material[p.j]);
    if (law < 0) continue;
    if (m_.laws[static_cast<std::size_t>(law)].kind == LawKind::linear) {
      LinearSlot s;
      s.i = p.i, s.j = p.j, s.law = law;
      lin.push_back(s);
    } else {
      FaceSlot s;
      s.i = p.i, s.j = p.j, s.law = law;
      face.push_back(s);
    }
  }
  merge(linear_pairs_, linear_scratch_, lin);
  merge(face_pairs_, face_scratch_, face);
  // Element–wall candidates.
  lin.clear();
  face.clear();
  for (std::uint32_t i = 0; i < e.size(); ++i) {
    if (!e.active[i]) continue;
    const Vec2 c{e.x[i], e.y[i]};
    for (std::uint32_t k = 0; k < m_.walls.size(); ++k) {
      const Wall& w = m_.walls[k];
      if (w.open) continue;
      const double cut = e.radius[i] + skin_;
      const Vec2 d = closest_point(w, c) - c;
      if (dot(d, d) >= cut * cut) continue;
      const std::int32_t law = m_.law_index(e.material[i], w.material);
      if (law < 0) continue;
      if (m_.laws[static_cast<std::size_t>(law)].kind == LawKind::linear) {
        LinearSlot s;
        s.i = i, s.j = k, s.law = law;
        lin.push_back(s);
      } else {
        FaceSlot s;
        s.i = i, s.j = k, s.law = law;
        face.push_back(s);
      }
    }
  }
  merge(linear_walls_, linear_scratch_, lin);
  merge(face_walls_, face_scratch_, face);
  x_ref_ = e.x;
  y_ref_ = e.y;
  wall_ref_.resize(m_.walls.size());
  for (std::size_t k = 0; k < m_.walls.size(); ++k) wall_ref_[k] = m_.walls[k].a;
}

Dashpots linear_dashpots(const PairLaw& law, double mass_i, double mass_j) {
  Dashpots d;
  if (law.damping_from_ratio) {
    // (K20, K25): η_n = 2ζ√(m K_n), η_s = η_n √(K_s/K_n); m per the mass basis.
    double m = 0.0;
    if (mass_j <= 0.0) m = mass_i;  // wall
    else m = law.mass_basis == MassBasis::reduced ? reduced_mass(mass_i, mass_j) : 0.5 * (mass_i + mass_j);
    d.eta_n = 2.0 * law.damping_ratio * std::sqrt(m * law.linear.kn);
    d.eta_s = law.linear.kn > 0.0 ? d.eta_n * std::sqrt(law.linear.ks / law.linear.kn) : 0.0;
  } else {
    d.eta_n = law.eta_n;
    d.eta_s = law.eta_s;
  }
  return d;
}

void Simulation::start_linear(LinearSlot& s, double overlap, double du_n, double du_s, double mass_i,
                              double mass_j) const {
  const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
  s.touching = 1;
  s.h = {};
  const Dashpots d = linear_dashpots(law, mass_i, mass_j);
  s.eta_n = d.eta_n;
  s.eta_s = d.eta_s;
  // Contacts present at the start, or formed with the overlap onset, start from the geometric
  // overlap: e_n = K_n δ after this step's increment is added (docs/references.md §1.4: e_0 = K x(0)).
  if (step_ == 0 || law.onset == Onset::overlap) {
    s.h.en = law.linear.kn * (overlap - du_n);  // the face law's start, operation for operation (M18)
    // The first increment of a plain start is the virtual v(0)Δt (docs/references.md §1.4): it drives the
    // dashpots, not the shear spring. A static preload is a real deformation: it loads the spring.
    s.h.es = preloading_ ? 0.0 : -law.linear.ks * du_s;
  }
}

void Simulation::sweep_linear_pairs(double inv_dt) {
  Elements& e = m_.elements;
  const double* const x = e.x.data();
  const double* const y = e.y.data();
  const double* const radius = e.radius.data();
  const std::uint8_t* const active = e.active.data();
  const double* const dx = e.dx.data();
  const double* const dy = e.dy.data();
  const double* const dphi = e.dphi.data();
  double* const fx_e = e.fx.data();
  double* const fy_e = e.fy.data();
  double* const moment = e.moment.data();
  const PairLaw* const laws = m_.laws.data();
  for (LinearSlot& s : linear_pairs_) {
    const std::uint32_t i = s.i, j = s.j;
    const double ddx = x[j] - x[i], ddy = y[j] - y[i];
    const double rs = radius[i] + radius[j];
    const double r2 = ddx * ddx + ddy * ddy;
    if (r2 > rs * rs || !active[i] || !active[j]) {  // (K3): not touching
      if (s.touching) reset_slot(s);
      continue;
    }
    const double dist = std::sqrt(r2);
    const double nx = ddx / dist, ny = ddy / dist;  // cos α, sin α (K3): from i towards j
    const double ux = dx[i] - dx[j], uy = dy[i] - dy[j];
    const double du_n = ux * nx + uy * ny;                                      // (K5)
    const double du_s = -ux * ny + uy * nx + radius[i] * dphi[i] + radius[j] * dphi[j];
    if (!s.touching) start_linear(s, rs - dist, du_n, du_s, e.mass[i], e.mass[j]);
    const PairLaw& law = laws[static_cast<std::size_t>(s.law)];
    const ContactForce f = linear_contact_force(law.linear, s.eta_n, s.eta_s, du_n, du_s, inv_dt, s.h);
    if (f.opened) {  // (K8): the contact ends; if the cores still overlap it forms anew next step
      reset_slot(s);
      continue;
    }
    s.f = f;
    s.nx = nx;
    s.ny = ny;
    // (K15): force on i is −f_n n − f_s t, t = (−sin α, cos α); on j the opposite.
    const double fx = -f.fn * nx + f.fs * ny, fy = -f.fn * ny - f.fs * nx;
    fx_e[i] += fx;
    fy_e[i] += fy;
    fx_e[j] -= fx;
    fy_e[j] -= fy;
    moment[i] -= radius[i] * f.fs;
    moment[j] -= radius[j] * f.fs;
  }
}

void Simulation::open_wall(std::uint32_t w) {
  m_.walls[w].open = true;
  std::erase_if(linear_walls_, [w](const LinearSlot& s) { return s.j == w; });
  std::erase_if(face_walls_, [w](const FaceSlot& s) { return s.j == w; });
}

void Simulation::sweep_linear_walls(double inv_dt) {
  Elements& e = m_.elements;
  for (LinearSlot& s : linear_walls_) {
    const std::uint32_t i = s.i;
    Wall& w = m_.walls[s.j];
    const Vec2 c{e.x[i], e.y[i]};
    const Vec2 d = closest_point(w, c) - c;
    const double r2 = dot(d, d), r = e.radius[i];
    if (r2 > r * r || !e.active[i] || r2 == 0.0) {
      if (s.touching) reset_slot(s);
      continue;
    }
    const double dist = std::sqrt(r2);
    const double nx = d.x / dist, ny = d.y / dist;  // from the element towards the wall
    const double ux = e.dx[i] - w.increment.x, uy = e.dy[i] - w.increment.y;
    const double du_n = ux * nx + uy * ny;  // (K5) with the wall as element j, r_j = 0
    const double du_s = -ux * ny + uy * nx + r * e.dphi[i];
    if (!s.touching) start_linear(s, r - dist, du_n, du_s, e.mass[i], 0.0);
    const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
    const ContactForce f = linear_contact_force(law.linear, s.eta_n, s.eta_s, du_n, du_s, inv_dt, s.h);
    if (f.opened) {
      reset_slot(s);
      continue;
    }
    s.f = f;
    s.nx = nx;
    s.ny = ny;
    const double fx = -f.fn * nx + f.fs * ny, fy = -f.fn * ny - f.fs * nx;
    e.fx[i] += fx;
    e.fy[i] += fy;
    e.moment[i] -= r * f.fs;
    w.force.x -= fx;
    w.force.y -= fy;
  }
}

FaceConstants face_constants(const PairLaw& law, double r_i, double r_j, double m_eff, double thickness) {
  FaceConstants c;
  const int n = law.face.segments;
  c.half_length = r_j > 0.0 ? std::min(r_i, r_j) : r_i;
  const double area = 2.0 * c.half_length * thickness;  // (M1): A = 2 r l
  c.segment_area = area / n;
  if (law.face_modulus) {  // (M6): K = k A / ((r1 + r2) N); for a wall (r1 + r2) → r2 (M19)
    c.kn = law.face_kn * area / ((r_i + r_j) * n);
    c.ks = law.face_ks * area / ((r_i + r_j) * n);
  } else {
    c.kn = law.face_kn;
    c.ks = law.face_ks;
  }
  if (law.damping_from_ratio) {
    c.eta_n = 2.0 * law.damping_ratio * std::sqrt(c.kn * n * m_eff) / n;  // (M7.3)
    c.eta_s = c.kn > 0.0 ? c.eta_n * std::sqrt(c.ks / c.kn) : 0.0;         // (M7.4)
  } else {
    c.eta_n = law.eta_n;
    c.eta_s = law.eta_s;
  }
  return c;
}

void Simulation::sweep_face_pairs(double inv_dt) {
  Elements& e = m_.elements;
  for (FaceSlot& s : face_pairs_) {
    const std::uint32_t i = s.i, j = s.j;
    if (!e.active[i] || !e.active[j]) {
      if (s.touching) reset_slot(s);
      continue;
    }
    const double ddx = e.x[j] - e.x[i], ddy = e.y[j] - e.y[i];
    const double rs = e.radius[i] + e.radius[j];
    const double r2 = ddx * ddx + ddy * ddy;
    const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
    // Faces bonded at the start touch by construction (a generated lattice): accept them up to
    // round-off of the generated positions.
    const bool bond = step_ == 0 && (law.bond_at_start || (e.group[i] >= 0 && e.group[i] == e.group[j]));
    const double touch = bond ? rs * (1.0 + 1e-9) : rs;
    if (!s.touching && r2 > touch * touch) continue;  // not touching → touching when D ≤ r1 + r2
    const double dist = std::sqrt(r2);
    const double nx = ddx / dist, ny = ddy / dist;
    const double ux = e.dx[i] - e.dx[j], uy = e.dy[i] - e.dy[j];
    FaceKinematics k;
    k.du_projected = ux * nx + uy * ny;
    k.dv_translation = -ux * ny + uy * nx;
    const double ox = ddx - (e.dx[j] - e.dx[i]), oy = ddy - (e.dy[j] - e.dy[i]);  // centre line before the step
    k.du_exact = std::hypot(ox, oy) - dist;
    k.dbeta = std::atan2(ox * ddy - oy * ddx, ox * ddx + oy * ddy);
    k.dphi1 = e.dphi[i];
    k.dphi2 = e.dphi[j];
    k.r1 = e.radius[i];
    k.r2 = e.radius[j];
    if (!s.touching) {
      s.touching = 1;
      s.c = face_constants(law, e.radius[i], e.radius[j], reduced_mass(e.mass[i], e.mass[j]), m_.thickness);
      const bool bonded = bond;
      const bool geometric = step_ == 0 || law.onset == Onset::overlap;
      const double u0 = geometric ? (rs - dist) - k.du_projected : 0.0;
      start_face(law.face, s.c, u0, bonded, geometric, s.h);
      if (preloading_) s.h.geometric_start = 0;  // a static preload loads the shear springs
    }
    const FaceForce f = face_contact_force(law.face, s.c, k, inv_dt, s.h);
    s.f = f;
    s.nx = nx;
    s.ny = ny;
    if (f.links == 0) s.touching = 0;  // touching → not touching when no link remains
    const double fx = -f.p * nx + f.q * ny, fy = -f.p * ny - f.q * nx;  // (M12)
    e.fx[i] += fx;
    e.fy[i] += fy;
    e.fx[j] -= fx;
    e.fy[j] -= fy;
    e.moment[i] += -e.radius[i] * f.q + f.p_moment;
    e.moment[j] += -e.radius[j] * f.q - f.p_moment;
  }
}

void Simulation::sweep_face_walls(double inv_dt) {
  Elements& e = m_.elements;
  for (FaceSlot& s : face_walls_) {
    const std::uint32_t i = s.i;
    Wall& w = m_.walls[s.j];
    if (!e.active[i]) {
      if (s.touching) reset_slot(s);
      continue;
    }
    const Vec2 c{e.x[i], e.y[i]};
    const Vec2 d = closest_point(w, c) - c;
    const double r2 = dot(d, d), r = e.radius[i];
    const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
    const double touch = (step_ == 0 && law.bond_at_start) ? r * (1.0 + 1e-9) : r;
    if ((!s.touching && r2 > touch * touch) || r2 == 0.0) continue;
    const double dist = std::sqrt(r2);
    const double nx = d.x / dist, ny = d.y / dist;
    const double ux = e.dx[i] - w.increment.x, uy = e.dy[i] - w.increment.y;
    FaceKinematics k;  // (M19): the wall replaces one element; its frame does not turn
    k.du_projected = ux * nx + uy * ny;
    k.du_exact = k.du_projected;
    k.dv_translation = -ux * ny + uy * nx;
    k.dv_frame = k.dv_translation;
    k.dphi1 = e.dphi[i];
    k.r1 = r;
    if (!s.touching) {
      s.touching = 1;
      s.c = face_constants(law, r, 0.0, e.mass[i], m_.thickness);
      const bool geometric = step_ == 0 || law.onset == Onset::overlap;
      const double u0 = geometric ? (r - dist) - k.du_projected : 0.0;
      start_face(law.face, s.c, u0, step_ == 0 && law.bond_at_start, geometric, s.h);
      if (preloading_) s.h.geometric_start = 0;
    }
    const FaceForce f = face_contact_force(law.face, s.c, k, inv_dt, s.h);
    s.f = f;
    s.nx = nx;
    s.ny = ny;
    if (f.links == 0) s.touching = 0;
    const double fx = -f.p * nx + f.q * ny, fy = -f.p * ny - f.q * nx;
    e.fx[i] += fx;
    e.fy[i] += fy;
    e.moment[i] += -r * f.q + f.p_moment;
    w.force.x -= fx;
    w.force.y -= fy;
  }
}

void Simulation::integrate() {
  Elements& e = m_.elements;
  const double dt = m_.numerics.dt;
  // docs/references.md §1.4: a staggered start takes half a velocity step first, v_0 = v(Δt/2).
  const double dt_v = (step_ == 0 && m_.numerics.velocity_start == VelocityStart::staggered) ? 0.5 * dt : dt;
  const bool k19 = m_.numerics.integrator == Integrator::k19;
  const std::size_t n = e.size();
  // The usual case, every element active and free: the same operations per element, in branch-free
  // loops that the compiler vectorises (the lanes round exactly as the scalar code; no FMA contraction).
  std::uint8_t all_free = 1;
  {
    const std::uint8_t* __restrict act = e.active.data();
    const Motion* __restrict mot = e.motion.data();
    for (std::size_t i = 0; i < n; ++i) all_free &= (act[i] != 0) & (mot[i] == Motion::free);
  }
  if (all_free) {
    auto dof = k19 ? integrate_free<true> : integrate_free<false>;
    dof(e.vx.data(), e.fx.data(), e.inv_mass.data(), e.dx.data(), e.x.data(), dt_v, dt, n);
    dof(e.vy.data(), e.fy.data(), e.inv_mass.data(), e.dy.data(), e.y.data(), dt_v, dt, n);
    dof(e.omega.data(), e.moment.data(), e.inv_inertia.data(), e.dphi.data(), e.phi.data(), dt_v, dt, n);
  }
  for (std::size_t i = 0; i < n && !all_free; ++i) {
    if (!e.active[i]) continue;
    switch (e.motion[i]) {
      case Motion::free:  // (K17): v_t = v_{t−Δt} + a_t Δt
        e.vx[i] += dt_v * e.fx[i] * e.inv_mass[i];
        e.vy[i] += dt_v * e.fy[i] * e.inv_mass[i];
        e.omega[i] += dt_v * e.moment[i] * e.inv_inertia[i];
        break;
      case Motion::fixed:
        e.vx[i] = e.vy[i] = e.omega[i] = 0.0;
        break;
      case Motion::driven: {
        const Vec2 v = m_.drives[static_cast<std::size_t>(e.drive[i])].at(time_ + 0.5 * dt);
        e.vx[i] = v.x;
        e.vy[i] = v.y;
        e.omega[i] = 0.0;
        break;
      }
    }
    if (k19 && e.motion[i] == Motion::free) {  // (K19): averaged increment
      e.dx[i] = 0.5 * (e.dx[i] + e.vx[i] * dt);
      e.dy[i] = 0.5 * (e.dy[i] + e.vy[i] * dt);
      e.dphi[i] = 0.5 * (e.dphi[i] + e.omega[i] * dt);
    } else {  // (K18)
      e.dx[i] = e.vx[i] * dt;
      e.dy[i] = e.vy[i] * dt;
      e.dphi[i] = e.omega[i] * dt;
    }
    e.x[i] += e.dx[i];
    e.y[i] += e.dy[i];
    e.phi[i] += e.dphi[i];
  }
  for (Wall& w : m_.walls) {
    w.increment = w.drive >= 0 ? m_.drives[static_cast<std::size_t>(w.drive)].at(time_ + 0.5 * dt) * dt : Vec2{};
    w.a = w.a + w.increment;
    w.b = w.b + w.increment;
  }
}

void Simulation::step() {
  if (step_ > 0 && needs_rebuild()) rebuild();
  Elements& e = m_.elements;
  const std::size_t n = e.size();
  const Vec2 g = m_.gravity;
  weight(e.fx.data(), e.mass.data(), g.x, n);  // (K15): gravity
  weight(e.fy.data(), e.mass.data(), g.y, n);
  std::fill(e.moment.begin(), e.moment.end(), 0.0);
  for (Wall& w : m_.walls) w.force = {};
  const double inv_dt = 1.0 / m_.numerics.dt;
  sweep_linear_pairs(inv_dt);
  sweep_face_pairs(inv_dt);
  sweep_linear_walls(inv_dt);
  sweep_face_walls(inv_dt);
  if (m_.base_plate.enabled) advance_base_plate();
  integrate();
  ++step_;
  time_ = static_cast<double>(step_) * m_.numerics.dt;
}

void Simulation::advance_base_plate() {
  // (M21) on the velocities of the array, v_{k−1}: the velocity over [t − Δt, t], so the plate's is
  // taken at t − Δt/2; then the plate moves by its velocity over [t, t + Δt] (as a driven wall does).
  const double dt = m_.numerics.dt;
  add_base_friction(m_.elements, m_.base_plate, plate_velocity(m_.base_plate, m_.drives, time_ - 0.5 * dt));
  const Vec2 d = plate_velocity(m_.base_plate, m_.drives, time_ + 0.5 * dt) * dt;
  plate_travel_.displacement = plate_travel_.displacement + d;
  plate_travel_.travel += norm(d);
}

Energies Simulation::energies() const {
  const Elements& e = m_.elements;
  Energies en;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i]) continue;
    en.kinetic += 0.5 * e.mass[i] * (e.vx[i] * e.vx[i] + e.vy[i] * e.vy[i]) +
                  0.5 * e.inertia[i] * e.omega[i] * e.omega[i];
    en.potential -= e.mass[i] * (m_.gravity.x * e.x[i] + m_.gravity.y * e.y[i]);
  }
  auto lin = [&](const LinearSlot& s) {
    if (!s.touching) return;
    const LinearSpringDashpot& l = m_.laws[static_cast<std::size_t>(s.law)].linear;
    if (l.kn > 0.0) en.elastic += 0.5 * s.h.en * s.h.en / l.kn;
    if (l.ks > 0.0) en.elastic += 0.5 * s.h.es * s.h.es / l.ks;
  };
  auto face = [&](const FaceSlot& s) {
    if (!s.touching) return;
    const int n = m_.laws[static_cast<std::size_t>(s.law)].face.segments;
    for (int k = 0; k < n; ++k) {
      const SegmentState& g = s.h.seg[static_cast<std::size_t>(k)];
      if (!g.linked) continue;
      if (s.c.kn > 0.0) en.elastic += 0.5 * g.pe * g.pe / s.c.kn;
      if (s.c.ks > 0.0) en.elastic += 0.5 * g.qe * g.qe / s.c.ks;
    }
  };
  for (const auto& s : linear_pairs_) lin(s);
  for (const auto& s : linear_walls_) lin(s);
  for (const auto& s : face_pairs_) face(s);
  for (const auto& s : face_walls_) face(s);
  return en;
}

std::vector<ContactView> Simulation::contacts() const {
  std::vector<ContactView> out;
  for (const auto& s : linear_pairs_)
    if (s.touching) out.push_back({s.i, s.j, false, s.nx, s.ny, s.f.fn, s.f.fs, 1});
  for (const auto& s : face_pairs_)
    if (s.touching) out.push_back({s.i, s.j, false, s.nx, s.ny, s.f.p, s.f.q, s.f.links});
  for (const auto& s : linear_walls_)
    if (s.touching) out.push_back({s.i, s.j, true, s.nx, s.ny, s.f.fn, s.f.fs, 1});
  for (const auto& s : face_walls_)
    if (s.touching) out.push_back({s.i, s.j, true, s.nx, s.ny, s.f.p, s.f.q, s.f.links});
  return out;
}

Simulation::BandForce Simulation::wall_band_force(std::uint32_t w, double s0, double s1) const {
  const Wall& wall = m_.walls[w];
  const Vec2 ab = wall.b - wall.a;
  const double len = wall.kind == WallKind::segment ? norm(ab) : 0.0;
  const Vec2 along = len > 0.0 ? ab * (1.0 / len) : Vec2{0.0, 0.0};
  const Elements& e = m_.elements;
  BandForce out;
  auto add = [&](std::uint32_t i, std::uint32_t j, std::uint8_t touching, double nx, double ny, double fn, double fs) {
    if (j != w || !touching) return;
    const Vec2 n{nx, ny}, t{-ny, nx};                                   // t = n rotated by +90°
    const Vec2 point = closest_point(wall, Vec2{e.x[i], e.y[i]});       // where the element touches it
    const double s = len > 0.0 ? dot(point - wall.a, along) : 0.0;
    if (s < s0 || s >= s1) return;
    out.normal += fn;                                                   // compression positive
    out.tangential += dot(n * fn + t * fs, along);                      // force on the wall along a→b
    ++out.contacts;
  };
  for (const auto& c : linear_walls_) add(c.i, c.j, c.touching, c.nx, c.ny, c.f.fn, c.f.fs);
  for (const auto& c : face_walls_) add(c.i, c.j, c.touching, c.nx, c.ny, c.f.p, c.f.q);
  return out;
}

std::size_t Simulation::contact_count() const {
  std::size_t n = 0;
  for (const auto& s : linear_pairs_) n += s.touching;
  for (const auto& s : face_pairs_) n += s.touching;
  for (const auto& s : linear_walls_) n += s.touching;
  for (const auto& s : face_walls_) n += s.touching;
  return n;
}

std::pair<double, std::size_t> Simulation::contact_force_sum() const {
  double sum = 0.0;
  std::size_t n = 0;
  auto add = [&](bool touching, double fn, double fs) {
    if (!touching || (fn == 0.0 && fs == 0.0)) return;
    sum += std::hypot(fn, fs);
    ++n;
  };
  for (const auto& s : linear_pairs_) add(s.touching, s.f.fn, s.f.fs);
  for (const auto& s : linear_walls_) add(s.touching, s.f.fn, s.f.fs);
  for (const auto& s : face_pairs_) add(s.touching, s.f.p, s.f.q);
  for (const auto& s : face_walls_) add(s.touching, s.f.p, s.f.q);
  return {sum, n};
}

ContactView Simulation::contact(std::uint32_t i, std::uint32_t j, bool wall) const {
  if (!wall && j < i) std::swap(i, j);
  auto find = [&](const auto& slots) -> const auto* {
    auto it = std::lower_bound(slots.begin(), slots.end(), key(i, j),
                               [](const auto& s, std::uint64_t k) { return key(s.i, s.j) < k; });
    return (it != slots.end() && it->i == i && it->j == j && it->touching) ? &*it : nullptr;
  };
  if (const auto* s = find(wall ? linear_walls_ : linear_pairs_))
    return {i, j, wall, s->nx, s->ny, s->f.fn, s->f.fs, 1};
  if (const auto* s = find(wall ? face_walls_ : face_pairs_))
    return {i, j, wall, s->nx, s->ny, s->f.p, s->f.q, s->f.links};
  return {i, j, wall, 0.0, 0.0, 0.0, 0.0, 0};
}

}  // namespace dem

// ---------------------------------------------------------------------------------------------------
// Time-step guard: the bound over every contact the case can form (stability.cpp).
namespace dem {

StabilityBound Simulation::stability_bound() const {
  return assembly_stability_bound(m_, registered_stability_terms(m_));
}

double Simulation::stability_limit() const { return stability_bound().limit; }

}  // namespace dem
