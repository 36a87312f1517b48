// The summary table of every study's checks, printed on the terminal by `dem2d report` before the
// report is written (the report has the full tables): checks, failed checks, observed orders within
// their bands, title. Reads the studies' result.json files tolerantly (study_result.hpp).
#pragma once

#include <filesystem>

namespace report {

/// Prints one row per study of `studies_dir` on stdout, then the pass / fail counts; a broken or
/// incomplete study is listed as such, a missing folder as "none".
void print_study_summary(const std::filesystem::path& studies_dir);

}  // namespace report
