#pragma once
// Kiyama's 2D contact stiffness of two parallel elastic cylinders of equal E and nu, pressed
// together by a line load q (refs §5, K22-K23). SI: E in Pa, q in N/m, radii in m; the stiffness
// K_n = q/delta is per unit length and has the units of E.

namespace ref {

// The constant in the approach bracket (c + ln(4 r1/b) + ln(4 r2/b)). refs §5.1: K22.a prints 2/3,
// K23 prints 1.5; they disagree. 1.5 with q = 0.068 kgf/cm reproduces Kiyama's Table 1.
inline constexpr double kiyama_constant_K23 = 1.5;
inline constexpr double kiyama_constant_K22a = 2.0 / 3.0;

struct CylinderContact {
  double youngs_modulus;  // E, Pa
  double poisson_ratio;   // nu, in [0, 0.5)
  double radius1;         // r1, m
  double radius2;         // r2, m
  double line_load;       // q, N/m (force per unit length of the cylinders)
  double approach_constant = kiyama_constant_K23;  // c, dimensionless
};

// Half-width b of the contact strip (K22.b): b^2 = (8/pi) (r1 r2/(r1 + r2)) ((1 - nu^2)/E) q.
// Accuracy: a few ulp.
double contact_half_width(const CylinderContact& contact);

// Approach of the centres (K22.a with constant c): delta = (2(1 - nu^2)/pi)(q/E)(c + ln(4 r1/b) +
// ln(4 r2/b)). Throws if the bracket is not positive (b > 4r: a load far outside the model's
// range). Accuracy: a few ulp.
double cylinder_approach(const CylinderContact& contact);

// Secant normal stiffness K_n = q/delta (K23; for r1 = r2 = r:
// pi E / (2(1 - nu^2)(c + 2 ln(4r/b)))). Accuracy: a few ulp.
double contact_stiffness(const CylinderContact& contact);

}  // namespace ref
