#include "dem/core/model.hpp"

#include <numbers>

namespace dem {

std::size_t add_element(Model& m, Shape shape, std::int32_t material, double radius, Vec2 position,
                        Vec2 velocity, double omega, PreMass pre_mass, double mass_override) {
  Elements& e = m.elements;
  const double rho = m.materials.at(static_cast<std::size_t>(material)).density;
  const double l = m.thickness;
  double mass = 0.0, inertia = 0.0;
  const bool square = shape == Shape::pre && pre_mass == PreMass::square;
  if (square) {
    mass = 4.0 * radius * radius * l * rho;  // (M17)
    inertia = (2.0 / 3.0) * radius * radius * mass;
  } else {
    mass = std::numbers::pi * radius * radius * l * rho;  // (M18), Kiyama's disk
    inertia = 0.5 * radius * radius * mass;  // Kiyama's I = ρπr⁴/2 per unit thickness (K16)
  }
  if (mass_override > 0.0) {
    // the inertia of the given mass in the same shape: scaled if the density gave a mass (as
    // before, bit for bit), else from the shape's factor (a material without density)
    if (mass > 0.0) inertia *= mass_override / mass;
    else inertia = (square ? 2.0 / 3.0 : 0.5) * radius * radius * mass_override;
    mass = mass_override;
  }
  e.x.push_back(position.x);
  e.y.push_back(position.y);
  e.phi.push_back(0.0);
  e.dx.push_back(0.0);
  e.dy.push_back(0.0);
  e.dphi.push_back(0.0);
  e.vx.push_back(velocity.x);
  e.vy.push_back(velocity.y);
  e.omega.push_back(omega);
  e.fx.push_back(0.0);
  e.fy.push_back(0.0);
  e.moment.push_back(0.0);
  e.radius.push_back(radius);
  e.mass.push_back(mass);
  e.inertia.push_back(inertia);
  e.inv_mass.push_back(1.0 / mass);        // ü = X/m, v̈ = Y/m (K16) are formed with 1/m and 1/I
  e.inv_inertia.push_back(1.0 / inertia);  // φ̈ = M/I (K16)
  e.material.push_back(material);
  e.group.push_back(-1);
  e.shape.push_back(shape);
  e.motion.push_back(Motion::free);
  e.drive.push_back(-1);
  e.active.push_back(1);
  e.id.push_back(static_cast<std::uint32_t>(e.size() - 1));
  return e.size() - 1;
}

}  // namespace dem
