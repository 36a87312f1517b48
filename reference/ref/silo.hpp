#pragma once
// Silo references (refs §6): Janssen's wall stress in a plane (slot) silo of width B, the lateral
// ratio K_geom of Kiyama's ordered (s−1)/s packings, and the 2D Beverloo flow rate. SI, per unit
// thickness. Independent of lib/.

namespace ref {

/// Geometry of the (s−1)/s packing of equal disks (radius r) in a box of width B with the rows of s
/// touching both walls (refs §6.1): d_x = (B − 2r)/(s − 1), d_y = √(4r² − d_x²/4).
struct OrderedPacking {
  double dx, dy;
  double k_geom;        ///< tan²θ_c = (d_x/2)²/d_y² (frictionless, forces along the contact directions)
  double area_fraction; ///< φ_A = (2s − 1)πr²/(2 B d_y): the disks of two rows over the box width (refs §6.1)
};
OrderedPacking ordered_packing(int s, double width, double radius);

/// Janssen's horizontal wall stress at depth z below the free surface (refs §6.1):
/// σ_h(z) = (ρ_b g B/(2μ_w)) (1 − e^{−z/z₀}), z₀ = B/(2Kμ_w). With μ_w → 0 it tends to K ρ_b g z.
double janssen_horizontal_stress(double z, double bulk_density, double g, double width, double k, double mu_w);

/// Janssen's vertical stress σ_v = σ_h / K.
double janssen_vertical_stress(double z, double bulk_density, double g, double width, double k, double mu_w);

/// Horizontal wall force per unit thickness on a wall band z₁ ≤ z ≤ z₂ (the integral of σ_h):
/// (ρ_b g B/(2μ_w)) [ (z₂ − z₁) − z₀ (e^{−z₁/z₀} − e^{−z₂/z₀}) ].
double janssen_wall_force(double z1, double z2, double bulk_density, double g, double width, double k, double mu_w);

/// 2D Beverloo mass flow rate per unit thickness through a slot of width D (refs §6.2):
/// W = C ρ_b √g (D − k d)^{3/2}; 0 when D ≤ k d.
double beverloo_2d(double c, double bulk_density, double g, double slot, double k, double grain_diameter);

}  // namespace ref
