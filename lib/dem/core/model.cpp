#include "dem/core/model.hpp"

#include <algorithm>
#include <cmath>

#include "dem/core/corner_contacts.hpp"

#include <numbers>
#include <stdexcept>

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
  if (!m.polygon_of.empty()) m.polygon_of.push_back(-1);
  return e.size() - 1;
}

std::size_t add_polygon(Model& m, std::int32_t material, const std::vector<Vec2>& vertices, Vec2 position,
                        Vec2 velocity, double omega, double mass_override) {
  if (const std::string why = polygon_problem(vertices); !why.empty()) throw std::invalid_argument(why);
  const PolygonProperties p = polygon_properties(vertices);  // (P1)
  const double rho = m.materials.at(static_cast<std::size_t>(material)).density, l = m.thickness;
  double mass = rho * p.area * l, inertia = rho * p.polar * l;  // (P2)
  if (mass_override > 0.0) {
    inertia = p.polar / p.area * mass_override;  // the same shape, uniform density
    mass = mass_override;
  }
  const std::size_t i = add_element(m, Shape::polygon, material, p.circumradius, position + p.centroid, velocity, omega);
  m.polygon_of.resize(m.elements.size(), -1);
  m.polygon_of[i] = static_cast<std::int32_t>(m.polygons.size());
  m.polygons.push_back(centred_shape(vertices));
  Elements& e = m.elements;
  e.mass[i] = mass, e.inertia[i] = inertia;
  e.inv_mass[i] = 1.0 / mass, e.inv_inertia[i] = 1.0 / inertia;
  return i;
}

void element_corners(const Model& m, std::size_t i, std::vector<Vec2>& out) {
  const Elements& e = m.elements;
  const PolygonShape& s = m.polygons[static_cast<std::size_t>(m.polygon_of[i])];
  const double c = std::cos(e.phi[i]), sn = std::sin(e.phi[i]);
  out.resize(s.vertices.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = world_vertex(s, k, e.x[i], e.y[i], c, sn);  // (P3)
}

std::vector<Vec2> element_corners(const Model& m, std::size_t i) {
  std::vector<Vec2> out;
  element_corners(m, i, out);
  return out;
}

namespace {
double deepest(const std::vector<CornerHit>& hits) {
  double d = -1.0;
  for (const CornerHit& h : hits) d = std::max(d, h.depth);
  return d;
}
}  // namespace

double element_overlap(const Model& m, std::size_t i, std::size_t j) {
  const Elements& e = m.elements;
  const bool pi = e.shape[i] == Shape::polygon, pj = e.shape[j] == Shape::polygon;
  if (!pi && !pj) return e.radius[i] + e.radius[j] - std::hypot(e.x[j] - e.x[i], e.y[j] - e.y[i]);
  if (!pi) std::swap(i, j);
  std::vector<CornerHit> hits;
  if (pi && pj) polygon_pair_hits(element_corners(m, i), element_corners(m, j), hits);
  else polygon_disk_hits(element_corners(m, i), {e.x[j], e.y[j]}, e.radius[j], hits);
  return deepest(hits);
}

double wall_overlap(const Model& m, std::size_t i, const Wall& w) {
  const Elements& e = m.elements;
  const Vec2 c{e.x[i], e.y[i]};
  if (e.shape[i] != Shape::polygon) return e.radius[i] - norm(closest_point(w, c) - c);
  std::vector<CornerHit> hits;
  polygon_wall_hits(element_corners(m, i), c, w.a, w.kind == WallKind::point ? w.a : w.b, w.kind == WallKind::point, hits);
  return deepest(hits);
}

}  // namespace dem
