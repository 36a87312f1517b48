// libFuzzer target: the whole text of a case file → read_case_text + check_case (what `dem2d check` does,
// without running), from memory: no file is written or read per input. Seeds: cases/**/*.toml and
// tests/lib/fixtures/*.toml; dictionary: case.dict.
#include <string_view>

#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path name = "fuzz_case.toml";  // the location every error must start with
  fuzz::check_case_text(std::string_view(reinterpret_cast<const char*>(data), size), name, {});
  return 0;
}
