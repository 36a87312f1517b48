#include "dem/contact/face_contact.hpp"

#include <cmath>

namespace dem {

namespace {

// Rotation part of the exact face displacement at ξ (docs/model.md §2, (M2) with ξ → −ξ in our axes):
// u_rot = −r1(1 − cos θ1) − r2(1 − cos θ2) − aξ(sin θ1 − sin θ2)            (M2.1)
// v_rot =  r1 sin θ1 + r2 sin θ2 + aξ(cos θ1 − cos θ2)                        (M2.2)
struct Trig {
  double s1, c1, s2, c2;
};
inline Trig trig(double t1, double t2) { return {std::sin(t1), std::cos(t1), std::sin(t2), std::cos(t2)}; }

}  // namespace

void start_face(const FaceLaw& law, const FaceConstants& c, double u0, bool bonded, bool geometric,
                FaceHistory& h) {
  h = FaceHistory{};
  h.geometric_start = geometric ? 1 : 0;
  const int n = law.segments;
  for (int i = 0; i < n; ++i) {
    SegmentState& s = h.seg[i];
    s.u = u0;
    s.intact = (bonded || law.healing) ? 1 : 0;
    // link: unlinked → linked when u(ξ) ≥ 0. A geometric start (the contact exists at t = 0 or forms
    // with the overlap onset) links every segment with P_e = K_n u0, u0 = overlap − this step's
    // increment, so that after the step P_e = K_n × overlap exactly as the disk law's e_n (a segment
    // still apart after the step then breaks at once, carrying nothing); so does a bonded face.
    if (u0 >= 0.0 || bonded || geometric) {
      s.linked = 1;
      s.pe = c.kn * u0;
    }
  }
}

FaceForce face_contact_force(const FaceLaw& law, const FaceConstants& c, const FaceKinematics& k,
                             double inv_dt, FaceHistory& h) {
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

  FaceForce f;
  const bool first = h.geometric_start != 0;
  for (int i = 0; i < n; ++i) {
    SegmentState& s = h.seg[i];
    const double xi = segment_xi(law.positions, n, i);
    const double du = du0 + du_xi * xi;
    const double dv = dv0 + dv_xi * xi;
    s.u += du;
    if (!s.linked) {
      if (s.u < 0.0) continue;  // still apart at ξ_i
      s.linked = 1;             // unlinked → linked when u(ξ) ≥ 0
      s.intact = law.healing ? 1 : s.intact;
      s.pe = c.kn * s.u;
      s.qe = 0.0;
    } else {
      s.pe += c.kn * du;  // (M6)
      if (h.geometric_start) s.qe = -c.ks * dv;
      s.qe += c.ks * dv;
    }
    const double sigma_t = s.intact ? law.tensile_strength : 0.0;
    if (s.pe < -sigma_t * c.segment_area) {  // (M8, M9): the link breaks and carries nothing
      s.linked = 0;
      s.intact = 0;
      s.pe = s.qe = 0.0;
      continue;
    }
    double pd = c.eta_n * du * inv_dt;  // (M7.1)
    double qd = c.eta_s * dv * inv_dt;  // (M7.2)
    const double cohesion = s.intact ? law.cohesion : 0.0;
    const double limit = cohesion * c.segment_area + s.pe * law.tan_phi;  // (M10, M11): τ_y A/N
    if (limit <= 0.0) {
      s.qe = 0.0;
      qd = 0.0;
    } else if (std::abs(s.qe) > limit) {
      s.qe = std::copysign(limit, s.qe);
      qd = 0.0;
    }
    const double p = s.pe + pd, q = s.qe + qd;
    f.p += p;
    f.q += q;
    f.p_moment += a * xi * p;
    ++f.links;
    f.any_tensile = f.any_tensile || sigma_t > 0.0;
  }
  if (first) h.geometric_start = 0;
  return f;
}

}  // namespace dem
