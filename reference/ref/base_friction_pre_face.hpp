#pragma once
// The quasi-static rotation rate that the PRE model ITSELF implies for a rigid block of n_w x n_h
// square PREs toppling on a slope in a base-friction model (refs §3.7; model.md M2, M3, M12, M13.2,
// M15.2, M19, M21), for comparison with the M21 rate of a rigid block pivoting about its real corner
// (ref/base_friction_m21.hpp) and with exact Bray & Goodman (ref/base_friction.hpp).
//
// Frame: the slope is the x axis, descending to the LEFT; the block stands on it with its base face
// on x in [0, W], toppling counter-clockwise (θ > 0) about its down-slope corner; plate velocity
// V_B = v (-sin alpha, -cos alpha), v = |v_B|. The pivot element (bottom row, down-slope column) has
// radius r = W/(2 n_w), centre c_0 and rotation θ; element (i, j) has centre c_0 + R(θ)(2r i, 2r j).
// Its face on the slope carries two springs at the face ends (M13.2) whose positions s = r ξ, ξ = ±1,
// are measured along the WALL from the projection of c_0 (M19: element 1 = the wall, its frame does
// not turn). While the block topples, the down-slope spring (ξ = -1) carries the load and the other
// is lifted off (u(+1) = -2 r sin θ < 0: unlinked, M8). In the stiff-spring limit (P/K_n, Q/K_s ≪ r):
//  - normal (M2.1/M3.1, exact): u(-1) is the penetration of the body corner (-r, -r): the real corner
//    stays on the slope, c_0y = r (cos θ + sin θ);
//  - tangential (M15.2, linearised): Δv = Δ(translation) + r Δθ, the slip of a DISK's contact point;
//    sticking (v ≈ 0) gives c_0x = r - r θ: the block rolls like a disk of radius r, and its
//    instantaneous centre of rotation is I = c_0 + (-r (cos θ - sin θ), -r), not the corner. (With the
//    exact tangential increment (M3.2) at ξ = -1, Δv is the real corner's slip and I = the corner.)
//    The real corner drifts UP the slope by r (θ - sin θ + cos θ - 1) (linearised law).
//  - resultant (M12 with M19): the spring's P and Q act on the element with the levers of the wall
//    frame, M = -r Q + r ξ P: as a force applied at A = c_0 + (-r, -r), the corner of the UNROTATED
//    square, not at the rotated corner c_0 + R(θ)(-r, -r).
// Equilibrium of the rigid block (quasi-static, dashpots idle): the moment about A of the base-friction
// forces (M21, each at its element centre, plus the spin moments) vanishes. With λ = Ω/v (> 0 while
// toppling), u_e = λ ẑ x (c_e - I) - ĝ, S_e = sqrt(|u_e|² + (λ r)²):
//   G(λ) = Σ_e [ ((c_e - A) x u_e)_z + (2/3) r² λ ] / S_e = 0,                     (M21, M12)
// and dθ/dδ_B = λ. At θ = 0, I = A = the corner and G = -F21 of base_friction_m21 (same rate); as
// r -> 0 both points tend to the corner and the rate to Bray & Goodman's. Units SI (m, rad, 1/m).

namespace ref {

enum class WallTangentialLaw { linearised, exact };  // (M15.2) or (M3.2) at the pivot spring

// Where the pivot spring's P and Q act: at the face end of the WALL frame, A = c_0 + (-r, -r) (M12 with
// M19, what the model and lib/ do), or at the ROTATED body corner c_0 + R(θ)(-r, -r) (a face-end rule
// that follows the corner; not in the paper). With WallTangentialLaw::exact and rotated_corner, I = A =
// the real corner and the rate is the rigid block's M21 rate (ref/base_friction_m21.hpp) at psi = alpha + θ.
enum class WallLever { wall_frame, rotated_corner };

// G(λ; theta, alpha) (m³: each term times the element area s² and a length; same normalisation as
// m21_moment), for lambda >= 0, theta in [0, pi/2], alpha in [0, pi/2). Requires W/n_w = H/n_h (square elements).
double pre_face_moment(double lambda, double theta, double alpha, double width, double height,
                       int n_w, int n_h, WallTangentialLaw law = WallTangentialLaw::linearised,
                       WallLever lever = WallLever::wall_frame);

// dθ/dδ_B = λ (rad/m, >= 0): 0 when G(0) >= 0 (the base-friction resultant passes up-slope of A: no
// toppling), else the root in (0, λ_hi], λ_hi = 2^k / H doubled until G(λ_hi) > 0, by GSL Brent to a
// relative 1e-13. The unit tests check that the bracket holds one sign change.
double pre_face_rate(double theta, double alpha, double width, double height, int n_w, int n_h,
                     WallTangentialLaw law = WallTangentialLaw::linearised,
                     WallLever lever = WallLever::wall_frame);

// θ (rad) at plate travel delta_B (m) under pre_face_rate, from θ(0) = 0 (Odeint dopri5, as
// theta_at_travels of ref/base_friction_travel.hpp), capped at pi/2.
double theta_at_travel_pre_face(double travel, double alpha, double width, double height, int n_w,
                                int n_h, WallTangentialLaw law = WallTangentialLaw::linearised,
                                WallLever lever = WallLever::wall_frame);

}  // namespace ref
