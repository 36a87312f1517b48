#pragma once
// Normal impact of a linear spring-dashpot contact with no tension (refs §1.2).
// The contact starts at overlap x(0) = 0 with approach speed v0 > 0; during contact
// m_eff x'' = -(K x + eta x'); the outgoing speed is -x'(t_c) and e = v_out / v0.

#include "ref/oscillator.hpp"

namespace ref {

// When the contact ends.
enum class ContactEnd {
  elastic_force_zero,  // convention A: the overlap (elastic force K x) returns to zero (K8)
  total_force_zero,    // convention B: the total force K x + eta x' returns to zero
};

// Coefficient of restitution as a function of the damping ratio zeta >= 0 (refs §1.2).
// A: exp(-pi zeta/sqrt(1 - zeta^2)) for zeta < 1, 0 for zeta >= 1.
// B: exp(-zeta omega0 t_c) with omega0 t_c from scaled_contact_duration.
// Accuracy: a few ulp (closed forms).
double restitution(ContactEnd end, double damping_ratio);

// omega0 t_c as a function of zeta >= 0 (refs §1.2).
// A: pi/sqrt(1 - zeta^2) for zeta < 1, +infinity for zeta >= 1.
// B: 2 acos(zeta)/sqrt(1 - zeta^2) (zeta < 1), 2 (zeta = 1), 2 acosh(zeta)/sqrt(zeta^2 - 1)
//    (zeta > 1). This single expression equals the three arctan/logarithm branches (the
//    tests check both) and has no special point at zeta = 1/sqrt(2).
// Accuracy: a few ulp.
double scaled_contact_duration(ContactEnd end, double damping_ratio);

// Contact duration t_c in seconds (+infinity for convention A with zeta >= 1). Accuracy: a few ulp.
double contact_duration(ContactEnd end, const Oscillator& contact);

struct MaximumOverlap {
  double overlap;  // m
  double time;     // s, measured from first touch
};

// Largest overlap during the impact and when it occurs (the same for both conventions: both end
// after x' = 0). omega0 t_m = g(zeta) = acos(zeta)/sqrt(1 - zeta^2) (acosh form for zeta > 1,
// 1 at zeta = 1) and x_max = (v0/omega0) exp(-zeta g(zeta)) = (v0/omega0) sqrt(e_B).
// Derived here from x(t) of refs §1.1 with x0 = 0 by setting x'(t_m) = 0. Accuracy: a few ulp.
MaximumOverlap maximum_overlap(const Oscillator& contact, double approach_speed);

struct ImpactOutcome {
  double duration;                 // s (+infinity when the end condition is never met)
  double restitution;              // -x'(t_c)/v0 (0 when the contact never ends)
  double maximum_overlap;          // m
  double time_of_maximum_overlap;  // s
};

// The impact integrated by Boost.Odeint (runge_kutta_dopri5, controlled, abs = rel = 1e-13) in
// tau = omega0 t, y = x omega0/v0, u = x'/v0, with the end condition and x' = 0 located by
// bisection on re-integrations from the start of the step in which the sign changes. Because the
// equation is linear and homogeneous the state is renormalised whenever it has decayed by half, so
// the tolerance stays relative to the current amplitude. If the end condition has not been met by
// tau = max_scaled_time, duration = +infinity and restitution = 0 (convention A, zeta >= 1).
// Independent of the closed forms; meant for cross-checking them.
// Accuracy: relative ~1e-11 in t_c, e and x_max (measured against the closed forms for
// 0 <= zeta <= 3 in steps of 0.01: at most 1.0e-12 in t_c and 8.6e-12 in e, the latter where e_A
// is tiny as zeta -> 1-).
ImpactOutcome impact_odeint(ContactEnd end, const Oscillator& contact, double approach_speed,
                            double max_scaled_time = 1000.0);

}  // namespace ref
