#include "dem/core/simulation.hpp"
// The reference step: Kiyama & Fujimura's cycle (docs/model.md §1) on one thread, contact by contact and
// element by element, in the words of the paper, with the readable contact laws (linear_contact.hpp,
// face_contact.hpp) and none of the optimised step's machinery (no two-stage sweep, no vectorised
// integration, no thread shares, no travel bound). It is the oracle of tests/lib/core/reference_step_tests.cpp:
// the optimised step() on any number of threads must give the same state bit for bit.
//
// Why the forces are summed in this order. A sum of doubles depends on its order, so the reference must add
// each element's contact forces in the order step() does: the weight first (K15.a), then its slots list by
// list, linear pairs, face pairs, linear walls, face walls, each by ascending slot (slots are sorted by
// (i, j), so by ascending partner). On one thread step() scatters every slot's force as it sweeps the lists
// in that order; on several threads each element sums its slots in the contact index's fixed order
// (contact_index.hpp, Simulation::gather_forces), which is the same order. The walls' reactions are
// summed over the linear wall slots, then the face wall slots (Simulation::sum_wall_forces).
//
// The candidate pairs are the optimised code's (neighbour search and slot merge, rebuild.cpp), renewed when
// an element may have moved far enough (the exact test, each step): which pair is a candidate changes no
// force, and with the same slot lists the states compare field by field.
#include <cmath>

#include "dem/core/face_geometry.hpp"

namespace dem {

namespace {

/// A contact that ends: the slot stays (a candidate pair) and forgets its history.
template <class Slot>
void forget(Slot& s) {
  Slot fresh;
  fresh.i = s.i, fresh.j = s.j, fresh.law = s.law;
  s = fresh;
}

}  // namespace

void Simulation::reference_step() {
  Elements& e = m_.elements;
  const double dt = m_.numerics.dt, inv_dt = 1.0 / dt;
  tested_step_ = -1;  // step()'s own bookkeeping (its rebuild test, travel bound, blow-up test): not kept here
  travel_ = kTravelUnknown;
  oversteps_.clear();
  // New candidates once an element may have moved far enough from where the last rebuild saw it.
  const double limit2 = rebuild_limit2();
  bool displaced = limit2 < 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    const double ddx = e.x[i] - x_ref_[i], ddy = e.y[i] - y_ref_[i];
    displaced = displaced || !(ddx * ddx + ddy * ddy - limit2 < 0.0);
  }
  if (step_ > 0 && displaced) rebuild_on(Team{});
  // (K15.a, K15.b, K15.c): the resultants start from the weight m g and a zero moment.
  for (std::size_t i = 0; i < e.size(); ++i) {
    e.fx[i] = e.mass[i] * m_.gravity.x;
    e.fy[i] = e.mass[i] * m_.gravity.y;
    e.moment[i] = 0.0;
  }
  for (Wall& w : m_.walls) w.force = {};
  // Every contact (K3–K15, M3–M12, M19), in the order step() sums them (above).
  for (std::size_t k = 0; k < linear_pairs_.size(); ++k) reference_linear_pair(k, inv_dt);
  for (std::size_t k = 0; k < face_pairs_.size(); ++k) reference_face_pair(k, inv_dt);
  for (std::size_t k = 0; k < linear_walls_.size(); ++k) reference_linear_wall(k, inv_dt);
  for (std::size_t k = 0; k < face_walls_.size(); ++k) reference_face_wall(k, inv_dt);
  sweep_polygons(inv_dt);  // polygon elements (P5–P8, K6–K14): one readable loop, shared with step()
  sweep_gap_springs(inv_dt);  // gap springs (B2–B5): one readable loop, shared with step()
  if (m_.base_plate.enabled) advance_base_plate();  // (M21): base friction, before the velocities
  // (K16, K17): velocities; (K18) or (K19): the increments of the next step; positions.
  const double dt_v = velocity_dt();  // Δt, or Δt/2 at a staggered start
  const bool k19 = m_.numerics.integrator == Integrator::k19;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i]) continue;  // removed from the run (a silo's outlet): it keeps its state
    if (e.motion[i] == Motion::free) {  // (K17): v_t = v_{t−Δt} + (X/m) Δt
      e.vx[i] += dt_v * e.fx[i] * e.inv_mass[i];
      e.vy[i] += dt_v * e.fy[i] * e.inv_mass[i];
      e.omega[i] += dt_v * e.moment[i] * e.inv_inertia[i];
    } else {  // fixed (at rest) or driven (its prescribed velocity at the middle of the step)
      const Vec2 v = e.motion[i] == Motion::fixed ? Vec2{}
                                                  : m_.drives[static_cast<std::size_t>(e.drive[i])].at(time_ + 0.5 * dt);
      e.vx[i] = v.x, e.vy[i] = v.y, e.omega[i] = 0.0;
    }
    if (k19 && e.motion[i] == Motion::free) {  // (K19): Δu_t = (Δu_{t−Δt} + u̇_t Δt)/2
      e.dx[i] = 0.5 * (e.dx[i] + e.vx[i] * dt);
      e.dy[i] = 0.5 * (e.dy[i] + e.vy[i] * dt);
      e.dphi[i] = 0.5 * (e.dphi[i] + e.omega[i] * dt);
    } else {  // (K18): Δu_t = u̇_t Δt
      e.dx[i] = e.vx[i] * dt, e.dy[i] = e.vy[i] * dt, e.dphi[i] = e.omega[i] * dt;
    }
    e.x[i] += e.dx[i], e.y[i] += e.dy[i], e.phi[i] += e.dphi[i];
  }
  move_walls();
  ++step_;
  forces_step_ = keep_forces_ ? step_ : -1;
  time_ = static_cast<double>(step_) * dt;
}

void Simulation::reference_linear_pair(std::size_t k, double inv_dt) {
  Elements& e = m_.elements;
  LinearPairSlots& s = linear_pairs_;
  const std::uint32_t i = s.pair[k].i, j = s.pair[k].j;
  const double ddx = e.x[j] - e.x[i], ddy = e.y[j] - e.y[i];
  const double rs = e.radius[i] + e.radius[j];
  const double r2 = ddx * ddx + ddy * ddy;  // R_ij² (K3)
  if (r2 > rs * rs || !e.active[i] || !e.active[j]) {  // (K3): the cores do not overlap
    if (s.touching[k]) s.reset(k);
    return;
  }
  const double dist = std::sqrt(r2);
  const double nx = ddx / dist, ny = ddy / dist;  // cos α, sin α (K4): from i towards j
  const double ux = e.dx[i] - e.dx[j], uy = e.dy[i] - e.dy[j];
  const double du_n = ux * nx + uy * ny;                                                   // (K5.a)
  const double du_s = -ux * ny + uy * nx + e.radius[i] * e.dphi[i] + e.radius[j] * e.dphi[j];  // (K5.b)
  const double dtheta_r = e.dphi[i] - e.dphi[j];  // (R1): the relative rotation increment
  LinearContactState& c = s.state[k];
  const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law[k])];
  if (!s.touching[k]) {
    s.touching[k] = 1;
    start_linear(s.law[k], rs - dist, du_n, du_s, e.mass[i], e.mass[j], c.eta_n, c.eta_s, c.h);
    if (law.rolling.enabled) start_rolling(law, i, j, false, dtheta_r, s.rolling[k]);  // (R2, R5)
  }
  const ContactForce f = linear_contact_force(law.linear, c.eta_n, c.eta_s, du_n, du_s, inv_dt, c.h);  // (K6–K14)
  if (f.opened) {  // (K8): the contact ends
    s.reset(k);
    return;
  }
  if (keep_forces_) s.resultant[k] = {f.fn, f.fs, nx, ny};
  const double fx = -f.fn * nx + f.fs * ny, fy = -f.fn * ny - f.fs * nx;  // (K15.a, K15.b): on i; on j the opposite
  e.fx[i] += fx, e.fy[i] += fy, e.fx[j] -= fx, e.fy[j] -= fy;
  e.moment[i] -= e.radius[i] * f.fs;  // (K15.c)
  e.moment[j] -= e.radius[j] * f.fs;
  if (law.rolling.enabled) {  // (R3–R6): the rolling moment, on i and the opposite on j
    const double m_r = rolling_moment(dtheta_r, c.h.en, inv_dt, s.rolling[k]);
    e.moment[i] += m_r;
    e.moment[j] -= m_r;
  }
}

void Simulation::reference_linear_wall(std::size_t k, double inv_dt) {
  Elements& e = m_.elements;
  LinearSlot& s = linear_walls_[k];
  const std::uint32_t i = s.i;
  Wall& w = m_.walls[s.j];
  const Vec2 c{e.x[i], e.y[i]};
  const Vec2 d = closest_point(w, c) - c;  // the wall as element j of radius 0
  const double r2 = dot(d, d), r = e.radius[i];
  if (r2 > r * r || !e.active[i] || r2 == 0.0) {  // (K3)
    if (s.touching) forget(s);
    return;
  }
  const double dist = std::sqrt(r2);
  const double nx = d.x / dist, ny = d.y / dist;  // (K4): towards the wall
  const double ux = e.dx[i] - w.increment.x, uy = e.dy[i] - w.increment.y;
  const double du_n = ux * nx + uy * ny;                      // (K5.a)
  const double du_s = -ux * ny + uy * nx + r * e.dphi[i];  // (K5.b), r_j = 0
  const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
  if (!s.touching) {
    s.touching = 1;
    start_linear(s.law, r - dist, du_n, du_s, e.mass[i], 0.0, s.eta_n, s.eta_s, s.h);
    if (law.rolling.enabled) start_rolling(law, i, s.j, true, e.dphi[i], s.rolling);  // (R1: Δθ_r = Δφ_i), R2, R5
  }
  const ContactForce f = linear_contact_force(law.linear, s.eta_n, s.eta_s, du_n, du_s, inv_dt, s.h);  // (K6–K14)
  if (f.opened) {  // (K8)
    forget(s);
    return;
  }
  s.f = f, s.nx = nx, s.ny = ny;
  const double fx = -f.fn * nx + f.fs * ny, fy = -f.fn * ny - f.fs * nx;  // (K15.a, K15.b)
  e.fx[i] += fx, e.fy[i] += fy;
  e.moment[i] -= r * f.fs;  // (K15.c)
  if (law.rolling.enabled) e.moment[i] += rolling_moment(e.dphi[i], s.h.en, inv_dt, s.rolling);  // (R3–R6)
  w.force.x -= fx, w.force.y -= fy;  // the reaction on the wall
}

void Simulation::reference_face_pair(std::size_t k, double inv_dt) {
  Elements& e = m_.elements;
  FaceSlot& s = face_pairs_[k];
  const std::uint32_t i = s.i, j = s.j;
  if (!e.active[i] || !e.active[j]) {
    if (s.touching) forget(s);
    return;
  }
  const double ddx = e.x[j] - e.x[i], ddy = e.y[j] - e.y[i];
  const double rs = e.radius[i] + e.radius[j];
  const double r2 = ddx * ddx + ddy * ddy;
  const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
  const bool bond = face_bonded_at_start(law, e, i, j, step_);
  if (!s.touching && face_pair_apart(r2, rs, bond)) return;  // a contact forms when D ≤ r1 + r2
  const double dist = std::sqrt(r2);
  const double nx = ddx / dist, ny = ddy / dist;
  const FaceKinematics m = face_pair_kinematics(e, i, j, ddx, ddy, dist, nx, ny);  // (M3, M15)
  if (!s.touching) {
    s.touching = 1;
    const double m_eff = e.mass[i] * e.mass[j] / (e.mass[i] + e.mass[j]);
    s.c = face_constants(law, e.radius[i], e.radius[j], m_eff, m_.thickness);  // (M6, M7.3, M7.4)
    const bool geometric = step_ == 0 || law.onset == Onset::overlap;
    start_face(law.face, s.c, geometric ? (rs - dist) - m.du_projected : 0.0, bond, geometric, s.h);
    if (preloading_) s.h.geometric_start = 0;
  }
  const FaceForce f = face_contact_force_scalar(law.face, s.c, m, inv_dt, s.h);  // (M3–M12)
  s.f = f, s.nx = nx, s.ny = ny;
  if (f.links == 0) s.touching = 0;  // no link left: the contact ends
  const double fx = -f.p * nx + f.q * ny, fy = -f.p * ny - f.q * nx;  // (M12): on i; on j the opposite
  e.fx[i] += fx, e.fy[i] += fy;
  e.moment[i] += -e.radius[i] * f.q + f.p_moment;  // M1 = −r1 Q − Σ aξ P (ξ → −ξ in our axes)
  e.fx[j] -= fx, e.fy[j] -= fy;
  e.moment[j] += -e.radius[j] * f.q - f.p_moment;  // M2
}

void Simulation::reference_face_wall(std::size_t k, double inv_dt) {
  Elements& e = m_.elements;
  FaceSlot& s = face_walls_[k];
  const std::uint32_t i = s.i;
  Wall& w = m_.walls[s.j];
  if (!e.active[i]) {
    if (s.touching) forget(s);
    return;
  }
  const Vec2 c{e.x[i], e.y[i]};
  const Vec2 d = closest_point(w, c) - c;
  const double r2 = dot(d, d), r = e.radius[i];
  const PairLaw& law = m_.laws[static_cast<std::size_t>(s.law)];
  const bool bond = step_ == 0 && law.bond_at_start;
  const double touch = bond ? r * (1.0 + 1e-9) : r;
  if ((!s.touching && r2 > touch * touch) || r2 == 0.0) return;
  const double dist = std::sqrt(r2);
  const double nx = d.x / dist, ny = d.y / dist;
  const double ux = e.dx[i] - w.increment.x, uy = e.dy[i] - w.increment.y;
  FaceKinematics m;  // (M19): the wall replaces one element; its frame does not turn
  m.du_projected = m.du_exact = ux * nx + uy * ny;
  m.dv_translation = m.dv_frame = -ux * ny + uy * nx;
  m.dphi1 = e.dphi[i], m.r1 = r;
  if (!s.touching) {
    s.touching = 1;
    s.c = face_constants(law, r, 0.0, e.mass[i], m_.thickness);  // (M19)
    const bool geometric = step_ == 0 || law.onset == Onset::overlap;
    start_face(law.face, s.c, geometric ? (r - dist) - m.du_projected : 0.0, bond, geometric, s.h);
    if (preloading_) s.h.geometric_start = 0;
  }
  const FaceForce f = face_contact_force_scalar(law.face, s.c, m, inv_dt, s.h);  // (M3–M12)
  s.f = f, s.nx = nx, s.ny = ny;
  if (f.links == 0) s.touching = 0;
  const double fx = -f.p * nx + f.q * ny, fy = -f.p * ny - f.q * nx;  // (M12)
  e.fx[i] += fx, e.fy[i] += fy;
  e.moment[i] += -r * f.q + f.p_moment;
  w.force.x -= fx, w.force.y -= fy;  // the reaction on the wall
}

}  // namespace dem
