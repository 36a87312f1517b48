// The run cache of the study engine (engine/run_cache.hpp): what write_cached stores, read_cached gives
// back, including the provenance a study uses to pick the newest reused run. Planted bug that turns this
// red: the date not read back (every reused run then looks equally old).
#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "engine/run_cache.hpp"
#include "temp_dir.hpp"

TEST_CASE("run cache: an entry reads back its status, probes, speed and provenance", "[cache]") {
  const test::TempDir dir("dem2d_run_cache_");
  const auto entry = dir.path / "entry.json";
  ver::CachedRun run{"past peak", "stopped at t = 1 s", 1.5e6, {{"peak", 2.5}, {"none", std::nullopt}}, "", "", 3e-7};
  ver::write_cached(entry, run, "cases/x.toml", {"numerics.dt=1e-6"});
  const auto back = ver::read_cached(entry);
  REQUIRE(back);
  CHECK(back->status == "past peak");
  CHECK(back->message == "stopped at t = 1 s");
  CHECK(back->eps == 1.5e6);
  CHECK(back->seconds_per_step == 3e-7);
  CHECK(back->probes.at("peak") == std::optional<double>(2.5));
  CHECK_FALSE(back->probes.at("none"));
  // the provenance as written (the date is the time of writing: read from the file, not the clock again)
  const nlohmann::json p = nlohmann::json::parse(std::ifstream(entry)).at("provenance");
  REQUIRE_FALSE(p.value("date", "").empty());
  CHECK(back->date == p.value("date", ""));  // the newest reused run is picked by this (study_run.cpp)
  CHECK(back->code_version == p.value("code_version", ""));
  CHECK_FALSE(ver::read_cached(dir.path / "missing.json"));
}
