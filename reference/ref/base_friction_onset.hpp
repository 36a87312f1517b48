#pragma once
// When the pivot of a toppling block in a base-friction model starts to slip (refs §3.6, §3.8): the
// onset of toppling-with-sliding that Matsui's Fig. 9 shows at alpha = 60° and 75° (model.md M-C).
//
// Quasi-static, no gravity in the plane: the slope touches the block only at the pivot, so its reaction
// balances the resultant of the base-friction forces, R = -Σ_e F_e. With M21 each element's force is
// F_e = -μ_B m_e g u_e / S_e (u_e the velocity of its centre relative to the plate, S_e as in M21, the
// spin part included), so per μ_B m_e g v_B:  R = Σ_e u_e / S_e  (the frame, kinematics and rate of
// ref/base_friction_pre_face.hpp: slope = x axis descending to the left, u_e = λ ẑ x (c_e - I) - ĝ,
// λ the quasi-static rate of that model at θ). The pivot holds while R_x <= tan phi_w R_y (R_y > 0:
// the slope presses; R_x > 0: the slope holds the pivot from sliding DOWN the slope); the onset is the
// first θ with R_x / R_y = tan phi_w.
//
// The rigid block pivoting about its real corner under M21 is the model {exact, rotated_corner}
// (I = A = the corner: rate = m21_rate(alpha + θ)); the PRE model itself is {linearised, wall_frame}.
// Units SI (rad, m).

#include "ref/base_friction_pre_face.hpp"

namespace ref {

struct PivotModel {
  WallTangentialLaw law = WallTangentialLaw::linearised;
  WallLever lever = WallLever::wall_frame;
};
inline constexpr PivotModel rigid_m21_pivot{WallTangentialLaw::exact, WallLever::rotated_corner};
inline constexpr PivotModel pre_face_pivot{WallTangentialLaw::linearised, WallLever::wall_frame};

// R_x / R_y at rotation theta in [0, pi/2] (the friction the pivot needs), alpha in [0, pi/2), W/n_w =
// H/n_h. Requires the block to topple at theta (rate > 0) and R_y > 0; throws std::invalid_argument
// otherwise. Accuracy: that of the rate (~1e-13 relative) times the condition of the sum (~1e-14).
double pivot_friction_demand(double theta, double alpha, double width, double height, int n_w, int n_h,
                             PivotModel model);

// The first θ in (0, pi/2) at which pivot_friction_demand reaches tan phi_w (phi_w in (0, pi/2)):
// scanned in steps of 0.25°, then GSL Brent to 1e-10 rad; pi/2 when the pivot holds until the long face
// lands (no onset). Requires the block to topple at theta = 0.
double onset_rotation(double alpha, double wall_friction_angle, double width, double height, int n_w,
                      int n_h, PivotModel model);

// Plate travel (m) at the onset: ∫₀^θ_on dθ / rate(θ) under the same model (quadrature of
// ref/base_friction_travel.hpp, ~1e-10 relative); +inf when there is no onset.
double onset_travel(double alpha, double wall_friction_angle, double width, double height, int n_w,
                    int n_h, PivotModel model);

}  // namespace ref
