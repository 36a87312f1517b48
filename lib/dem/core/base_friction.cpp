#include "dem/core/base_friction.hpp"

#include <algorithm>

namespace dem {

namespace {

double friction_of(const BasePlate& plate, std::int32_t material) {
  const auto k = static_cast<std::size_t>(material);
  return k < plate.friction.size() ? plate.friction[k] : 0.0;
}

}  // namespace

BaseFrictionRates base_friction_rates(const BasePlate& plate, const Elements& e, std::size_t i) {
  const double mu = plate.enabled ? friction_of(plate, e.material[i]) : 0.0;
  if (!(mu > 0.0)) return {};
  const double g = plate.normal_gravity, v_eps = plate.regularisation_speed;
  return {base_friction_rate(mu, g, v_eps),
          base_friction_rotational_rate(mu, g, v_eps, e.mass[i], e.radius[i], e.inertia[i])};
}

double max_base_friction_rate(const BasePlate& plate, const Elements& e) {
  double rate = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i] || e.motion[i] != Motion::free) continue;
    const BaseFrictionRates r = base_friction_rates(plate, e, i);
    rate = std::max({rate, r.translation, r.rotation});
  }
  return rate;
}

Vec2 plate_velocity(const BasePlate& plate, const std::vector<VelocityHistory>& drives, double t) {
  return plate.drive >= 0 ? drives[static_cast<std::size_t>(plate.drive)].at(t) : plate.velocity;
}

void add_base_friction(Elements& e, const BasePlate& plate, Vec2 v_plate) {
  const double g = plate.normal_gravity, v_eps = plate.regularisation_speed;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i] || e.motion[i] != Motion::free) continue;
    const double mu = friction_of(plate, e.material[i]);
    if (mu == 0.0) continue;
    const BaseFrictionForce f = base_friction_force(mu, e.mass[i], e.radius[i], g, v_eps,
                                                    Vec2{e.vx[i] - v_plate.x, e.vy[i] - v_plate.y}, e.omega[i]);
    e.fx[i] += f.fx;
    e.fy[i] += f.fy;
    e.moment[i] += f.moment;
  }
}

}  // namespace dem
