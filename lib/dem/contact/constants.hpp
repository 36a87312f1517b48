#pragma once
// Helpers for contact constants (docs/model.md §1 "Constants", §2 (M25.l), docs/references.md §1.2, §5).

namespace dem {

/// Kiyama's 2D elastic contact stiffness of two equal cylinders (K22, K23), per unit thickness [Pa]:
/// b² = (8/π)(r/2)((1−ν²)/E) q  (contact half-width, K22.b, r₁ = r₂ = r), and
/// K_n = πE / (2(1−ν²)(c + 2 ln(4r/b)))  with c = 1.5 as printed in K23 (c = 2/3 from K22.a).
/// K_n depends on the line load q [N/m] through b; Table 1 of the paper is reproduced with
/// q = 0.068 kgf/cm and c = 1.5 (docs/references.md §5.2).
double hertz_2d_stiffness(double youngs_modulus, double poisson, double radius, double line_load,
                          double c = 1.5);

/// Critical damping of one mass on one spring (K20): η = 2√(mK).
double critical_damping(double mass, double stiffness);

/// Coefficient of restitution of a linear spring–dashpot contact that ends when the elastic force
/// returns to zero (convention A, Kiyama's K8): e = exp(−πζ/√(1−ζ²)), 0 for ζ ≥ 1.
double restitution_from_damping_ratio(double zeta);
/// Inverse of the above: ζ = −ln e / √(π² + ln² e).
double damping_ratio_from_restitution(double e);

/// Square-lattice constants from E, ν (M25.l, the second (25) of the paper):
/// k_n = (1−ν)E/((1+ν)(1−2ν)), k_s = (1−2ν)k_n/(2(1−ν)) [Pa].
double lattice_kn(double youngs_modulus, double poisson);
double lattice_ks(double youngs_modulus, double poisson);

/// Matsui's single-pair time-step bound (M26), Δt < h_n √(m / K) with K the whole face's normal
/// stiffness N·K_n (the paper prints k_n, a stiffness per unit area: docs/model.md §2). It bounds one pair
/// only; a bonded lattice needs the assembly bound of stability.hpp (docs/references.md §4.6).
double pre_pair_time_step(double damping_ratio, double mass, double face_stiffness);

}  // namespace dem
