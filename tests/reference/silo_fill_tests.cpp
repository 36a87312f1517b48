// Ordered silo fills as built (ref/silo_fill.hpp, refs §6.1): rows, disks and fill heights of the table
// for s = 12 … 19, the weight, and Janssen per wall contact (the contacts' bands tile the wall).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "ref/registry.hpp"
#include "ref/silo_fill.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("silo fill: rows and disks nearest 350 and the fill heights of the refs 6.1 table", "[silo]") {
  struct Row { int s, rows; long disks; double height_cm; };
  const Row table[] = {{12, 30, 345, 31.24}, {13, 28, 350, 34.99}, {14, 26, 351, 36.13}, {15, 24, 348, 35.79},
                       {16, 23, 357, 36.05}, {17, 21, 347, 34.19}, {18, 20, 350, 33.51}, {19, 19, 352, 32.58}};
  for (const Row& r : table) {
    CAPTURE(r.s);
    const ref::OrderedFill f = ref::ordered_fill(r.s, 0.40, 0.01, 350);
    CHECK(f.rows == r.rows);
    CHECK(f.count == r.disks);
    CHECK_THAT(f.height * 100.0, WithinAbs(r.height_cm, 6e-3));  // the table's two decimals
    CHECK(ref::evaluate("silo.fill_height", {{"s", r.s}, {"B", 0.40}, {"r", 0.01}, {"count", 350}}) == f.height);
    CHECK(ref::evaluate("silo.area_fraction", {{"s", r.s}, {"B", 0.40}, {"r", 0.01}}) == f.packing.area_fraction);
    const double w = ref::evaluate("silo.fill_weight", {{"s", r.s}, {"B", 0.4}, {"r", 0.01}, {"count", 350}, {"rho", 2650.0}, {"g", 9.80665}});
    CHECK_THAT(w, WithinRel(r.disks * 2650.0 * std::numbers::pi * 1e-4 * 9.80665, 1e-14));
  }
  // a tie goes to the fewer rows: s = 3 gives 3, 5, 8, 10 disks; 9 lies between 8 and 10
  CHECK(ref::ordered_fill(3, 0.08, 0.01, 9).rows == 3);
  CHECK(ref::ordered_fill(3, 0.08, 0.01, 10).rows == 4);
  CHECK_THROWS(ref::ordered_fill(12, 0.40, 0.01, 0));
  CHECK_THROWS(ref::ordered_fill(18, 0.40, 0.01, 350).wall_contact_height(10));  // 20 rows: 10 contacts, k < 10
}

TEST_CASE("silo fill: Janssen per wall contact tiles the wall and is sigma_h x 2 d_y inside", "[silo]") {
  const double rho = 2650.0, g = 9.80665, mu = std::tan(10.0 * std::numbers::pi / 180.0);
  for (int s : {12, 18, 19}) {
    CAPTURE(s);
    const ref::OrderedFill f = ref::ordered_fill(s, 0.40, 0.01, 350);
    const double rho_b = rho * f.packing.area_fraction;
    double sum = 0.0;
    for (int k = 0; k < f.wall_contacts(); ++k) sum += ref::janssen_wall_contact(k, f, rho, g, mu);
    CHECK_THAT(sum, WithinRel(ref::janssen_wall_force(0.0, f.height, rho_b, g, 0.40, f.packing.k_geom, mu), 1e-12));
    // an interior contact: the band average of sigma_h is sigma_h at the centre to O(d_y^2 sigma_h'')
    const int k = f.wall_contacts() / 2;
    const double z = f.height - f.wall_contact_height(k);
    const double point = ref::janssen_contact_force(z, f, rho, g, mu);
    CHECK_THAT(ref::janssen_wall_contact(k, f, rho, g, mu), WithinRel(point, 1e-3));
    CHECK_THAT(point, WithinRel(ref::janssen_horizontal_stress(z, rho_b, g, 0.40, f.packing.k_geom, mu) * 2.0 * f.packing.dy, 1e-14));
    CHECK(ref::evaluate("silo.janssen_wall_contact", {{"k", k}, {"s", s}, {"B", 0.4}, {"r", 0.01}, {"count", 350},
                                                      {"rho", rho}, {"g", g}, {"mu_w", mu}}) ==
          ref::janssen_wall_contact(k, f, rho, g, mu));
  }
  // refs 6.1: 17/18 at 20 cm depth, sigma_h = 1879.6 Pa, contacts every 2 d_y = 3.3172 cm: 62.35 N/m
  const ref::OrderedFill f18 = ref::ordered_fill(18, 0.40, 0.01, 350);
  CHECK_THAT(ref::janssen_contact_force(0.20, f18, rho, g, mu), WithinRel(1879.6 * 0.033172, 2e-4));
}
