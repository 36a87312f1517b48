#pragma once
// Rigid rectangular block resting on an incline (refs §2): sliding from rest (M20), the
// static classification of Goodman & Bray (1976), Sagaseta's (1986) dynamic classification of the
// initial motion from rest, its boundary angles and the initial accelerations of each mode.
// Angles in radians: alpha = slope angle, phi = friction angle of the base (tan phi = mu).
// beta = b/h: base length along the slope over height.

#include <optional>

namespace ref {

enum class Mode {
  stable = 0,
  slide = 1,
  topple = 2,
  slide_topple = 3,
};

// '.', 'S', 'T', 'X' as in the mode map of refs §2.
char mode_code(Mode mode);

// a = g (sin alpha - cos alpha tan phi) = g cos alpha (tan alpha - tan phi)  (M20), signed:
// a <= 0 means friction holds the block. Accuracy: a few ulp.
double sliding_acceleration(double alpha, double phi, double g);

// delta(t) = a t^2/2 for a block sliding from rest with full base contact (M20); 0 when a <= 0
// (the block stays at rest). Accuracy: a few ulp.
double slide_distance(double alpha, double phi, double g, double t);

// Goodman & Bray (refs §2.2): stable, slide, topple or slide + topple from tan alpha against tan
// phi and beta. Exact comparisons.
Mode mode_goodman_bray(double alpha, double phi, double beta);

// T(alpha, beta) = [(4 beta^2 + 1) tan alpha + 3 beta] / [3 beta tan alpha + beta^2 + 4]
// (refs §2.3): the friction coefficient needed for pure toppling about the down-slope corner
// without slip. Accuracy: a few ulp.
double toppling_friction_threshold(double alpha, double beta);

// Sagaseta's classification of the motion from rest (refs §2.3):
//   stable if tan alpha <= tan phi and tan alpha <= beta; else slide if tan alpha > tan phi and
//   beta >= tan phi; else topple if tan phi >= T(alpha, beta); else slide + topple.
Mode mode_sagaseta(double alpha, double phi, double beta);

// Boundary angles (refs §2.3), radians: alpha_s = phi, alpha_t = atan(beta), and alpha_ST where
// T(alpha_ST, beta) = tan phi: tan alpha_ST = [tan phi (beta^2 + 4) - 3 beta] /
// [(4 beta^2 + 1) - 3 beta tan phi]; none when beta >= tan phi (pure sliding takes over) or when
// the denominator is <= 0 (no slide + topple below 90 degrees). Accuracy: a few ulp.
double sliding_angle(double phi);
double toppling_angle(double beta);
std::optional<double> slide_topple_angle(double phi, double beta);

// Initial motion from rest in the mode of mode_sagaseta (refs §2.3, derived there and re-derived
// here). Slope coordinates: s down-slope, n outward normal; pivot O = down-slope lower corner.
struct InitialMotion {
  Mode mode;
  double slide_acceleration;  // m/s^2, down-slope acceleration of the block (slide) or of the
                              // pivot O (slide + topple); 0 for stable and topple
  double
      angular_acceleration;   // rad/s^2, toppling (down-slope tipping) positive; 0 unless toppling
  double normal_force_ratio;  // N/(m g): normal reaction of the slope (at O when toppling)
  double friction_force_ratio;  // F/(m g): friction of the slope, positive down-slope
};

// base = b (m, along the slope), height = h (m), g > 0. Accuracy: a few ulp.
//   stable:       N/mg = cos alpha, F/mg = -sin alpha.
//   slide:        a = g(sin alpha - cos alpha tan phi), N/mg = cos alpha, F/mg = -tan phi cos
//   alpha. topple:       theta'' = (3g/2)(h sin alpha - b cos alpha)/(b^2 + h^2) (I_O = m(b^2 +
//   h^2)/3);
//                 N/mg = [3bh sin alpha + (b^2 + 4h^2) cos alpha]/[4(b^2 + h^2)];
//                 F/mg = -[(4b^2 + h^2) sin alpha + 3bh cos alpha]/[4(b^2 + h^2)].
//   slide+topple: theta'' = 6g cos alpha (h tan phi - b)/(4b^2 + h^2 - 3bh tan phi);
//                 N = m(g cos alpha + theta'' b/2); F = -tan phi N;
//                 a_O = g sin alpha - tan phi N/m - theta'' h/2.
InitialMotion initial_motion(double alpha, double phi, double base, double height, double g);

}  // namespace ref
