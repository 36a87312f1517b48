#pragma once
// A checkpoint's state checked field by field before a Simulation takes it (checkpoint.cpp), as a case is:
// a checksum only proves the file was not damaged, not that it was written by dem2d. Indices within
// their tables (elements, walls, laws of the right kind), flags 0 or 1, every number finite, lists of
// the lengths the case implies and sorted as the rebuild's merge expects. Every error is a CaseError (an input
// error, exit status 2) "FILE: corrupt checkpoint (FIELD: what)".
#include <cstddef>
#include <string>
#include <vector>

#include "dem/contact/contact_slots.hpp"
#include "dem/core/model.hpp"
#include "dem/core/neighbour_search.hpp"

namespace dem {

struct Checkpoint;

[[noreturn]] void corrupt_checkpoint(const std::string& file, const std::string& field, const std::string& what);

/// The header: step ≥ 0, a finite clock ≥ 0, a finite Δt > 0.
void check_checkpoint_header(const Checkpoint& ck);
/// A byte that stores a flag: 0 or 1.
void check_flag(const std::string& file, const std::string& field, unsigned value);
/// Finite numbers (an index names the element of a list).
void check_finite(const std::string& file, const std::string& field, double v);
void check_finite(const std::string& file, const std::string& field, const std::vector<double>& v);

/// The elements' state (positions, increments, velocities, forces) and their `active` flags.
void check_element_state(const std::string& file, const Elements& e);
/// The walls' end points, increments and forces.
void check_wall_state(const std::string& file, const std::vector<Wall>& walls);
/// Candidate pairs: i < j < n, sorted by (i, j).
void check_candidates(const std::string& file, const std::vector<CandidatePair>& c, std::size_t n);
/// Contact slots: element (and wall) indices, the law's index and kind (`laws`: false for a checkpoint taken
/// as the start of another case, whose slots take that case's laws afterwards), flags, finite numbers, sorted.
void check_slots(const std::string& file, const LinearPairSlots& s, const Model& m, bool laws);
void check_slots(const std::string& file, const std::vector<LinearSlot>& s, const Model& m, bool laws);  // wall slots
void check_slots(const std::string& file, const std::vector<FaceSlot>& s, const Model& m, bool walls, bool laws);
/// The neighbour list's reference positions: n elements, one per wall, finite.
void check_references(const std::string& file, const std::vector<double>& x_ref, const std::vector<double>& y_ref,
                      const std::vector<Vec2>& wall_ref, std::size_t n, std::size_t n_walls);

}  // namespace dem
