// A restore rebuilds the contact index (lib/dem/run/checkpoint.cpp, Simulation::index_contacts): on
// several threads every element sums its slots through that index, and a fresh Simulation's index
// belongs to its own t = 0 slot lists, not to the checkpoint's. Restored into a fresh Simulation on 2
// threads, a state whose slot lists differ from t = 0's must continue bit for bit, including the steps
// before the next neighbour-list rebuild (which would remake the index anyway). Planted bug that turned
// this red (mutant g728335-015): the restore without index_contacts() (differs at the first step from the
// checkpoint at step 5000).
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "dem/run/checkpoint.hpp"

#include "../test_support.hpp"

namespace {

dem::Simulation on_two_threads(const dem::Model& m) {
  dem::Simulation s(m);
  s.set_threads(2, 1, false);  // one element per thread at least: the threaded sums (the index) run
  return s;
}

}  // namespace

TEST_CASE("A restored state continues bit for bit on 2 threads before any rebuild", "[restart][checkpoint][threads]") {
  const dem::Case c = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"));
  const auto dir = test::fresh_dir("dem2d_checkpoint_index", "ck");
  std::filesystem::create_directories(dir);
  dem::Simulation a(c.model);  // the uninterrupted run: one thread (any number gives the same bits)
  const std::size_t contacts0 = a.contact_count();
  int restored_without_rebuild = 0, restored_other_contacts = 0;
  for (int stop : {5000, 7500}) {
    while (a.steps() < stop) a.step();
    const auto file = dir / ("at" + std::to_string(stop) + ".bin");
    dem::write_checkpoint(file, a, c, {});
    dem::Simulation b = on_two_threads(c.model);
    dem::restore_simulation(b, dem::read_checkpoint(file), false);
    REQUIRE(dem::simulation_state(b) == dem::simulation_state(a));
    if (a.contact_count() != contacts0) ++restored_other_contacts;
    const std::int64_t rebuilds0 = b.rebuilds();
    for (int k = 0; k < 20; ++k) {
      a.step();
      b.step();
      if (k == 0 && b.rebuilds() == rebuilds0) ++restored_without_rebuild;
      CAPTURE(stop, k);
      REQUIRE(dem::simulation_state(b) == dem::simulation_state(a));
    }
  }
  // the property was tested where it matters: a first step on the restored index, other slots than t = 0's
  CHECK(restored_without_rebuild > 0);
  CHECK(restored_other_contacts > 0);
}
