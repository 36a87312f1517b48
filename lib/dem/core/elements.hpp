#pragma once
// Elements stored as contiguous arrays, one per field (structure of arrays).
// Kiyama's explicit cycle (docs/model.md §1, docs/references.md §1.4) keeps, per element, the position that
// already includes the latest increment, that increment, and the velocity of the previous step.
#include <cstdint>
#include <vector>

namespace dem {

enum class Shape : std::uint8_t { disk, pre, polygon };  // PRE: pseudo-rectangle element (docs/model.md §2);
                                                        // polygon: rigid convex polygon (docs/model.md §5)
enum class Motion : std::uint8_t { free, fixed, driven };  // driven: prescribed velocity

struct Elements {
  // state
  std::vector<double> x, y, phi;     // centre [m], rotation [rad], counter-clockwise positive
  std::vector<double> dx, dy, dphi;  // increment of the current step, already in x, y, phi [m, rad]
  std::vector<double> vx, vy, omega; // velocity of the previous step v_{k-1} [m/s, rad/s]
  // forces of the current step
  std::vector<double> fx, fy, moment;  // [N, N·m]
  // properties
  std::vector<double> radius, mass, inertia, inv_mass, inv_inertia;  // [m, kg, kg·m², 1/kg, 1/(kg·m²)]
  std::vector<std::int32_t> material;  // index into the materials table
  std::vector<std::int32_t> group;     // bond group (a generated lattice), -1 for none
  std::vector<Shape> shape;
  std::vector<Motion> motion;
  std::vector<std::int32_t> drive;     // index into the velocity histories for driven elements, else -1
  std::vector<std::uint8_t> active;    // 0 once removed from the run (e.g. discharged from a silo)
  // identity
  std::vector<std::uint32_t> id;       // the element's number in the case (what outputs, probes and the
                                       // user see); its index changes when the run reorders the
                                       // elements in space (spatial_order.hpp), its id never does

  std::size_t size() const { return x.size(); }
  /// Gives back what the arrays' growth reserved beyond their size (up to half of it after push_backs),
  /// one array at a time (bench/journal.md, "Where the time and the bytes go").
  void shrink_to_fit() {
    for (auto* v : {&x, &y, &phi, &dx, &dy, &dphi, &vx, &vy, &omega, &fx, &fy, &moment, &radius, &mass, &inertia,
                    &inv_mass, &inv_inertia})
      v->shrink_to_fit();
    material.shrink_to_fit(), group.shrink_to_fit(), shape.shrink_to_fit(), motion.shrink_to_fit();
    drive.shrink_to_fit(), active.shrink_to_fit();
  }
};

}  // namespace dem
