// Kiyama's 2D elastic cylinder contact (refs §5.1, K22-K23).
#include "ref/elastic_contact_2d.hpp"

#include <cmath>
#include <numbers>

#include "ref/require.hpp"

namespace ref {

namespace {

void validate(const char* where, const CylinderContact& c) {
  detail::require_positive(where, "youngs_modulus", c.youngs_modulus);
  detail::require_finite(where, "poisson_ratio", c.poisson_ratio);
  if (!(c.poisson_ratio >= 0.0 && c.poisson_ratio < 0.5))
    detail::fail(where, "poisson_ratio must lie in [0, 0.5)", c.poisson_ratio);
  detail::require_positive(where, "radius1", c.radius1);
  detail::require_positive(where, "radius2", c.radius2);
  detail::require_positive(where, "line_load", c.line_load);
  detail::require_finite(where, "approach_constant", c.approach_constant);
}

}  // namespace

double contact_half_width(const CylinderContact& contact) {
  validate("ref::contact_half_width", contact);
  const double nu = contact.poisson_ratio;
  const double reduced_radius =
      contact.radius1 * contact.radius2 / (contact.radius1 + contact.radius2);
  return std::sqrt(8.0 / std::numbers::pi * reduced_radius * (1.0 - nu * nu) /
                   contact.youngs_modulus * contact.line_load);  // (K22.b)
}

double cylinder_approach(const CylinderContact& contact) {
  constexpr const char* where = "ref::cylinder_approach";
  validate(where, contact);
  const double b = contact_half_width(contact);
  const double nu = contact.poisson_ratio;
  const double bracket = contact.approach_constant + std::log(4.0 * contact.radius1 / b) +
                         std::log(4.0 * contact.radius2 / b);
  if (!(bracket > 0.0))
    detail::fail(where, "c + ln(4 r1/b) + ln(4 r2/b) must be > 0 (load too large for the model)",
                 bracket);
  return 2.0 * (1.0 - nu * nu) / std::numbers::pi * contact.line_load / contact.youngs_modulus *
         bracket;  // (K22.a)
}

double contact_stiffness(const CylinderContact& contact) {
  return contact.line_load / cylinder_approach(contact);  // (K23)
}

}  // namespace ref
