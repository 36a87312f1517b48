#pragma once
// A uniform disk (I = ½ m r²) on a straight wall of slope α under gravity g, pressed by its weight's normal
// part N = m g cos α, with rolling resistance: an elastic–plastic rolling spring k_r and dashpot C_r on the
// disk's rotation (the wall does not turn), capped at μ_r r N with no dashpot at the cap (Ai, Chen, Rotter &
// Ooi 2011, type C), beside the contact's shear spring K_s and dashpot η_s under a Coulomb slider at μN
// (Kiyama's K10–K13). Derived in verification/rolling_resistance/README.md. Independent of the DEM code.
//
// x down the slope, v its velocity, φ the rotation (counter-clockwise positive: rolling down the slope
// is φ' = −v/r), s = x + r φ the slip of the contact point. The normal direction is at rest (N constant);
// in continuous time:
//   m v' = m g sin α − F,         F = e_s + d_s,  e_s' = K_s s' (held at ±μN while it pushes outward),
//   I φ'' = −r F + M,             M = M_k + M_d,  M_k' = −k_r φ' (held at ±μ_r r N while it pushes outward),
//   d_s = η_s s', M_d = −C_r φ' (each zero while its spring is held).
// Solved by Boost.Odeint (Dormand–Prince 5, absolute and relative tolerance 1e-12, dense output).
// Closed forms of the rigid limit (K_s, k_r → ∞; Ai et al.'s analytic cases, for a disk):
//   rolling to rest on a flat wall from v0 (pure rolling): deceleration (2/3) μ_r g, time 3 v0/(2 μ_r g),
//   distance 3 v0²/(4 μ_r g);
//   on a slope: at rest if tan α ≤ μ_r, else rolling at (2/3) g (sin α − μ_r cos α) (if μ is large enough).

namespace ref {

struct RollingDisk {
  double m;        // mass, kg (per unit thickness: kg/m)
  double r;        // radius, m
  double g;        // gravity, m/s²
  double alpha;    // slope, rad, in [0, π/2)
  double ks;       // shear spring K_s, N/m
  double eta_s;    // shear dashpot η_s, N·s/m
  double mu;       // Coulomb friction μ
  double kr;       // rolling spring k_r, N·m/rad
  double cr;       // rolling dashpot C_r, N·m·s/rad
  double mu_r;     // rolling friction μ_r
  double v0 = 0.0; // initial velocity down the slope, rolling without slip (φ'(0) = −v0/r), m/s
};

struct RollingDiskState {
  double x;       // m
  double v;       // m/s
  double omega;   // rad/s
  double moment;  // the rolling moment M on the disk, N·m
};

/// The motion at time t ≥ 0. Throws std::invalid_argument on a bad argument.
RollingDiskState rolling_disk(const RollingDisk& d, double t);

/// The rigid limit: rolling to rest on a flat wall from v0, the distance and the time (for a uniform disk).
double rolling_stop_distance(double v0, double mu_r, double g);
double rolling_stop_time(double v0, double mu_r, double g);
/// The rigid limit on a slope: the acceleration down it (0 while tan α ≤ μ_r).
double rolling_slope_acceleration(double alpha, double mu_r, double g);
/// The rigid limit's velocity down a slope α ≥ 0 from v0 ≥ 0, rolling: max(0, v0 + (2/3) g (sin α − μ_r cos α) t)
/// (it stops and stays once the moment can hold it).
double rolling_rigid_velocity(double v0, double alpha, double mu_r, double g, double t);
/// The rigid limit's initial motion from rest on a slope α (a uniform disk, I = ½ m r², friction μ, rolling
/// friction μ_r), in the block codes of refs §2.3: 0 stays (tan α ≤ μ and tan α ≤ μ_r), 1 slides without
/// turning (μ ≤ μ_r, tan α > μ), 2 rolls without slip (μ_r < tan α ≤ 3μ − 2μ_r), 3 rolls and slides
/// (tan α > max(μ_r, 3μ − 2μ_r), μ_r < μ). Derived in docs/references.md §7.4.
int rolling_disk_mode(double alpha, double mu, double mu_r);

/// A rolling spring k_r with its cap μ_r R_r e_n (R3, R4) on a disk pressed into a wall by the approach δ
/// (e_n = k_n times it) and turned statically by θ about its contact point: the centre's approach grows by
/// (r − δ)(1 − cos θ) (the rigid turn). Returns the size of the moment: min(k_r θ, μ_r R_r e_n).
double rolling_spring_moment(double kr, double kn, double mu_r, double radius, double approach, double rotation);
/// The same for a pair of disks r_i, r_j pressed together by the approach δ, disk j turned statically by θ about
/// the middle of the overlap (a_i = r_i − δ/2 from i's centre, a_j = r_j − δ/2 from j's): the centres end
/// √(a_i² + a_j² + 2 a_i a_j cos θ) apart, e_n = k_n times the overlap that leaves; the cap is μ_r R_r e_n with
/// R_r = r_i r_j/(r_i + r_j) (R1, R4).
double rolling_pair_spring_moment(double kr, double kn, double mu_r, double r_i, double r_j, double approach, double rotation);

}  // namespace ref
