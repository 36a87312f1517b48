// libFuzzer target: study files (verification/engine/study_file.hpp, `dem2d study`). The input is a
// study.toml, read as `dem2d study` reads it before anything runs; it lies two folders below a scratch
// root whose cases/ is the repository's, so the seeds' "../../cases/…" reach their base cases. Accepted:
// a study, or a dem::CaseError located at the file ("file:line: …" or "file: …"). Anything else is a
// finding. Seeds: fuzz/corpus/study/ (small study files of each kind).
#include <string>
#include <string_view>

#include "dem/cases/case_file.hpp"
#include "engine/study_file.hpp"
#include "harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = fuzz::scratch_beside_cases("study.toml");
  fuzz::write_file(file, data, size);
  try {
    (void)ver::read_study(file);
  } catch (const dem::CaseError& e) {
    const std::string_view msg = e.what();
    if (!msg.starts_with(file.string() + ":")) fuzz::finding("CaseError without the study file: " + std::string(msg));
    if (msg.starts_with(file.string() + ":0:")) fuzz::finding("CaseError at line 0: " + std::string(msg));
  } catch (const std::exception& e) {
    fuzz::finding(std::string("exception other than dem::CaseError: ") + e.what());
  }
  return 0;
}
