#pragma once
// What the files of Simulation's step share (internal to lib/dem/core: simulation.cpp, rebuild.cpp,
// integration.cpp, contact_sweeps.cpp, parallel_step.cpp, observables.cpp): the sort key of a slot and the
// element loops of the hot path that more than one of them runs.
#include <cstddef>
#include <cstdint>

#include "dem/core/simulation.hpp"

namespace dem::step_detail {

/// The key by which every slot list and candidate list is sorted: (i, j).
inline std::uint64_t key(std::uint32_t i, std::uint32_t j) { return (std::uint64_t{i} << 32) | j; }

// Element loops of the hot path as functions of restrict-qualified parameters, so that the compiler
// vectorises them (it does not trust restrict on local pointers); integration.cpp and contact_sweeps.cpp.

/// Whether an element moved by at least √limit2 from its reference position (the rebuild test).
bool any_displaced(const double* __restrict x, const double* __restrict y, const double* __restrict xr,
                   const double* __restrict yr, double limit2, std::size_t n);
/// The first NaN, else the first largest (the order in which oversteps of successive ranges combine).
void take_worse(Simulation::Overstep& worst, const Simulation::Overstep& o);
/// The forces of a step start from the weight, f = m g (K15), both components in one pass.
void weight(double* __restrict fx, double* __restrict fy, const double* __restrict m, Vec2 g, std::size_t n);

}  // namespace dem::step_detail
