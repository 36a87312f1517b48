// Kiyama's ordered silo fills as built and Janssen per wall contact (refs §6.1), see ref/silo_fill.hpp.
#include "ref/silo_fill.hpp"

#include <algorithm>
#include <cstdlib>

#include "ref/require.hpp"

namespace ref {

namespace {
long disks_in(int s, int rows) { return static_cast<long>((rows + 1) / 2) * s + static_cast<long>(rows / 2) * (s - 1); }
}  // namespace

OrderedFill ordered_fill(int s, double width, double radius, long target) {
  if (target < 1 || target > 100000000) detail::fail("ref::ordered_fill", "target count must be in [1, 1e8]", target);
  OrderedFill f;
  f.packing = ordered_packing(s, width, radius);  // refuses an s without an (s−1)/s packing
  f.s = s;
  f.radius = radius;
  f.width = width;
  // The count grows by s or s − 1 per row: the nearest count lies at the first row count reaching the
  // target or the one before it.
  int rows = 1;
  while (disks_in(s, rows) < target) ++rows;
  if (rows > 1 && target - disks_in(s, rows - 1) <= disks_in(s, rows) - target) --rows;  // a tie: fewer rows
  f.rows = rows;
  f.count = disks_in(s, rows);
  f.height = 2.0 * radius + (rows - 1) * f.packing.dy;
  return f;
}

double OrderedFill::wall_contact_height(int k) const {
  if (k < 0 || k >= wall_contacts()) detail::fail("ref::OrderedFill", "no such wall contact (k from 0, the bottom)", k);
  return radius + 2.0 * k * packing.dy;
}

double janssen_contact_force(double z, const OrderedFill& f, double rho, double g, double mu_w) {
  detail::require_positive("ref::janssen_contact_force", "rho", rho);
  const double rho_b = rho * f.packing.area_fraction;
  return janssen_horizontal_stress(z, rho_b, g, f.width, f.packing.k_geom, mu_w) * 2.0 * f.packing.dy;
}

double janssen_wall_contact(int k, const OrderedFill& f, double rho, double g, double mu_w) {
  detail::require_positive("ref::janssen_wall_contact", "rho", rho);
  const double y = f.wall_contact_height(k);
  // the top wall contact carries the rest up to the fill top (a top row of s − 1 does not touch the walls)
  const double y_low = std::max(0.0, y - f.packing.dy);
  const double y_high = k + 1 == f.wall_contacts() ? f.height : std::min(f.height, y + f.packing.dy);
  return janssen_wall_force(f.height - y_high, f.height - y_low, rho * f.packing.area_fraction, g, f.width,
                            f.packing.k_geom, mu_w);
}

}  // namespace ref
