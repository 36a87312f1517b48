// libFuzzer target: the whole text of a case file → read_case + check_case (what `dem2d check` does,
// without running). Seeds: cases/**/*.toml and tests/lib/fixtures/*.toml; dictionary: case.dict.
#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::write_file(fuzz::scratch_file(), data, size);
  fuzz::check_case_file(fuzz::scratch_file(), {});
  return 0;
}
