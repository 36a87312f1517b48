// Only files dem2d wrote are ever removed (lib/dem/run/owned_files.hpp): a new run into the same --out
// refuses when a user put a file of their own into o/vtk/ or o/pictures/ (it was deleted silently), and
// `study --fresh` refuses a foreign file in DIR/cache/; the folder is left as it was. Snapshots, pictures,
// cache entries and their temporaries are recognised by name.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "dem/run/output_files.hpp"
#include "dem/run/owned_files.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

TEST_CASE("A run into an output folder refuses a user's file in vtk/ or pictures/ and removes nothing", "[outputs]") {
  const dem::Case c = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"), {"numerics.duration=0.031"});
  const fs::path out = test::fresh_dir("dem2d_unit_owned_files", "run");
  dem::RunOptions o;
  o.out_dir = out;
  REQUIRE(dem::run_case(c, o).status == "completed");
  REQUIRE(fs::exists(out / "vtk" / "snapshot_000003000.vtp"));
  CHECK(dem::run_case(c, o).status == "completed");  // dem2d's own files: cleared, the run goes on
  for (const char* foreign : {"vtk/my_mesh.vtu", "pictures/figure1.png"}) {
    INFO(foreign);
    fs::create_directories((out / foreign).parent_path());
    std::ofstream(out / foreign) << "mine";
    CHECK_THROWS_WITH(dem::run_case(c, o), Contains(fs::path(foreign).filename().string()) && Contains("did not write"));
    CHECK(fs::exists(out / foreign));
    CHECK(fs::exists(out / "summary.json"));  // nothing removed
    fs::remove(out / foreign);
  }
}

TEST_CASE("study --fresh removes a cache of entries only and refuses anything else in it", "[outputs]") {
  const fs::path cache = test::fresh_dir("dem2d_unit_owned_files", "cache");
  fs::create_directories(cache);
  std::ofstream(cache / "0123456789abcdef.json") << "{}";
  std::ofstream(cache / "0123456789abcdef.json.1234-5.tmp") << "{";
  std::ofstream(cache / "notes.txt") << "mine";
  CHECK_THROWS_WITH(dem::remove_owned_folder(cache, dem::OwnedFolder::study_cache, "--fresh"),
                    Contains("notes.txt") && Contains("did not write"));
  CHECK(fs::exists(cache / "0123456789abcdef.json"));
  fs::remove(cache / "notes.txt");
  dem::remove_owned_folder(cache, dem::OwnedFolder::study_cache, "--fresh");
  CHECK_FALSE(fs::exists(cache));
}

TEST_CASE("dem2d's own names are recognised with their temporaries and nothing else is", "[outputs]") {
  CHECK(dem::is_numbered_name("snapshot_000003000.vtp", "snapshot_", 9, ".vtp"));
  CHECK(dem::is_numbered_name("snapshot_000003000.vtp.77-3.tmp", "snapshot_", 9, ".vtp"));
  CHECK_FALSE(dem::is_numbered_name("snapshot_3000.vtp", "snapshot_", 9, ".vtp"));
  CHECK_FALSE(dem::is_numbered_name("snapshot_00000300x.vtp", "snapshot_", 9, ".vtp"));
  CHECK_FALSE(dem::is_numbered_name("my_mesh.vtu", "snapshot_", 9, ".vtp"));
  CHECK_FALSE(dem::is_numbered_name(".vtp", "snapshot_", 9, ".vtp"));
  CHECK(dem::is_numbered_name("00ff00ff00ff00ff.json", "", 16, ".json", true));
  CHECK_FALSE(dem::is_numbered_name("notes.json", "", 16, ".json", true));
}
