// Simulation::wall_contact_forces: a wall's contacts one by one (a silo's wall-force profile per contact,
// refs §6.1), with the same geometry and signs as wall_band_force (observables.cpp).
#include "dem/core/simulation.hpp"

namespace dem {

std::vector<Simulation::WallContactForce> Simulation::wall_contact_forces(std::uint32_t w) const {
  const Wall& wall = m_.walls[w];
  const Vec2 ab = wall.b - wall.a;
  const double len = wall.kind == WallKind::segment ? norm(ab) : 0.0;
  const Vec2 along = len > 0.0 ? ab * (1.0 / len) : Vec2{0.0, 0.0};
  const Elements& e = m_.elements;
  std::vector<WallContactForce> out;
  auto add = [&](std::uint32_t i, std::uint32_t j, std::uint8_t touching, double nx, double ny, double fn, double fs) {
    if (j != w || !touching) return;
    const Vec2 n{nx, ny}, t{-ny, nx};                              // n from the element towards the wall
    const Vec2 point = closest_point(wall, Vec2{e.x[i], e.y[i]});  // where the element touches it
    const double s = len > 0.0 ? dot(point - wall.a, along) : 0.0;
    out.push_back({s, point, fn, dot(n * fn + t * fs, along)});   // compression positive; on the wall along a→b
  };
  for (const auto& c : linear_walls_) add(c.i, c.j, c.touching, c.nx, c.ny, c.f.fn, c.f.fs);
  for (const auto& c : face_walls_) add(c.i, c.j, c.touching, c.nx, c.ny, c.f.p, c.f.q);
  for (const PolygonSlot& p : polygon_walls_) {  // a polygon's contact points, each where it is (P6)
    if (p.j != w) continue;
    for (const CornerSlot& c : p.corners) {
      const Vec2 n{c.nx, c.ny}, t{-c.ny, c.nx}, point = closest_point(wall, Vec2{c.px, c.py});
      const double s = len > 0.0 ? dot(point - wall.a, along) : 0.0;
      out.push_back({s, point, c.f.fn, dot(n * c.f.fn + t * c.f.fs, along)});
    }
  }
  return out;
}

}  // namespace dem
