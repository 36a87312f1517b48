#pragma once
// Oblique impact of a uniform disk (I = ½ m r²) on a fixed flat wall, without gravity (Chung & Ooi's
// benchmark tests 4–6 in 2D, with the linear contact of docs/model.md §1 in continuous time; derived in
// docs/references.md §1.8). Independent of the DEM code.
//
// δ is the overlap (approach positive), v_t the centre's velocity along the wall, ω the spin (counter-
// clockwise positive; the contact point is below the centre), s' = v_t + r ω the slip rate of the contact
// point. While the elastic normal force e_n = K_n δ is positive (Kiyama's K8: convention A):
//   m δ'' = −(e_n + η_n δ'),
//   m v_t' = −F,   I ω' = −r F,   F = e_s + η_s s',   e_s' = K_s s',
// the shear spring capped at |e_s| ≤ μ e_n (K13: held at the cap while its rate pushes it outward, following
// the cap as e_n changes, its dashpot off). Solved with the classic Runge–Kutta method at 40000 steps per
// normal period and a projection of e_s onto the cap after each step; the end of contact (δ = 0) found by
// linear interpolation between the last two steps.
// Closed forms used to test it: μ = 0 keeps v_t and ω; gross sliding throughout (tan θ large) gives
// m Δv_t = −μ ∫e_n dt and I Δω = −r μ ∫e_n dt, ∫e_n dt = m v_n (1 + e) with ζ = 0.

namespace ref {

struct ObliqueImpact {
  double m;      // mass, kg (per unit thickness: kg/m)
  double r;      // radius, m
  double kn;     // normal spring K_n, N/m
  double eta_n;  // normal dashpot η_n, N·s/m
  double ks;     // shear spring K_s, N/m
  double eta_s;  // shear dashpot η_s, N·s/m
  double mu;     // Coulomb friction μ
  double v;      // impact speed, m/s
  double theta;  // incidence from the wall's normal, rad, in [0, π/2)
  double omega0 = 0.0;  // initial spin, rad/s (counter-clockwise positive)
};

struct ObliqueRebound {
  double vn;        // normal velocity away from the wall after contact, m/s
  double vt;        // velocity along the wall after contact (the incoming direction positive), m/s
  double omega;     // spin after contact, rad/s
  double duration;  // contact duration, s
};

/// The rebound. Throws std::invalid_argument on a bad argument.
ObliqueRebound oblique_impact(const ObliqueImpact& d);

}  // namespace ref
