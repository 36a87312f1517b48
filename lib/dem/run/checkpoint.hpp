#pragma once
// Checkpoints: the complete state of a Simulation (positions, increments, velocities, rotations,
// forces, every contact slot with its history — segment links, accumulated springs, contact frame
// rotations —, wall positions and increments, the neighbour list's reference positions, step counter
// and clock; drives read the clock, there is no random number generator) plus the run loop's own state
// (probes, the energy bound), in a versioned binary file with the hash of the case it belongs to and a
// checksum. Restoring it into a Simulation of the same case continues bit for bit like the
// uninterrupted run.
//
// Format (little-endian host order, checked by a marker): "DEM2D-CHECKPOINT\n", u32 version, u32
// 0x01020304, strings (u64 length + bytes) case hash, case path, meta (JSON: case, overrides,
// provenance), i64 step, f64 time,
// f64 dt, then the state sections (checkpoint.cpp, write_state), the run loop numbers (u64 count +
// f64s), and an FNV-1a 64 checksum of everything before it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"

namespace dem {

inline constexpr std::uint32_t kCheckpointVersion = 6;  // 6: rolling states (R1–R6); 2: the run loop's discharge state; 3: element ids (order);
                                                          // 4: linear pair slots without ContactForce::opened;
                                                          // 5: the base plate's displacement and travel

struct Checkpoint {
  std::string file;          // the checkpoint file it was read from (what errors name)
  std::string case_hash, case_path;
  nlohmann::json meta;       // {case, overrides, provenance (code version, date, machine, ...)}
  std::int64_t step = 0;
  double time = 0.0, dt = 0.0;
  std::string state;         // the Simulation's state, serialised (restore_simulation reads it)
  std::vector<double> loop;  // the run loop's state (loop_state.hpp)
};

/// The hash of what determines a run's state: the resolved case without its `output` table and
/// `numerics.duration` (a restart may write other outputs and run longer).
std::string case_hash(const Case& c);

/// Serialises the complete state of `sim` (atomic write: file.tmp, then rename). Throws OutputError.
void write_checkpoint(const std::filesystem::path& file, const Simulation& sim, const Case& c,
                      const std::vector<double>& loop);

/// Reads and validates (magic, version, byte order, checksum, the header's numbers) a checkpoint. Throws
/// CaseError naming the file: a checkpoint is an input (exit status 2, as a wrong case).
Checkpoint read_checkpoint(const std::filesystem::path& file);
/// The same from the file's bytes (`file` only names it in errors).
Checkpoint parse_checkpoint(std::string_view bytes, const std::string& file);
/// The FNV-1a 64 checksum a checkpoint ends with, of the bytes before it (tests and fuzz targets craft
/// checkpoints with it).
std::uint64_t checkpoint_checksum(std::string_view bytes);

/// Restores the state into `sim`, built from the case to continue; every field is checked (indices,
/// flags, finiteness: checkpoint_checks.hpp) before the Simulation uses it, and errors name ck.file. `other_case`: the checkpoint comes
/// from another case (a checkpoint as the start of a new case): element count, wall count and Δt must
/// match; each contact slot takes the new case's law for its material pair (the constants fixed when
/// the contact formed are kept), masses and laws are the new case's. Throws CaseError if they do not
/// match.
/// `into` names the case restarted (its file, where numerics.dt is given): a count, Δt or law that does not
/// match names the checkpoint file and the case's file (file:line of the key at fault where there is one).
struct RestartInto {
  std::string case_file;    // the case file restarted from the checkpoint ("" : not named)
  std::string dt_location;  // "file:line" (or "--set …") of its numerics.dt; "" : the default
};
void restore_simulation(Simulation& sim, const Checkpoint& ck, bool other_case, const RestartInto& into = {});

/// The serialised state alone (tests compare two states bit for bit with it).
std::string simulation_state(const Simulation& sim);

}  // namespace dem
