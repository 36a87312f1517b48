// libFuzzer target: `--set` overrides on a fixed valid case (cases/pre/block_on_slope.toml: face law,
// wall, gravity table, probes). The input is split at newlines into up to 8 override strings, each
// applied as `dem2d check CASE --set <line>` would. Seeds: fuzz/corpus/override/; dictionary: case.dict.
#include <string>
#include <vector>

#include "harness.hpp"

#ifndef DEM2D_SOURCE_DIR
#error "DEM2D_SOURCE_DIR must be defined (the repository root)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path base = std::filesystem::path(DEM2D_SOURCE_DIR) / "cases/pre/block_on_slope.toml";
  static const std::string base_text = fuzz::read_text(base);  // read once: each input is read from memory
  std::vector<std::string> overrides;
  std::string line;
  for (std::size_t k = 0; k <= size && overrides.size() < 8; ++k) {
    if (k == size || data[k] == '\n') {
      overrides.push_back(line);
      line.clear();
    } else {
      line += static_cast<char>(data[k]);
    }
  }
  fuzz::check_case_text(base_text, base, overrides);
  return 0;
}
