// Every test process gets a temporary folder of its own: TMPDIR is pointed at a fresh mkdtemp folder
// before any test runs, so std::filesystem::temp_directory_path() (test_support.hpp's fresh_dir and
// write_temp, engine/temp_dir.hpp, every fixed "<tmp>/dem2d_unit_…" group) differs between processes.
// Two ctest runs at once (two clones, or ctest -j) cannot remove or overwrite each other's files; a
// discharge test once failed that way. The folder is removed when the process ends, unless
// DEM2D_TEST_KEEP_TMPDIR is set (then its path is printed: to look at what a test wrote).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace {

struct ProcessTmpdir {
  std::filesystem::path dir;
  ProcessTmpdir() {
    std::error_code ec;
    const std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    std::string pattern = ((ec ? std::filesystem::path("/tmp") : base) / "dem2d_test_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) return;  // keep the system's TMPDIR
    dir = pattern;
    ::setenv("TMPDIR", pattern.c_str(), 1);
  }
  ~ProcessTmpdir() {
    if (dir.empty()) return;
    if (std::getenv("DEM2D_TEST_KEEP_TMPDIR") != nullptr) {
      std::fprintf(stderr, "kept the test's temporary folder %s\n", dir.c_str());
      return;
    }
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
  ProcessTmpdir(const ProcessTmpdir&) = delete;
  ProcessTmpdir& operator=(const ProcessTmpdir&) = delete;
};

const ProcessTmpdir kProcessTmpdir;

}  // namespace
