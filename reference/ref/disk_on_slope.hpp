#pragma once
// A uniform disk (I = ½ m r², K16) released at rest on a straight slope of angle α under gravity g, on
// Kiyama's contact: a tangential spring K_s and dashpot η_s (K10, K11) under a Coulomb slider that caps the
// spring force at μN (K13), N = m g cos α, μ = tan φ (K28). Derived here (verification/disk_on_slope/README.md).
// x is down the slope, v the centre's velocity, ω the spin (rolling is v = r ω).
//
// Sticking: the slip s of the contact point (v − r ω = s') carries F = K_s s + η_s s'; since a force F
// changes v − r ω at the rate g sin α − F (1/m + r²/I) = g sin α − 3F/m,
//   (m/3) s'' + η_s s' + K_s s = (m/3) g sin α,   s(0) = s'(0) = 0,
// and momentum gives v = (2/3) g sin α t + s'/3, x = (1/3) g sin α t² + s/3, r ω = v − s'.
// Sliding: from the first time t₁ at which the spring force K_s s reaches μN (never when μN exceeds the
// spring's largest force), the spring holds μN and the dashpot is off (K13.a, K13.b): v' = g (sin α − μ cos α),
// r ω' = 2 μ g cos α, and the slip keeps growing when tan φ < tan α / 3. (A rigid Coulomb contact slides
// from t = 0; the elastic stick phase leads it by O(μ g cos α/ω_s), ω_s = √(3K_s/m).)
// Accuracy: the oscillator in closed form (ref/oscillator.hpp); t₁ by bisection to ~1e-15 relative.

namespace ref {

struct DiskOnSlope {
  double m;      // mass, kg (per unit thickness: kg/m)
  double kn;     // normal stiffness of the contact, N/m; K_s = s K_n (K24)
  double s;      // K_s/K_n
  double zeta;   // η_n = 2ζ√(m K_n), η_s = η_n √s (K25)
  double alpha;  // slope, rad, in (0, π/2)
  double phi;    // friction angle, rad, in [0, π/2)
  double g;      // gravity, m/s²
};

struct DiskMotion {
  double x;          // m, down the slope from the start
  double v;          // m/s
  double spin_speed; // r ω, m/s
  bool sliding;
};

/// The motion at time t ≥ 0. Throws std::invalid_argument on a bad argument.
DiskMotion disk_on_slope(const DiskOnSlope& disk, double t);

}  // namespace ref
