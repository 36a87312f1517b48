#pragma once
// Matsui & Nishimura's pseudo-rectangle face contact (docs/model.md §2, M1–M19): a straight face of length
// 2a between two elements (or an element and a straight wall), cut into N segments, each with its own
// spring, dashpot, tension cut-off and Mohr–Coulomb limit.
//
// Frame and sign conventions (documented in lib/README.md, "PRE face"): n is the unit normal from
// element 1 towards element 2 (the current line of centres; the wall normal for a wall contact),
// t = n rotated by +90°, and a face point sits at r1 n + a ξ t from the centre of element 1. With
// these axes the paper's (M2) reads with ξ → −ξ; the moments below are the paper's (M12) under the
// same change. θ1, θ2 are the rotations of the elements relative to the contact frame since the start
// of contact (the frame turns with the line of centres; a wall frame does not turn).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace dem {

inline constexpr int kMaxSegments = 8;

enum class SegmentPositions : std::uint8_t { centres, ends };  // (M13.1), (M13.2)
enum class NormalIncrement : std::uint8_t { exact, linearised };  // (M3.1), (M15.1)
enum class TangentialIncrement : std::uint8_t {
  exact,       // (M3.2), consistent reading: v̄ is the translation-only part
  literal,     // (M3.2) read literally: the rotation r θ counted twice
  linearised,  // (M15.2): Cundall's increment
  hisatake     // (M16): rotation terms only, no translation (kept as the comparison that drifts)
};
// Where a WALL contact's segment forces act on the element (M19): at the face points of the wall frame
// (the paper: M12 with M19), or at the element's rotated body points R(θ1)(r1 n + aξ t), the face-end
// rule that follows the rotated corner (M19.r, not in the paper; docs/model.md). Walls only: the case
// reader refuses it on a law that two elements can share.
enum class FaceLever : std::uint8_t { wall_frame, rotated_corner };

struct FaceLaw {
  int segments = 1;                                    // N
  SegmentPositions positions = SegmentPositions::centres;
  NormalIncrement normal = NormalIncrement::linearised;
  TangentialIncrement tangential = TangentialIncrement::linearised;
  double tensile_strength = 0.0;  // σ_t [Pa]
  double cohesion = 0.0;          // c [Pa]
  double tan_phi = 0.0;           // tan φ
  bool healing = false;           // a re-formed link regains σ_t and c
  FaceLever lever = FaceLever::wall_frame;  // (M19), (M19.r): wall contacts only
};

/// Per-pair constants fixed when the contact forms (they depend on the radii and masses).
struct FaceConstants {
  double kn = 0.0, ks = 0.0;        // discrete springs per segment [N/m] (M6)
  double eta_n = 0.0, eta_s = 0.0;  // discrete dashpots per segment [N·s/m] (M7.3, M7.4)
  double half_length = 0.0;         // a: the face is 2a long [m]
  double segment_area = 0.0;        // A/N [m²] (M1)
};

struct SegmentState {
  double u = 0.0;   // normal displacement at ξ_i since the contact started [m], compression positive
  double pe = 0.0;  // accumulated elastic normal force P_e [N] (M6)
  double qe = 0.0;  // accumulated elastic shear force Q_e [N] (M6)
  std::uint8_t linked = 0;  // the link carries force
  std::uint8_t intact = 1;  // still has its tensile strength and cohesion
  std::uint8_t broke = 0;   // an intact link broke in tension (M8) since the breaks were last taken
                            // (Simulation::take_bond_breaks); not part of the law's state
};
static_assert(sizeof(SegmentState) == 32, "a segment's state fills half a cache line (face_contact_lanes.hpp)");

struct FaceHistory {
  double theta1 = 0.0, theta2 = 0.0;  // rotations relative to the contact frame since contact start
  std::uint8_t geometric_start = 0;   // the first step starts the shear at zero (as the disk law's
                                      // e_s = −K_s Δu_s + K_s Δu_s): set by start_face, cleared after it
  std::array<SegmentState, kMaxSegments> seg{};
};

/// The motion of one step, in the current contact frame.
struct FaceKinematics {
  double du_projected = 0.0;  // (Δx1 − Δx2)·n: Cundall's normal increment (K5) [m]
  double du_exact = 0.0;      // exact approach of the centres over the step (R_old − R_new for pairs) [m]
  double dv_translation = 0.0;  // (Δx1 − Δx2)·t [m]
  double dv_frame = 0.0;      // translation-only tangential increment in the contact frame: 0 for
                              // pairs (the frame turns with the centres), (Δx1 − Δw)·t for walls [m]
  double dphi1 = 0.0, dphi2 = 0.0;  // absolute rotation increments [rad]
  double dbeta = 0.0;         // rotation of the contact frame over the step [rad] (0 for walls)
  double r1 = 0.0, r2 = 0.0;  // centre-to-face distances (r2 = 0 for a wall) [m]
};

struct FaceForce {
  double p = 0.0;        // normal resultant Σ(P_e + P_d) [N] (M12), compression positive
  double q = 0.0;        // shear resultant Σ(Q_e + Q_d) [N] (M12)
  double p_moment = 0.0; // Σ a ξ_i P(i) [N·m]: M1 = −r1 Q + p_moment, M2 = −r2 Q − p_moment; with the
                         // rotated lever (M19.r, walls) M1 + r1 Q, so that M1 = −r1 Q + p_moment still
  int links = 0;         // segments linked after the step
  bool any_tensile = false;  // a linked segment still has tensile strength
};

/// Segment position ξ_i, i = 0..N−1 (M13.1 / M13.2).
constexpr double segment_xi(SegmentPositions pos, int n, int i) {
  if (pos == SegmentPositions::ends) return i == 0 ? -1.0 : 1.0;  // (M13.2), N = 2
  return (2.0 * (i + 1) - 1.0 - n) / n;                              // (M13.1)
}

/// segment_xi for every arrangement, N = 1..kMaxSegments and i < N, computed once at compile time (the
/// same correctly rounded division): the face law reads ξ_i instead of dividing per segment and step.
struct SegmentXiTable {
  double xi[2][kMaxSegments + 1][kMaxSegments] = {};
};
inline constexpr SegmentXiTable kSegmentXi = [] {
  SegmentXiTable t;
  for (int p = 0; p < 2; ++p)
    for (int n = 1; n <= kMaxSegments; ++n)
      for (int i = 0; i < n; ++i) t.xi[p][n][i] = segment_xi(static_cast<SegmentPositions>(p), n, i);
  return t;
}();

/// Starts a contact: every segment gets the same initial normal displacement u0 (the overlap, or the
/// first increment), and links if u0 >= 0. `bonded`: the links start intact (tensile strength and
/// cohesion); otherwise they start as broken-and-re-formed links (compression and friction only,
/// unless healing).
/// `geometric`: the contact starts from the geometric state (present at t = 0, or the overlap onset):
/// the first step's tangential increment does not load the shear springs (it drives the dashpots).
void start_face(const FaceLaw& law, const FaceConstants& c, double u0, bool bonded, bool geometric,
                FaceHistory& h);

/// One step of the face law (M3–M12), the fast form of face_contact_force_scalar (below), the same bits
/// (defined in face_contact_lanes.hpp). Updates the history and returns the resultants. Inline (the
/// contact sweeps call it once per touching face and step): the kinematics and the resultants stay in
/// registers instead of going through memory (g++ would not inline it by itself: measured, bench/journal.md).
[[gnu::always_inline]] inline FaceForce face_contact_force(const FaceLaw& law, const FaceConstants& c, const FaceKinematics& k,
                                    double inv_dt, FaceHistory& h);

namespace face_detail {
// Rotation part of the exact face displacement at ξ (docs/model.md §2, (M2) with ξ → −ξ in our axes):
// u_rot = −r1(1 − cos θ1) − r2(1 − cos θ2) − aξ(sin θ1 − sin θ2)            (M2.1)
// v_rot =  r1 sin θ1 + r2 sin θ2 + aξ(cos θ1 − cos θ2)                        (M2.2)
struct Trig {
  double s1, c1, s2, c2;
};
inline Trig trig(double t1, double t2) { return {std::sin(t1), std::cos(t1), std::sin(t2), std::cos(t2)}; }

/// What the segment loop needs per face: the segments' ξ_i, the ξ-independent parts of the increments
/// (Δu(ξ) = du0 + du_xi ξ, Δv(ξ) = dv0 + dv_xi ξ) and the per-segment constants.
struct SegmentInputs {
  const double* xis;
  double a, du0, du_xi, dv0, dv_xi;
  double kn, ks, eta_n, eta_s, inv_dt;
  double tension_intact, tension_broken, cohesion_intact, cohesion_broken, tan_phi;
  bool healing;
};
/// The resultants in scalars (registers), put together once at the end: a FaceForce built field by
/// field in memory and copied whole stalls the copy's wide loads on the narrow stores.
struct SegmentSums {
  double p = 0.0, q = 0.0, moment = 0.0;
  int links = 0;
  std::uint8_t any_intact = 0;  // a linked segment is intact (keeps σ_t)
};

/// One step of segment i (M6–M12), after the first step's shear restart; adds its resultants to the sums
/// (and Σ a ξ_i Q(i) to *sum_q_moment when given: the rotated lever, M19.r).
[[gnu::always_inline]] inline void segment(const SegmentInputs& in, int i, FaceHistory& h, double& sum_p,
                                           double& sum_q, double& sum_moment, int& links, std::uint8_t& any_intact,
                                           double* sum_q_moment = nullptr) {
  SegmentState& s = h.seg[static_cast<std::size_t>(i)];
  const double xi = in.xis[i];
  const double du = in.du0 + in.du_xi * xi;
  const double dv = in.dv0 + in.dv_xi * xi;
  s.u += du;
  if (!s.linked) [[unlikely]] {  // the hints keep the usual path (linked, holding, below the limit) straight
    if (s.u < 0.0) return;  // still apart at ξ_i
    s.linked = 1;           // unlinked → linked when u(ξ) ≥ 0
    s.intact = in.healing ? 1 : s.intact;
    s.pe = in.kn * s.u;
    s.qe = 0.0;
  } else {
    s.pe += in.kn * du;  // (M6)
    s.qe += in.ks * dv;
  }
  const bool intact = s.intact != 0;
  if (s.pe < (intact ? in.tension_intact : in.tension_broken)) [[unlikely]] {  // (M8, M9): the link breaks and carries nothing
    s.linked = 0;
    s.broke |= s.intact;  // a bond, not a re-formed link, broke: the bond-break log (output.bond_breaks)
    s.intact = 0;
    s.pe = s.qe = 0.0;
    return;
  }
  const double pd = in.eta_n * du * in.inv_dt;  // (M7.1)
  const double qd = in.eta_s * dv * in.inv_dt;  // (M7.2)
  const double limit = (intact ? in.cohesion_intact : in.cohesion_broken) + s.pe * in.tan_phi;  // (M10, M11): τ_y A/N
  // q = Q_e + Q_d, with Q_d = 0 while sliding (Q_e + 0.0 formed as such: −0.0 + 0.0 = +0.0).
  double q;
  if (limit <= 0.0) [[unlikely]] {
    s.qe = 0.0;
    q = s.qe + 0.0;
  } else if (std::abs(s.qe) > limit) [[unlikely]] {
    s.qe = std::copysign(limit, s.qe);
    q = s.qe + 0.0;
  } else {
    q = s.qe + qd;
  }
  const double p = s.pe + pd;
  sum_p += p;
  sum_q += q;
  sum_moment += in.a * xi * p;
  if (sum_q_moment) *sum_q_moment += in.a * xi * q;
  ++links;
  any_intact |= s.intact;
}

/// The part of one step of the face law (M3–M5, M13–M16) that every segment shares: the relative rotations
/// in the contact frame (updated in h), the ξ-independent parts of the increments and the per-segment
/// constants; on the first step of a geometric start the linked segments' shear restarts (first = true).
[[gnu::always_inline]] inline SegmentInputs face_inputs(const FaceLaw& law, const FaceConstants& c, const FaceKinematics& k,
                                                        double inv_dt, FaceHistory& h, bool& first) {
  const int n = law.segments;
  const double a = c.half_length;
  const bool exact_rotations = law.normal == NormalIncrement::exact ||
                               law.tangential != TangentialIncrement::linearised;
  // Relative rotations in the contact frame, before and after the step.
  const double t1_old = h.theta1, t2_old = h.theta2;
  const double dth1 = k.dphi1 - k.dbeta, dth2 = k.dphi2 - k.dbeta;
  h.theta1 += dth1;
  h.theta2 += dth2;
  Trig o{}, w{};
  if (exact_rotations) {
    o = trig(t1_old, t2_old);
    w = trig(h.theta1, h.theta2);
  }
  // ξ-independent parts of the increments.
  double du0 = 0.0, du_xi = 0.0, dv0 = 0.0, dv_xi = 0.0;
  if (law.normal == NormalIncrement::exact) {  // (M3.1), integrated exactly over the step
    du0 = k.du_exact - k.r1 * (o.c1 - w.c1) - k.r2 * (o.c2 - w.c2);
    du_xi = -a * ((w.s1 - w.s2) - (o.s1 - o.s2));
  } else {  // (M15.1)
    du0 = k.du_projected;
    du_xi = -a * (k.dphi1 - k.dphi2);
  }
  switch (law.tangential) {
    case TangentialIncrement::linearised:  // (M15.2) = Cundall's (K5)
      dv0 = k.dv_translation + k.r1 * k.dphi1 + k.r2 * k.dphi2;
      break;
    case TangentialIncrement::exact:  // (M3.2), consistent reading
    case TangentialIncrement::literal:
    case TangentialIncrement::hisatake:  // (M16): no translation term
      dv0 = k.r1 * (w.s1 - o.s1) + k.r2 * (w.s2 - o.s2);
      dv_xi = a * ((w.c1 - w.c2) - (o.c1 - o.c2));
      if (law.tangential != TangentialIncrement::hisatake) dv0 += k.dv_frame;
      if (law.tangential == TangentialIncrement::literal) dv0 += k.r1 * dth1 + k.r2 * dth2;
      break;
  }

  // Per-segment constants that do not depend on the segment, formed once (the same operations as
  // per segment: −σ_t·A/N with σ_t = 0 for a broken link, c·A/N with c = 0).
  SegmentInputs in;
  in.xis = kSegmentXi.xi[law.positions == SegmentPositions::ends ? 1 : 0][n];
  in.a = a;
  in.du0 = du0, in.du_xi = du_xi, in.dv0 = dv0, in.dv_xi = dv_xi;
  in.kn = c.kn, in.ks = c.ks, in.eta_n = c.eta_n, in.eta_s = c.eta_s, in.inv_dt = inv_dt;
  const double area = c.segment_area;
  in.tension_intact = -law.tensile_strength * area, in.tension_broken = -0.0 * area;  // (M8, M9)
  in.cohesion_intact = law.cohesion * area, in.cohesion_broken = 0.0 * area;         // (M10)
  in.tan_phi = law.tan_phi;
  in.healing = law.healing;
  first = h.geometric_start != 0;
  // The first step of a geometric start: the linked segments' shear restarts from −K_s Δv (the loop then
  // adds K_s Δv, as the disk law's e_s = −K_s Δu_s + K_s Δu_s); Δv is formed as in the loop, bit for bit.
  if (first)
    for (int i = 0; i < n; ++i) {
      SegmentState& s = h.seg[static_cast<std::size_t>(i)];
      if (s.linked) s.qe = -in.ks * (dv0 + dv_xi * in.xis[i]);
    }
  return in;
}

/// The resultants of the step (M12) from the segments' sums; ends the first step of a geometric start.
[[gnu::always_inline]] inline FaceForce face_resultants(const FaceLaw& law, const SegmentSums& r, bool first, FaceHistory& h) {
  if (first) h.geometric_start = 0;
  FaceForce f;
  f.p = r.p;
  f.q = r.q;
  f.p_moment = r.moment;
  f.links = r.links;
  f.any_tensile = law.tensile_strength > 0.0 && r.any_intact != 0;  // a linked segment with σ_t > 0
  return f;
}

}  // namespace face_detail

/// One step of the face law (M3–M12), the readable statement: the shared part of the step, then the N
/// segments one after another (M6–M11), their resultants summed in segment order (M12). Updates the history
/// and returns the resultants. face_contact_force (face_contact_lanes.hpp) gives the same bits faster.
inline FaceForce face_contact_force_scalar(const FaceLaw& law, const FaceConstants& c, const FaceKinematics& k,
                                           double inv_dt, FaceHistory& h) {
  bool first = false;
  const face_detail::SegmentInputs in = face_detail::face_inputs(law, c, k, inv_dt, h, first);
  face_detail::SegmentSums r;
  double sum_p = 0.0, sum_q = 0.0, sum_moment = 0.0, sum_q_moment = 0.0;
  const bool rotated = law.lever == FaceLever::rotated_corner;
  for (int i = 0; i < law.segments; ++i)
    face_detail::segment(in, i, h, sum_p, sum_q, sum_moment, r.links, r.any_intact, rotated ? &sum_q_moment : nullptr);
  r.p = sum_p, r.q = sum_q, r.moment = sum_moment;
  if (rotated) [[unlikely]] {
    // (M19.r): segment i's −P(i) n − Q(i) t acts at the body point R(θ1)(r1 n + aξ_i t), θ1 the element's
    // rotation against the wall since the contact started:
    // M1 = cos θ1 (−r1 Q + Σ aξ P) + sin θ1 (r1 P + Σ aξ Q); kept as p_moment = M1 + r1 Q (FaceForce).
    const double c1 = std::cos(h.theta1), s1 = std::sin(h.theta1);
    const double m1 = c1 * (-k.r1 * sum_q + sum_moment) + s1 * (k.r1 * sum_p + sum_q_moment);
    r.moment = m1 + k.r1 * sum_q;
  }
  return face_detail::face_resultants(law, r, first, h);
}

}  // namespace dem

#include "dem/contact/face_contact_lanes.hpp"  // face_contact_force: the same law, segments in vector lanes
