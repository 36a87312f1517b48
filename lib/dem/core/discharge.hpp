#pragma once
// A silo's discharge (K §5(2), refs §6.2): the slit is a wall opened for the run (Wall::open), disks
// whose centre falls more than `outlet_depth` below the slit (along g) are removed from the run (their
// `active` flag cleared, never renumbered; they keep their last position), and a stalled arch can be
// broken as Kiyama & Fujimura did, by removing its keystone.
#include <cstddef>
#include <cstdint>
#include <optional>

namespace dem {

struct Model;

struct Discharge {
  bool enabled = false;
  std::int32_t slit = -1;       // the wall that is the slit (opened: no contacts)
  double outlet_depth = 0.0;    // outlet line: this far below the slit's mid-point along g [m]
  double keystone_after = 0.0;  // arch breaker: no disk out for this long → remove the keystone [s]; 0: never
  double open_at = 0.0;         // the slit opens at this time [s] (0: open from the start); removals and the
                                // arch breaker's clock start then
};

/// How far below the outlet line, along g, the point (x, y) lies [m] (> 0: below it).
double below_outlet(const Model& m, double x, double y);

/// Whether an active element may lie below the outlet line (a cheap test that never misses one: false means
/// remove_discharged would remove nothing), so a caller can skip taking the model mutable.
bool may_discharge(const Model& m);

/// Removes (active = 0) every active element whose centre lies below the outlet line. Returns how many.
std::size_t remove_discharged(Model& m);

/// The elements removed below the outlet line so far (inactive, centre below the line), and their mass
/// [kg]: exact, since a removed element no longer moves.
struct Discharged {
  std::size_t count = 0;
  double mass = 0.0;
};
Discharged discharged(const Model& m);

/// The keystone of a stalled arch: among the active elements whose centre lies over the slit (its
/// projection on the slit falls between the slit's ends) and above the outlet line, the one nearest
/// the slit's mid-point (ties: the lower id, Elements::id). None if no element is over the slit.
std::optional<std::size_t> keystone(const Model& m);

}  // namespace dem
