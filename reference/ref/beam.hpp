#pragma once
// Elastic beam theory for a simply supported beam of span L under a central point load P (three-point
// bending, case M-D), and what a square PRE lattice of that beam really is (refs §4).
//
// Section: width b (the out-of-plane thickness l of the 2D model) × depth h. I = b h³/12, A = b h.
//  - Euler–Bernoulli:  δ_b = P L³/(48 E I)                         (refs §4.1)
//  - Timoshenko adds the shear deflection of two half-spans, each carrying P/2 over L/2:
//                       δ_s = P L/(4 κ G A)                         (refs §4.1)
//    κ: shear coefficient of a rectangle. 5/6 is the value of a parabolic shear-stress profile (exact
//    for ν = 0, the lattice's ν); Cowper's 10(1+ν)/(12+11ν) is offered for the continuum.
//  - Peak load from the flexural strength σ_t: σ = M c/I = 3PL/(2bh²) ⇒ P_max = 2σ_t b h²/(3L).
// Assumptions: linear elasticity, small deflection, plane sections; L/h = 2.5 for M-D is a deep beam
// (shear is 45 % of the compliance) and the load and support indentation is not included, so beam
// theory is indicative there, and a DEM comparison must say which deflection it measures.
//
// The square PRE lattice (refs §4.3, derived from the stored energy of the face springs under a
// uniform strain, elements turning with the rigid-body rotation): C11 = C22 = k_n, C12 = 0,
// C66 = k_s/2, so E_eff = k_n, ν_eff = 0, G_eff = k_s/2 (k_n, k_s: stress per unit strain, M4–M6).
// Its discrete faces carry the bending moment with N springs: at segment centres (M13.1) the midpoint
// rule gives I_eff = I (1 − 1/(n_h N)²) for n_h element rows; at the face ends (M13.2, N = 2)
// I_eff = I (1 + 2/n_h²) (refs §4.3).
// First crack (refs §4.4): the outermost spring, at y_max = h/2 − r/N (centres) or h/2 (ends), breaks
// when k_n ε = σ_t: P₁/P_max = (I_eff/I)·(h/2)/y_max = 1 + 1/(n_h N) (centres), 1 + 2/n_h² (ends).
// An estimate for trends and bands, not a tight reference (refs §4.4 lists what shifts it).
// Accuracy: closed forms, exact to rounding.

namespace ref {

struct BeamSection {
  double width;  // b, out-of-plane thickness [m]
  double depth;  // h [m]
  double span;   // L, between the supports [m]
};

double second_moment(const BeamSection& s);  // I = b h³/12 [m⁴]

double euler_bernoulli_stiffness(const BeamSection& s, double young);  // 48 E I / L³ [N/m]

double shear_coefficient_parabolic();              // κ = 5/6
double shear_coefficient_cowper(double poisson);   // κ = 10(1+ν)/(12+11ν)

// P/δ with bending and shear deflection; bending_moment_factor multiplies I (1 for the continuum,
// I_eff/I for a lattice).
double timoshenko_stiffness(const BeamSection& s, double young, double shear_modulus, double kappa,
                            double bending_moment_factor = 1.0);

double flexural_peak_load(const BeamSection& s, double tensile_strength);  // 2σ_t b h²/(3L) [N]

// Square PRE lattice: effective moduli from the face spring constants (stress per unit strain).
struct LatticeModuli {
  double young;          // E_eff = k_n [Pa]
  double shear_modulus;  // G_eff = k_s/2 [Pa]
  double poisson;        // ν_eff = 0
};
LatticeModuli square_lattice_moduli(double kn, double ks);

enum class SegmentPositions { centres, face_ends };

// I_eff / I for n_h element rows across the depth with N segments per face.
double lattice_bending_factor(int rows, int segments, SegmentPositions where);

// First-crack load over P_max (beam-theory estimate, refs §4.4).
double lattice_first_crack_ratio(int rows, int segments, SegmentPositions where);

// Mid-span deflection of a beam resting on two linear support springs of stiffness k_c each (the
// support contacts): each carries P/2, so δ = P/k_beam + P/(2 k_c) and P/δ is returned [N/m].
// Exact for linear springs whose line of action is vertical (the beam's settlement is rigid).
double stiffness_on_support_springs(double beam_stiffness, double support_stiffness);

// Square PRE lattice beam (refs §4.3): Timoshenko with E_eff = k_n, G_eff = k_s/2, κ = 5/6 and
// I_eff = I · lattice_bending_factor(rows, segments, where) [N/m]. k_n, k_s per unit strain [Pa].
double lattice_beam_stiffness(const BeamSection& s, double kn, double ks, int rows, int segments,
                              SegmentPositions where);

// First-crack load of the lattice loaded by a disk of radius R resting in the groove between the two
// top cores at mid-span (cores of radius r = h/(2 n_h), centres at x = ±r, y = h − r), derived here
// by statics and beam theory. Without friction the two contact forces act along the lines of centres,
// at θ from the vertical, sin θ = r/(r + R): the disk wedges the two half-beams apart with
//   H = (P/2) tan θ  at the contact height y_p = h − r + r cos θ.
// At mid-span the section carries the tension H and the moment M = P L/4 − H (y_p − h/2), so the
// outermost bottom spring (y_max below the axis, refs §4.4) breaks when
//   σ_t = M y_max / I_eff + H / A   ⇒   P₁ = σ_t / [(L/4 − t e) y_max/I_eff + t/A],  t = tan θ/2,
// e = y_p − h/2. The wedge lowers the moment more than the tension adds, so it RAISES the peak:
// × 1.239 for 2 × 8 (r = 10 mm, R = 5 mm), × 1.129 for 6 × 24, × 1.086 for 10 × 40.
// Friction at the disk (φ = 5° in M-D) would lower H by up to tan(θ − φ)/tan θ; not included.
// CAUTION, measured (verification/beam_peak_load/README.md): the DEM does not follow this on 6 × 24
// and 10 × 40. With frictionless contacts their peaks are 1.032 and 0.981 P_max, at or below the plain
// estimate (1.033, 1.020), not × 1.13 / × 1.09 above it: the thrust acts across the mid-span face
// itself, where beam theory (Saint-Venant) does not hold. Kept as a tested, rejected hypothesis; the
// studies use lattice_first_crack_ratio.
double groove_first_crack_load(const BeamSection& s, double tensile_strength, int rows, int segments,
                               SegmentPositions where, double load_disk_radius);

}  // namespace ref
