#include "study_summary.hpp"

#include <cmath>

#include <fmt/format.h>

#include "report_content.hpp"
#include "study_result.hpp"

namespace fs = std::filesystem;

namespace report {

void print_study_summary(const fs::path& studies_dir) {
  int pass = 0, fail = 0;
  fmt::print("\n{:<24} {:>7} {:>7}  {:<12} {}\n", "study", "checks", "failed", "orders", "title");
  if (!fs::is_directory(studies_dir)) {
    fmt::print("studies: none (no folder {})\n\n", studies_dir.string());
    return;
  }
  // Tolerant reading (study_result.hpp): a broken or incomplete study is listed as such; the others follow.
  for (const StudyResult& st : read_study_results(studies_dir)) {
    if (!st.readable()) {
      fmt::print("{:<24} BROKEN: {}\n", st.folder, st.read_error);
      ++fail;
      continue;
    }
    const nlohmann::json& j = st.result;
    int n = 0, bad = 0, orders = 0, orders_ok = 0;
    for (const auto& c : array_field(j, "checks")) {
      ++n;
      if (check_status(c) != "PASS") ++bad;
      const auto expected = number_field(c, "expected_order");
      if (expected) {
        ++orders;
        const auto observed = number_field(c, "observed_order");
        const auto band = number_field(c, "order_band");
        if (observed && band && std::abs(*observed - *expected) <= *band) ++orders_ok;
      }
    }
    (study_status(st) == "PASS" ? pass : fail) += 1;
    fmt::print("{:<24} {:>7} {:>7}  {:<12} {}\n", study_name(st), n, bad,
               orders ? fmt::format("{}/{} ok", orders_ok, orders) : std::string("-"), text_field(j, "title"));
  }
  fmt::print("studies: {} passed, {} failed\n\n", pass, fail);
}

}  // namespace report
