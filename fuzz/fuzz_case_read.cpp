// libFuzzer target: the whole text of a case file → read_case_text alone (the reader: TOML, keys, units,
// generators, extents), from memory. fuzz_case adds check_case, whose time-step guard (the arrangement
// search of core/stability.cpp) takes most of a second per input under ASan + coverage; without it the
// reader is fuzzed at thousands of inputs a second. Seeds and dictionary as fuzz_case.
#include <string_view>

#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path name = "fuzz_case_read.toml";  // the location every error must start with
  fuzz::read_case_text(std::string_view(reinterpret_cast<const char*>(data), size), name);
  return 0;
}
