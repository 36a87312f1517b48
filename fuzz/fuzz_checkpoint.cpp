// libFuzzer target: checkpoints (lib/dem/run/checkpoint.hpp, checkpoint_checks.hpp). The input is a
// checkpoint without its last 8 bytes; the target appends the checksum, so every mutation reaches the
// field checks instead of stopping at "checksum mismatch" — a crafted file, as a user could make one. It
// is restarted as `dem2d run --restart` would (tests/lib/fixtures/restart_disks.toml, 20 steps past
// the seed checkpoint (step 4000), no output folder). Accepted: a run, or a dem::OutputError / dem::CaseError
// that names the checkpoint file. Anything else is a finding (another exception, a crash, a sanitizer
// report). Seed: fuzz/corpus/checkpoint/ (the case at step 4000, with contacts).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "dem/cases/case_file.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"
#include "harness.hpp"

#ifndef DEM2D_SOURCE_DIR
#error "DEM2D_SOURCE_DIR must be defined (the repository root)"
#endif

using fuzz::finding;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const dem::Case base = dem::read_case(std::filesystem::path(DEM2D_SOURCE_DIR) / "tests/lib/fixtures/restart_disks.toml",
                                               {"numerics.duration=0.0402", "output.vtk=false"});
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::uint64_t sum = dem::checkpoint_checksum(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  const std::filesystem::path file = fuzz::scratch_file().string() + ".ckpt";
  fuzz::write_file(file, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  dem::RunOptions o;
  o.restart = file;
  try {
    (void)dem::run_case(base, o);
  } catch (const dem::OutputError& e) {
    if (std::string_view(e.what()).find(file.string()) == std::string_view::npos)
      finding(std::string("checkpoint error that does not name the file: ") + e.what());
  } catch (const dem::CaseError& e) {
    if (std::string_view(e.what()).find(file.string()) == std::string_view::npos)
      finding(std::string("case error that does not name the checkpoint: ") + e.what());
  } catch (const std::exception& e) {
    finding(std::string("exception other than OutputError / CaseError: ") + e.what());
  }
  std::remove(file.c_str());
  return 0;
}
