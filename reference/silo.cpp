// Silo references (refs §6), see ref/silo.hpp.
#include "ref/silo.hpp"

#include <cmath>
#include <numbers>

#include "ref/require.hpp"

namespace ref {

OrderedPacking ordered_packing(int s, double width, double radius) {
  detail::require_positive("ref::ordered_packing", "radius", radius);
  detail::require_positive("ref::ordered_packing", "width", width);
  if (s < 2) detail::fail("ref::ordered_packing", "s must be at least 2", s);
  OrderedPacking p{};
  p.dx = (width - 2.0 * radius) / (s - 1);
  const double dy2 = 4.0 * radius * radius - 0.25 * p.dx * p.dx;
  if (!(p.dx >= 2.0 * radius) || !(dy2 > 0.0)) detail::fail("ref::ordered_packing", "no (s-1)/s packing for this s", s);
  p.dy = std::sqrt(dy2);
  p.k_geom = 0.25 * p.dx * p.dx / dy2;
  p.area_fraction = (2.0 * s - 1.0) * std::numbers::pi * radius * radius / (2.0 * width * p.dy);
  return p;
}

double janssen_horizontal_stress(double z, double rho, double g, double b, double k, double mu) {
  detail::require_positive("ref::janssen", "width", b);
  detail::require_positive("ref::janssen", "K", k);
  if (z < 0.0) detail::fail("ref::janssen", "depth must be >= 0", z);
  if (mu <= 0.0) return k * rho * g * z;  // no wall friction: hydrostatic with K
  const double z0 = b / (2.0 * k * mu);
  return rho * g * b / (2.0 * mu) * -std::expm1(-z / z0);
}

double janssen_vertical_stress(double z, double rho, double g, double b, double k, double mu) {
  return janssen_horizontal_stress(z, rho, g, b, k, mu) / k;
}

double janssen_wall_force(double z1, double z2, double rho, double g, double b, double k, double mu) {
  if (!(z2 >= z1) || z1 < 0.0) detail::fail("ref::janssen_wall_force", "need 0 <= z1 <= z2", z1);
  detail::require_positive("ref::janssen_wall_force", "K", k);
  if (mu <= 0.0) return 0.5 * k * rho * g * (z2 * z2 - z1 * z1);
  const double z0 = b / (2.0 * k * mu);
  // ∫₀^z (1 − e^{−t/z₀}) dt = z₀ f(z/z₀), f(x) = x − 1 + e^{−x}; the series for small x avoids the
  // cancellation of x and 1 − e^{−x} (weak wall friction: z₀ ≫ z)
  auto f = [](double x) {
    if (x < 1e-3) return x * x * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0 - x / 120.0)));
    return x + std::expm1(-x);
  };
  return rho * g * b / (2.0 * mu) * z0 * (f(z2 / z0) - f(z1 / z0));
}

double beverloo_2d(double c, double rho, double g, double slot, double k, double d) {
  const double open = slot - k * d;
  if (open <= 0.0) return 0.0;
  return c * rho * std::sqrt(g) * std::pow(open, 1.5);
}

}  // namespace ref
