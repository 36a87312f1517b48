#pragma once
// Kiyama's ordered (s−1)/s silo fills as built (refs §6.1): the row count nearest a disk count, the fill
// height, the weight, the heights of the wall contacts, and Janssen's force on one wall contact with
// K = K_geom of the packing and ρ_b = ρ φ_A. SI, per unit thickness. Independent of lib/ (its own row
// count and geometry; the DEM's generator is lib/dem/cases/generators.hpp).
#include "ref/silo.hpp"

namespace ref {

/// An (s−1)/s fill of equal disks (radius r) touching, no gaps, in a box of width B: rows alternate s
/// (the bottom row) and s − 1 disks; the rows of s touch both walls.
struct OrderedFill {
  OrderedPacking packing;  ///< d_x, d_y, K_geom, φ_A
  int s = 0;
  int rows = 0;
  long count = 0;          ///< disks: ⌈rows/2⌉ s + ⌊rows/2⌋ (s − 1)
  double height = 0.0;     ///< 2r + (rows − 1) d_y: floor to the top of the top row [m]
  double radius = 0.0;
  double width = 0.0;      ///< B [m]
  int wall_contacts() const { return (rows + 1) / 2; }  ///< per side wall: the rows of s
  /// Height above the floor of the k-th wall contact from the bottom (k = 0: the bottom row): r + 2k d_y.
  double wall_contact_height(int k) const;
};

/// The fill whose disk count is nearest `target` (ties: the fewer rows), refs §6.1 "about 350".
OrderedFill ordered_fill(int s, double width, double radius, long target);

/// Janssen's force on one wall contact at depth z below the fill top (refs §6.1): σ_h(z) × 2 d_y × 1 m,
/// with K = K_geom and ρ_b = ρ φ_A of the packing (the contacts of one wall are 2 d_y apart) [N/m].
double janssen_contact_force(double z, const OrderedFill& f, double rho, double g, double mu_w);

/// Janssen's force on the k-th wall contact from the bottom, integrated over the band the contact
/// carries: half-way to its neighbours (y_k ± d_y), from the floor for k = 0 and up to the fill top for the
/// top one, so that the bands of all contacts tile 0 ≤ z ≤ H [N/m].
double janssen_wall_contact(int k, const OrderedFill& f, double rho, double g, double mu_w);

}  // namespace ref
