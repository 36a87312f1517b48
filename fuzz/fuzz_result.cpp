// libFuzzer target: result.json as `dem2d report` reads it (reports/study_result.hpp, report.hpp). The
// input is one study's result.json; the report is written from it (figures skipped: no gnuplot) into a
// scratch folder. Accepted: any input gives a report (a malformed file is shown as UNREADABLE or BROKEN,
// never PASS unless its checks all passed). A thrown exception, a crash or a sanitizer report is a
// finding. Seeds: fuzz/corpus/result/.
#include <string>

#include "harness.hpp"
#include "report.hpp"
#include "study_result.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path root = fuzz::scratch_beside_cases("report");
  std::filesystem::create_directories(root / "studies" / "s");
  fuzz::write_file(root / "studies" / "s" / "result.json", data, size);
  try {
    for (const report::StudyResult& r : report::read_study_results(root / "studies")) {
      const std::string status = report::study_status(r);
      if (status == "PASS") {  // at least one check and every check passed
        const auto& checks = report::array_field(r.result, "checks");
        if (checks.empty()) fuzz::finding("PASS without a check");
        for (const auto& c : checks)
          if (report::check_status(c) != "PASS") fuzz::finding("PASS next to a check that did not pass");
      }
    }
    report::Options o;
    o.studies_dir = root / "studies";
    o.out_dir = root / "out";
    (void)report::write_report(o, root / "no_gnuplot");
  } catch (const std::exception& e) {
    fuzz::finding(std::string("the report threw: ") + e.what());
  }
  return 0;
}
