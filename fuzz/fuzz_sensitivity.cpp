// libFuzzer target: sensitivity files (verification/engine/sensitivity.hpp, `dem2d sweep`). The input is a
// sensitivity.toml, read and checked (keys, parameter ranges against the base case) as `dem2d sweep` does
// before any run; placed like fuzz_study's input so that "../../cases/…" reaches the base case. Accepted:
// nothing thrown, or an error whose message names the file's line ("file:line: …"). Anything else is a
// finding. Seeds: fuzz/corpus/sensitivity/.
#include <string>
#include <string_view>

#include "engine/sensitivity.hpp"
#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = fuzz::scratch_beside_cases("sensitivity.toml");
  fuzz::write_file(file, data, size);
  try {
    ver::check_sensitivity_file(file);
  } catch (const std::runtime_error& e) {
    const std::string_view msg = e.what();
    // located: at the file's line, in front ("file:line: …") or behind ("file not found: … (from file:line)")
    if (msg.find(file.string() + ":") == std::string_view::npos && !msg.starts_with("--set "))
      fuzz::finding("error without the sensitivity file: " + std::string(msg));
    if (msg.starts_with(file.string() + ":0:")) fuzz::finding("error at line 0: " + std::string(msg));
  } catch (const std::exception& e) {
    fuzz::finding(std::string("exception other than a located error: ") + e.what());
  }
  return 0;
}
