// Simulation's contact sweeps (simulation.hpp): every slot's contact law in slot order, the linear pairs
// and walls (K3, K5–K15) and the face pairs and walls (M3–M12, M19), with the constants a contact starts
// with (start_linear, linear_dashpots, face_constants); the walls' reactions. The sweeps of one thread
// (sweep_scatter) and of a thread's share (sweep_share) are here, with the sweeps: a function with AVX2
// clones (DEM2D_CLONES_AVX2) is called only from the file that defines it (a resolver emitted in another file
// does not find the clones at link time).
#include "dem/core/simulation.hpp"

#include <algorithm>
#include <cmath>

#include "dem/core/face_geometry.hpp"
#include "dem/core/step_loops.hpp"

namespace dem {

namespace step_detail {

/// The forces of a step start from the weight, f = m g (K15), both components in one pass.
void weight(double* __restrict fx, double* __restrict fy, const double* __restrict m, Vec2 g, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    fx[i] = m[i] * g.x;
    fy[i] = m[i] * g.y;
  }
}

}  // namespace step_detail

using step_detail::weight;

namespace {

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

}  // namespace

void Simulation::sweep_scatter(double inv_dt) {
  if (linear_pairs_.with_rolling) sweep_linear_pairs<false, true>(inv_dt, 0, linear_pairs_.size());
  else sweep_linear_pairs<false, false>(inv_dt, 0, linear_pairs_.size());
  sweep_face_pairs<false>(inv_dt, 0, face_pairs_.size());
  sweep_linear_walls<false>(inv_dt, 0, linear_walls_.size());
  sweep_face_walls<false>(inv_dt, 0, face_walls_.size());
}

void Simulation::sweep_share(double inv_dt, std::size_t k, bool from_weight) {
  const std::size_t b = shares_.first[k], end = shares_.first[k + 1];
  if (from_weight) {  // (K15): gravity; the shared elements start from it in gather_forces
    Elements& e = m_.elements;
    weight(e.fx.data() + b, e.fy.data() + b, e.mass.data() + b, m_.gravity, end - b);
    std::fill(e.moment.begin() + static_cast<std::ptrdiff_t>(b), e.moment.begin() + static_cast<std::ptrdiff_t>(end), 0.0);
  }
  const auto& sl = shares_.slots;
  if (linear_pairs_.with_rolling) sweep_linear_pairs<true, true>(inv_dt, sl[0][k], sl[0][k + 1]);
  else sweep_linear_pairs<true, false>(inv_dt, sl[0][k], sl[0][k + 1]);
  sweep_face_pairs<true>(inv_dt, sl[1][k], sl[1][k + 1]);
  sweep_linear_walls<true>(inv_dt, sl[2][k], sl[2][k + 1]);
  sweep_face_walls<true>(inv_dt, sl[3][k], sl[3][k + 1]);
}

/// The walls' reactions, in slot order (linear wall slots, then face wall slots), as the sweeps summed them.
void Simulation::sum_wall_forces() {
  for (const LinearSlot& s : linear_walls_) {
    if (!s.touching) continue;
    Wall& w = m_.walls[s.j];
    const double fx = -s.f.fn * s.nx + s.f.fs * s.ny, fy = -s.f.fn * s.ny - s.f.fs * s.nx;
    w.force.x -= fx;
    w.force.y -= fy;
  }
  for (std::size_t n = 0; n < face_walls_.size(); ++n) {
    const ElementPush& p = face_wall_push_[n];
    if (!p.applied) continue;
    Wall& w = m_.walls[face_walls_[n].j];
    w.force.x -= p.fx;
    w.force.y -= p.fy;
  }
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

void Simulation::start_linear(std::int32_t law_index, double overlap, double du_n, double du_s, double mass_i,
                              double mass_j, double& eta_n, double& eta_s, LinearContactHistory& h) const {
  const PairLaw& law = m_.laws[static_cast<std::size_t>(law_index)];
  h = {};
  const Dashpots d = linear_dashpots(law, mass_i, mass_j);
  eta_n = d.eta_n;
  eta_s = d.eta_s;
  // Contacts present at the start, or formed with the overlap onset, start from the geometric
  // overlap: e_n = K_n δ after this step's increment is added (docs/references.md §1.4: e_0 = K x(0)).
  if (step_ == 0 || law.onset == Onset::overlap) {
    h.en = law.linear.kn * (overlap - du_n);  // the face law's start, operation for operation (M18)
    // The first increment of a plain start is the virtual v(0)Δt (docs/references.md §1.4): it drives the
    // dashpots, not the shear spring. A static preload is a real deformation: it loads the spring.
    h.es = preloading_ ? 0.0 : -law.linear.ks * du_s;
  }
}

void Simulation::start_rolling(const PairLaw& law, std::uint32_t i, std::uint32_t j, bool wall, double dtheta,
                               RollingState& s) const {
  const Elements& e = m_.elements;
  const double r_j = wall ? 0.0 : e.radius[j];
  const double r_r = rolling_radius(e.radius[i], r_j);  // (R1)
  s = {};
  s.kr = rolling_stiffness(law.rolling, law.linear.kn, r_r);  // (R2)
  s.cr = rolling_dashpot(law.rolling,
                         rolling_inertia(e.inertia[i], e.mass[i], e.radius[i], wall ? 0.0 : e.inertia[j],
                                         wall ? 0.0 : e.mass[j], r_j),
                         s.kr);  // (R5)
  s.arm = law.rolling.mu_r * r_r;  // (R4)
  // As the shear spring (start_linear): a contact that starts from its geometry takes the first increment,
  // the virtual ω(0)Δt of a plain start, into the dashpot only; a static preload loads the spring.
  if ((step_ == 0 || law.onset == Onset::overlap) && !preloading_) s.mk = s.kr * dtheta;
}

namespace {
// One overlapping candidate's geometry (K3, K5), made one contact ahead of its law (below).
struct PairGeometry {
  std::size_t k;
  std::uint32_t i, j;
  double overlap, nx, ny, du_n, du_s;
};
}  // namespace

// The sweep runs in two stages one overlapping candidate apart: while the law and the scatter of one
// contact run, the next overlapping candidate's distance, square root and normal are already under way
// (they depend on nothing the law writes). Each stage performs the operations of the plain loop, and the
// laws run and add their forces in slot order: the same results bit for bit.
template <bool Shares, bool Rolling>
void Simulation::sweep_linear_pairs(double inv_dt, std::size_t b, std::size_t end) {
  Elements& e = m_.elements;
  const double* const x = e.x.data();
  const double* const y = e.y.data();
  const double* const radius = e.radius.data();
  const std::uint8_t* const active = e.active.data();
  const double* const dx = e.dx.data();
  const double* const dy = e.dy.data();
  const double* const dphi = e.dphi.data();
  double* const fx_e = e.fx.data();  // local pointers: no reloads after stores
  double* const fy_e = e.fy.data();
  double* const moment = e.moment.data();
  [[maybe_unused]] const std::uint8_t* const shared = shares_.shared.data();
  const PairLaw* const laws = m_.laws.data();
  const SlotPair* const pairs = linear_pairs_.pair.data();  // read for every candidate (hot)
  std::uint8_t* const touching = linear_pairs_.touching.data();
  const std::int32_t* const law_of = linear_pairs_.law.data();  // read for touching pairs only (cold)
  LinearContactState* const state = linear_pairs_.state.data();
  LinearContactResultant* const resultant = linear_pairs_.resultant.data();
  const bool keep = keep_forces_;
  // Stage 1: from slot k on, ends the contacts of the candidates that do not overlap (K3) and makes the
  // geometry of the first one that does; false at the end of the range.
  auto next_overlap = [&](std::size_t& k, PairGeometry& g) {
    for (; k < end; ++k) {
      const std::uint32_t i = pairs[k].i, j = pairs[k].j;
      const double ddx = x[j] - x[i], ddy = y[j] - y[i];
      const double rs = radius[i] + radius[j];
      const double r2 = ddx * ddx + ddy * ddy;
      if (r2 > rs * rs || !active[i] || !active[j]) {  // (K3): not touching
        if (touching[k]) linear_pairs_.reset(k);
        continue;
      }
      const double dist = std::sqrt(r2);
      g.nx = ddx / dist, g.ny = ddy / dist;  // cos α, sin α (K3): from i towards j
      const double ux = dx[i] - dx[j], uy = dy[i] - dy[j];
      g.du_n = ux * g.nx + uy * g.ny;  // (K5)
      g.du_s = -ux * g.ny + uy * g.nx + radius[i] * dphi[i] + radius[j] * dphi[j];
      g.overlap = rs - dist;
      g.k = k++, g.i = i, g.j = j;
      return true;
    }
    return false;
  };
  std::size_t k = b;
  PairGeometry g{}, g_next{};
  bool more = next_overlap(k, g);
  while (more) {
    more = next_overlap(k, g_next);
    // Stage 2: the law of contact g (K6–K14) and its forces (K15).
    const std::size_t c = g.k;
    const std::uint32_t i = g.i, j = g.j;
    LinearContactState& s = state[c];
    const std::int32_t law_k = law_of[c];
    const PairLaw& law = laws[static_cast<std::size_t>(law_k)];
    const bool rolls = Rolling && law.rolling.enabled;
    if (!touching[c]) {
      touching[c] = 1;
      start_linear(law_k, g.overlap, g.du_n, g.du_s, e.mass[i], e.mass[j], s.eta_n, s.eta_s, s.h);
      if (rolls) start_rolling(law, i, j, false, dphi[i] - dphi[j], linear_pairs_.rolling[c]);
    }
    const ContactForce f = linear_contact_force(law.linear, s.eta_n, s.eta_s, g.du_n, g.du_s, inv_dt, s.h);
    const double nx = g.nx, ny = g.ny;
    g = g_next;
    if (f.opened) {  // (K8): the contact ends; if the cores still overlap it forms anew next step
      linear_pairs_.reset(c);
      continue;
    }
    // (R1–R6): the rolling moment on i, on j the opposite; Δθ_r = Δφ_i − Δφ_j
    const double m_roll = rolls ? rolling_moment(dphi[i] - dphi[j], s.h.en, inv_dt, linear_pairs_.rolling[c]) : 0.0;
    // for outputs, if this step keeps them, and for gather_forces if an element is shared
    if (keep || (Shares && (shared[i] || shared[j]))) resultant[c] = {f.fn, f.fs, nx, ny};
    // (K15): force on i is −f_n n − f_s t, t = (−sin α, cos α); on j the opposite.
    const double fx = -f.fn * nx + f.fs * ny, fy = -f.fn * ny - f.fs * nx;
    if constexpr (!Shares) {
      fx_e[i] += fx;
      fy_e[i] += fy;
      fx_e[j] -= fx;
      fy_e[j] -= fy;
      moment[i] -= radius[i] * f.fs;
      moment[j] -= radius[j] * f.fs;
      if (rolls) moment[i] += m_roll, moment[j] -= m_roll;  // (R6)
    } else {
      if (!shared[i]) {
        fx_e[i] += fx;
        fy_e[i] += fy;
        moment[i] -= radius[i] * f.fs;
        if (rolls) moment[i] += m_roll;
      }
      if (!shared[j]) {
        fx_e[j] -= fx;
        fy_e[j] -= fy;
        moment[j] -= radius[j] * f.fs;
        if (rolls) moment[j] -= m_roll;
      }
    }
  }
}

template <bool Shares>
void Simulation::sweep_linear_walls(double inv_dt, std::size_t b, std::size_t end) {
  Elements& e = m_.elements;
  for (std::size_t k = b; k < end; ++k) {
    LinearSlot& s = linear_walls_[k];
    const std::uint32_t i = s.i;
    const Wall& w = m_.walls[s.j];
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
    const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
    const bool rolls = law.rolling.enabled;
    if (!s.touching) {
      s.touching = 1;
      start_linear(s.law, r - dist, du_n, du_s, e.mass[i], 0.0, s.eta_n, s.eta_s, s.h);
      if (rolls) start_rolling(law, i, s.j, true, e.dphi[i], s.rolling);
    }
    const ContactForce f = linear_contact_force(law.linear, s.eta_n, s.eta_s, du_n, du_s, inv_dt, s.h);
    if (f.opened) {
      reset_slot(s);
      continue;
    }
    s.f = f;  // sum_wall_forces adds it, and gather_forces if the element is shared
    s.nx = nx;
    s.ny = ny;
    if (rolls) rolling_moment(e.dphi[i], s.h.en, inv_dt, s.rolling);  // (R1–R6): the wall does not turn, Δθ_r = Δφ_i
    if (!Shares || !shares_.shared[i]) {
      e.fx[i] += -f.fn * nx + f.fs * ny;
      e.fy[i] += -f.fn * ny - f.fs * nx;
      e.moment[i] -= r * f.fs;
      if (rolls) e.moment[i] += s.rolling.m;  // (R6)
    }
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

namespace {
// The slot keeps the step's resultants (outputs), stored field by field: a whole-struct copy makes g++
// build the FaceForce on the stack and move it with wide loads over its narrow stores (a store-forwarding
// stall per face and step, measured in bench/journal.md).
inline void keep_forces(FaceForce& to, const FaceForce& f) {
  to.p = f.p;
  to.q = f.q;
  to.p_moment = f.p_moment;
  to.links = f.links;
  to.any_tensile = f.any_tensile;
}
}  // namespace

template <bool Shares>
void Simulation::sweep_face_pairs(double inv_dt, std::size_t b, std::size_t end) {
  Elements& e = m_.elements;
  for (std::size_t n = b; n < end; ++n) {
    FaceSlot& s = face_pairs_[n];
    ElementPush& push = face_push_[n];
    push.applied = 0;
    const std::uint32_t i = s.i, j = s.j;
    if (!e.active[i] || !e.active[j]) {
      if (s.touching) reset_slot(s);
      continue;
    }
    const double ddx = e.x[j] - e.x[i], ddy = e.y[j] - e.y[i];
    const double rs = e.radius[i] + e.radius[j];
    const double r2 = ddx * ddx + ddy * ddy;
    const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
    const bool bond = face_bonded_at_start(law, e, i, j, step_);
    if (!s.touching && face_pair_apart(r2, rs, bond)) continue;  // not touching → touching when D ≤ r1 + r2
    const double dist = std::sqrt(r2);
    const double nx = ddx / dist, ny = ddy / dist;
    const FaceKinematics k = face_pair_kinematics(e, i, j, ddx, ddy, dist, nx, ny);
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
    keep_forces(s.f, f);
    s.nx = nx;
    s.ny = ny;
    if (f.links == 0) s.touching = 0;  // touching → not touching when no link remains
    push.fx = -f.p * nx + f.q * ny;  // (M12): on i; on j the opposite
    push.fy = -f.p * ny - f.q * nx;
    push.mi = -e.radius[i] * f.q + f.p_moment;
    push.mj = -e.radius[j] * f.q - f.p_moment;
    push.applied = 1;
    if (!Shares || !shares_.shared[i]) {
      e.fx[i] += push.fx;
      e.fy[i] += push.fy;
      e.moment[i] += push.mi;
    }
    if (!Shares || !shares_.shared[j]) {
      e.fx[j] -= push.fx;
      e.fy[j] -= push.fy;
      e.moment[j] += push.mj;
    }
  }
}

template <bool Shares>
void Simulation::sweep_face_walls(double inv_dt, std::size_t b, std::size_t end) {
  Elements& e = m_.elements;
  for (std::size_t n = b; n < end; ++n) {
    FaceSlot& s = face_walls_[n];
    ElementPush& push = face_wall_push_[n];
    push.applied = 0;
    const std::uint32_t i = s.i;
    const Wall& w = m_.walls[s.j];
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
    keep_forces(s.f, f);
    s.nx = nx;
    s.ny = ny;
    if (f.links == 0) s.touching = 0;
    push.fx = -f.p * nx + f.q * ny;
    push.fy = -f.p * ny - f.q * nx;
    push.mi = -r * f.q + f.p_moment;
    push.applied = 1;
    if (!Shares || !shares_.shared[i]) {
      e.fx[i] += push.fx;
      e.fy[i] += push.fy;
      e.moment[i] += push.mi;
    }
  }
}

}  // namespace dem
