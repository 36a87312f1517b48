// libFuzzer target: study files (verification/engine/study_file.hpp, `dem2d study`). The input is a
// study.toml, read as `dem2d study` reads it before anything runs; it lies two folders below a scratch
// root whose cases/ is the repository's, so the seeds' "../../cases/…" reach their base cases. Accepted:
// a study, or a dem::CaseError located at the file ("file:line: …" or "file: …") or at a variant's override
// ("--set …"). Anything else is a
// finding. Seeds: fuzz/corpus/study/ (small study files of each kind).
#include <stdexcept>
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
    // "--set …": an override a study variant gives its case, refused by the case reader as on the command line
    // (it names the override, not the study file's line: the strict-readers issue)
    // and "file not found: … (from file:line)" names the line behind
    if (msg.find(file.string() + ":") == std::string_view::npos && !msg.starts_with("--set "))
      fuzz::finding("CaseError without the study file: " + std::string(msg));
    if (msg.starts_with(file.string() + ":0:")) fuzz::finding("CaseError at line 0: " + std::string(msg));
  } catch (const std::runtime_error& e) {
    // the study reader's own refusals (e.g. a refinement study without [refinement]) are runtime_errors that
    // name the file but not always a line (exit status 2 all the same): the strict-readers issue
    if (!std::string_view(e.what()).starts_with(file.string() + ":"))
      fuzz::finding(std::string("error without the study file: ") + e.what());
  } catch (const std::exception& e) {
    fuzz::finding(std::string("exception other than a located error: ") + e.what());
  }
  return 0;
}
