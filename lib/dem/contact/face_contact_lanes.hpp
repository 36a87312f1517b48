#pragma once
// The PRE face law (face_contact.hpp) with the segments in vector lanes: for N = 3…5, segments 0…3 step in the
// lanes of one vector while all four are linked, intact, holding and sticking (segment_block), the others on
// the scalar usual path (segment_usual) or the readable segment. Every lane performs the readable law's
// operations on the same operands, in the same order (no FMA: lib/CMakeLists.txt), so face_contact_force
// gives face_contact_force_scalar's bits (tests/lib/contact/face_contact_tests.cpp; bench/journal.md, "PRE faces: four
// segments in vector lanes").
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "dem/contact/face_contact.hpp"

namespace dem {

namespace face_detail {

/// Segment i when it is on segment_block's usual path (the same test in scalars, straight-line): its step
/// and sums as `segment` forms them. Returns false, having changed nothing, off that path.
[[gnu::always_inline]] inline bool segment_usual(const SegmentInputs& in, int i, FaceHistory& h, double& sum_p,
                                                 double& sum_q, double& sum_moment) {
  SegmentState& s = h.seg[static_cast<std::size_t>(i)];
  const double xi = in.xis[i];
  const double du = in.du0 + in.du_xi * xi;
  const double dv = in.dv0 + in.dv_xi * xi;
  const double pe = s.pe + in.kn * du;  // (M6)
  const double qe = s.qe + in.ks * dv;
  const double limit = in.cohesion_intact + pe * in.tan_phi;  // (M10, M11)
  if (!((s.linked == 1) & (s.intact == 1) & (pe >= in.tension_intact) & (std::abs(qe) < limit))) [[unlikely]]
    return false;
  s.u += du;
  s.pe = pe;
  s.qe = qe;
  const double p = pe + in.eta_n * du * in.inv_dt;  // (M7.1)
  const double q = qe + in.eta_s * dv * in.inv_dt;  // (M7.2)
  sum_p += p;
  sum_q += q;
  sum_moment += in.a * xi * p;
  return true;
}

// Four segments in the lanes of one vector (GCC/clang vector extensions: AVX2 registers in the sweeps'
// AVX2 clones, SSE2 pairs otherwise). Every lane performs the scalar segment's operations on the same
// operands (no FMA: see lib/CMakeLists.txt), so the results are the same bit for bit.
using V4d = double __attribute__((vector_size(32)));
using V4l = std::int64_t __attribute__((vector_size(32)));
// (macros, not functions: a function taking or returning a 32-byte vector warns of its ABI without AVX)
#define DEM2D_SPLAT(x) (V4d{(x), (x), (x), (x)})
#define DEM2D_AS_D(x) __builtin_bit_cast(V4d, (x))
#define DEM2D_AS_L(x) __builtin_bit_cast(V4l, (x))

/// Segments 0 … L−1 (L = 3 or 4) at once on the usual path: every one linked and intact (its flag bytes 1,
/// 1), holding (P_e ≥ −σ_t A/N) and below its Mohr–Coulomb limit. The segment states (32 bytes each: u,
/// P_e, Q_e, the flags) are loaded as four rows and transposed into columns. Returns false, having
/// changed nothing, if a segment leaves the usual path (the caller then runs the scalar segments);
/// otherwise stores the states and forms the sums in segment order: the column vector (Σp, Σq, Σmoment)
/// adds segment 0, then 1, … (each lane the scalar sum's operations, starting from +0.0).
template <int L>
[[gnu::always_inline]] inline bool segment_block(const SegmentInputs& in, FaceHistory& h, V4d& sums) {
  static_assert(L == 3 || L == 4);
  static_assert(sizeof(SegmentState) == 32 && offsetof(SegmentState, linked) == 24 &&
                offsetof(SegmentState, intact) == 25 && kMaxSegments >= 4);
  V4d r0, r1, r2, r3, xi;  // rows (u, P_e, Q_e, flags) of segments 0..3 (segment 3 only read when L = 3)
  std::memcpy(&r0, &h.seg[0], 32);
  std::memcpy(&r1, &h.seg[1], 32);
  std::memcpy(&r2, &h.seg[2], 32);
  std::memcpy(&r3, &h.seg[3], 32);
  std::memcpy(&xi, in.xis, 32);  // a row of kSegmentXi: kMaxSegments entries
  const V4d a0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6), a1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
  const V4d a2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6), a3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
  V4d u = __builtin_shufflevector(a0, a2, 0, 1, 4, 5), qe = __builtin_shufflevector(a0, a2, 2, 3, 6, 7);
  V4d pe = __builtin_shufflevector(a1, a3, 0, 1, 4, 5);
  const V4d flags = __builtin_shufflevector(a1, a3, 2, 3, 6, 7);
  const V4d du = DEM2D_SPLAT(in.du0) + DEM2D_SPLAT(in.du_xi) * xi;
  const V4d dv = DEM2D_SPLAT(in.dv0) + DEM2D_SPLAT(in.dv_xi) * xi;
  u += du;
  pe += DEM2D_SPLAT(in.kn) * du;  // (M6)
  qe += DEM2D_SPLAT(in.ks) * dv;
  const V4d limit = DEM2D_SPLAT(in.cohesion_intact) + pe * DEM2D_SPLAT(in.tan_phi);  // (M10, M11)
  const V4d abs_qe = DEM2D_AS_D(DEM2D_AS_L(qe) & 0x7fffffffffffffff);
  // On the usual path, tested so that every lane taken here the scalar segment takes too: linked and intact,
  // P_e ≥ −σ_t A/N (the scalar cut-off is P_e < −σ_t A/N) and |Q_e| < τ_y A/N (so τ_y > 0 and no sliding). The
  // boundaries that this leaves out (|Q_e| = τ_y A/N, NaN) go the scalar way, with the same results.
  V4l on = ((DEM2D_AS_L(flags) & 0xffff) == 0x0101) & (pe >= DEM2D_SPLAT(in.tension_intact)) & (abs_qe < limit);
  if constexpr (L == 3) on |= V4l{0, 0, 0, -1};  // segment 3 is not part of the face
  V4l all = on & __builtin_shufflevector(on, on, 2, 3, 0, 1);
  all &= __builtin_shufflevector(all, all, 1, 0, 3, 2);
  if (all[0] != -1) [[unlikely]] return false;
  const V4d pd = DEM2D_SPLAT(in.eta_n) * du * DEM2D_SPLAT(in.inv_dt);  // (M7.1)
  const V4d qd = DEM2D_SPLAT(in.eta_s) * dv * DEM2D_SPLAT(in.inv_dt);  // (M7.2)
  const V4d p = pe + pd, q = qe + qd;
  const V4d moment = DEM2D_SPLAT(in.a) * xi * p;
  // the states back into rows (the flags as they were)
  const V4d b0 = __builtin_shufflevector(u, pe, 0, 4, 2, 6), b1 = __builtin_shufflevector(u, pe, 1, 5, 3, 7);
  const V4d b2 = __builtin_shufflevector(qe, flags, 0, 4, 2, 6), b3 = __builtin_shufflevector(qe, flags, 1, 5, 3, 7);
  r0 = __builtin_shufflevector(b0, b2, 0, 1, 4, 5);
  r1 = __builtin_shufflevector(b1, b3, 0, 1, 4, 5);
  r2 = __builtin_shufflevector(b0, b2, 2, 3, 6, 7);
  r3 = __builtin_shufflevector(b1, b3, 2, 3, 6, 7);
  std::memcpy(static_cast<void*>(&h.seg[0]), &r0, 32);
  std::memcpy(static_cast<void*>(&h.seg[1]), &r1, 32);
  std::memcpy(static_cast<void*>(&h.seg[2]), &r2, 32);
  if constexpr (L == 4) std::memcpy(static_cast<void*>(&h.seg[3]), &r3, 32);
  // columns (p_i, q_i, moment_i, 0) of the segments, added in segment order
  const V4d zero{0.0, 0.0, 0.0, 0.0};
  const V4d c0 = __builtin_shufflevector(p, q, 0, 4, 2, 6), c1 = __builtin_shufflevector(p, q, 1, 5, 3, 7);
  const V4d c2 = __builtin_shufflevector(moment, zero, 0, 4, 2, 6), c3 = __builtin_shufflevector(moment, zero, 1, 5, 3, 7);
  sums += __builtin_shufflevector(c0, c2, 0, 1, 4, 5);
  sums += __builtin_shufflevector(c1, c3, 0, 1, 4, 5);
  sums += __builtin_shufflevector(c0, c2, 2, 3, 6, 7);
  if constexpr (L == 4) sums += __builtin_shufflevector(c1, c3, 2, 3, 6, 7);
  return true;
}
#undef DEM2D_SPLAT
#undef DEM2D_AS_D
#undef DEM2D_AS_L

/// One step of the N segments (M6–M12), after the first step's shear restart. NFixed > 0: N = NFixed
/// known at compile time (the loop unrolled; N = 3, 4, 5: segments 0 … min(N, 4) − 1 in vector lanes
/// when all are on the usual path); NFixed = 0: N = n.
template <int NFixed>
[[gnu::always_inline]] inline void segments(const SegmentInputs& in, int n, FaceHistory& h, SegmentSums& r) {
  const int count = NFixed > 0 ? NFixed : n;
  double sum_p = 0.0, sum_q = 0.0, sum_moment = 0.0;
  int links = 0;
  std::uint8_t any_intact = 0;
  if constexpr (NFixed >= 3 && NFixed <= 5) {
    constexpr int L = NFixed < 4 ? NFixed : 4;
    V4d sums{0.0, 0.0, 0.0, 0.0};
    if (segment_block<L>(in, h, sums)) [[likely]] {
      sum_p = sums[0], sum_q = sums[1], sum_moment = sums[2];
      links = L;
      any_intact = 1;
#pragma GCC unroll 8
      for (int i = L; i < NFixed; ++i) {
        if (segment_usual(in, i, h, sum_p, sum_q, sum_moment)) [[likely]]
          ++links;
        else
          segment(in, i, h, sum_p, sum_q, sum_moment, links, any_intact);
      }
    } else {
#pragma GCC unroll 8
      for (int i = 0; i < NFixed; ++i) segment(in, i, h, sum_p, sum_q, sum_moment, links, any_intact);
    }
  } else {
#pragma GCC unroll 8
    for (int i = 0; i < count; ++i) segment(in, i, h, sum_p, sum_q, sum_moment, links, any_intact);
  }
  r.p = sum_p;
  r.q = sum_q;
  r.moment = sum_moment;
  r.links = links;
  r.any_intact = any_intact;
}
}  // namespace face_detail

/// One step of the face law (M3–M12), as face_contact_force_scalar (face_contact.hpp), bit for bit: the N
/// segments unrolled for N known at compile time, segments 0…3 in vector lanes on the usual path.
[[gnu::always_inline]] inline FaceForce face_contact_force(const FaceLaw& law, const FaceConstants& c, const FaceKinematics& k,
                                    double inv_dt, FaceHistory& h) {
  if (law.lever == FaceLever::rotated_corner) [[unlikely]]  // (M19.r): a wall's option, the readable path
    return face_contact_force_scalar(law, c, k, inv_dt, h);
  bool first = false;
  const face_detail::SegmentInputs in = face_detail::face_inputs(law, c, k, inv_dt, h, first);
  const int n = law.segments;
  // The segment loop with N known at compile time (unrolled: no loop counter, the ξ_i at fixed
  // offsets); the resultants summed in segment order in every case.
  face_detail::SegmentSums r;
  switch (n) {
    case 1: face_detail::segments<1>(in, n, h, r); break;
    case 2: face_detail::segments<2>(in, n, h, r); break;
    case 3: face_detail::segments<3>(in, n, h, r); break;
    case 4: face_detail::segments<4>(in, n, h, r); break;
    case 5: face_detail::segments<5>(in, n, h, r); break;
    default: face_detail::segments<0>(in, n, h, r); break;
  }
  return face_detail::face_resultants(law, r, first, h);
}

}  // namespace dem
