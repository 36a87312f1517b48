// libFuzzer target: checkpoints (lib/dem/run/checkpoint.hpp, checkpoint_checks.hpp). The input is a
// checkpoint without its last 8 bytes; the target appends the checksum, so every mutation reaches the
// field checks instead of stopping at "checksum mismatch" — a crafted file, as a user could make one. It
// is restored as `dem2d run --restart` restores it (tests/lib/fixtures/restart_disks.toml: parse_checkpoint,
// restore_simulation, restore_loop_state) and stepped 20 times with the run's kinematic blow-up stop; the
// case's own checks (check_case, a second under ASan: its guard) are made once, not per input.
// Accepted: a run, or a dem::OutputError / dem::CaseError that names the checkpoint file. Anything else is a
// finding (another exception, a crash, a sanitizer report). Seed: fuzz/corpus/checkpoint/ (the case at
// step 4000, with contacts); regression/checkpoint/: the crafted checkpoints of the unit tests.
#include <string>
#include <string_view>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/loop_state.hpp"
#include "dem/run/output_files.hpp"
#include "harness.hpp"

#ifndef DEM2D_SOURCE_DIR
#error "DEM2D_SOURCE_DIR must be defined (the repository root)"
#endif

using fuzz::finding;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const dem::Case base = [] {
    dem::Case c = dem::read_case(std::filesystem::path(DEM2D_SOURCE_DIR) / "tests/lib/fixtures/restart_disks.toml");
    (void)dem::check_case(c);
    return c;
  }();
  const std::string file = "fuzz_checkpoint.bin";
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::uint64_t sum = dem::checkpoint_checksum(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  auto names_file = [&](const char* kind, const std::exception& e) {
    if (std::string_view(e.what()).find(file) == std::string_view::npos)
      finding(std::string(kind) + " that does not name the checkpoint file: " + e.what());
  };
  try {
    const dem::Checkpoint ck = dem::parse_checkpoint(bytes, file);
    dem::Simulation sim(dem::Model(base.model));
    dem::restore_simulation(sim, ck, false);
    dem::LoopState loop;
    std::vector<dem::ProbeState> probes(base.probes.size());
    dem::restore_loop_state(ck.loop, loop, probes, ck.file);
    for (int k = 0; k < 20 && sim.overstep().index == dem::Simulation::Overstep::npos; ++k) sim.step();
    (void)sim.energies();
  } catch (const dem::OutputError& e) {
    names_file("OutputError", e);
  } catch (const dem::CaseError& e) {
    names_file("CaseError", e);
  } catch (const std::exception& e) {
    finding(std::string("exception other than OutputError / CaseError: ") + e.what());
  }
  return 0;
}
