// A run that fails once its output folder is open (lib/dem/run/run_outputs.hpp, record_failure) leaves
// summary.json saying "failed" with the message, not "running" (what a run killed by SIGKILL leaves).
#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

TEST_CASE("A run stopped by a write error records status failed with the message in summary.json", "[outputs]") {
  const dem::Case c = dem::read_case(test::source("cases/impact/disk_wall.toml"));
  const fs::path out = test::fresh_dir("dem2d_unit_run_failure", "full");
  dem::RunOptions o;
  o.out_dir = out;
  // A file size limit of 8 kB (SIGXFSZ ignored): the 13 kB series fails, the small summary still fits.
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit old{};
  getrlimit(RLIMIT_FSIZE, &old);
  rlimit small = old;
  small.rlim_cur = 8 * 1024;
  setrlimit(RLIMIT_FSIZE, &small);
  std::string what;
  try {
    dem::run_case(c, o);
  } catch (const dem::OutputError& e) {
    what = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  REQUIRE_THAT(what, Contains("write failed"));
  const auto summary = nlohmann::json::parse(test::slurp(out / "summary.json"));
  CHECK(summary["status"] == "failed");
  CHECK_THAT(summary.value("message", ""), Contains("write failed"));
}
