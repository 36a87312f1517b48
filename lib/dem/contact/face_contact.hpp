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

struct FaceLaw {
  int segments = 1;                                    // N
  SegmentPositions positions = SegmentPositions::centres;
  NormalIncrement normal = NormalIncrement::linearised;
  TangentialIncrement tangential = TangentialIncrement::linearised;
  double tensile_strength = 0.0;  // σ_t [Pa]
  double cohesion = 0.0;          // c [Pa]
  double tan_phi = 0.0;           // tan φ
  bool healing = false;           // a re-formed link regains σ_t and c
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
};

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
  double p_moment = 0.0; // Σ a ξ_i P(i) [N·m]: M1 = −r1 Q + p_moment, M2 = −r2 Q − p_moment
  int links = 0;         // segments linked after the step
  bool any_tensile = false;  // a linked segment still has tensile strength
};

/// Segment position ξ_i, i = 0..N−1 (M13.1 / M13.2).
inline double segment_xi(SegmentPositions pos, int n, int i) {
  if (pos == SegmentPositions::ends) return i == 0 ? -1.0 : 1.0;  // (M13.2), N = 2
  return (2.0 * (i + 1) - 1.0 - n) / n;                              // (M13.1)
}

/// Starts a contact: every segment gets the same initial normal displacement u0 (the overlap, or the
/// first increment), and links if u0 >= 0. `bonded`: the links start intact (tensile strength and
/// cohesion); otherwise they start as broken-and-re-formed links (compression and friction only,
/// unless healing).
/// `geometric`: the contact starts from the geometric state (present at t = 0, or the overlap onset):
/// the first step's tangential increment does not load the shear springs (it drives the dashpots).
void start_face(const FaceLaw& law, const FaceConstants& c, double u0, bool bonded, bool geometric,
                FaceHistory& h);

/// One step of the face law (M3–M12). Updates the history and returns the resultants.
FaceForce face_contact_force(const FaceLaw& law, const FaceConstants& c, const FaceKinematics& k,
                             double inv_dt, FaceHistory& h);

}  // namespace dem
