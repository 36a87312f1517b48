#pragma once
// A gap spring (a bond of stiffness k and dashpot η, breaking when its elastic force exceeds a strength)
// stretched at a constant rate v from its rest length: the force f(t) = k v t + η v while k v t ≤ strength,
// zero after (docs/references.md §8). Independent of the DEM code.

namespace ref {

/// The force a bond pulled (or sheared) at constant speed v from rest at t = 0 exerts, or 0 once broken.
double gap_pull_force(double k, double eta, double v, double t, double strength);
/// The time at which it breaks: strength/(k v).
double gap_break_time(double k, double v, double strength);

}  // namespace ref
