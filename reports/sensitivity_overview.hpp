// One table over every sensitivity study of the report: per study and output, the most and the least
// influential parameter by the strongest measure the study computed (Sobol' total index S_T with its
// interval, else Morris μ*, else the one-at-a-time range), runs and failed runs; each row links to
// the study's section. Where other parameters' intervals overlap the chosen one's, they are named with
// it ("h_n (intervals overlap: K_n, K_s/K_n)"): the data do not rank them. With replicates, the noise
// fraction of a single run beside them (table "Run-to-run noise"). Read from the studies' own
// tables in result.json (kind "sensitivity").
#pragma once

#include <string>
#include <vector>

#include "report_content.hpp"

namespace report {

struct SensitivityOverviewRow {
  std::string anchor, study, output, measure;  // measure: "S_T (Jansen)", "μ* (Morris)", "range (one-at-a-time)"
  std::string most, most_value, most_interval, least, least_value, least_interval;
  std::string runs, failed;
  std::string noise;  // the run-to-run noise fraction with its interval (studies with replicates; "—" else)
};
std::vector<SensitivityOverviewRow> sensitivity_overview_rows(const ReportContent& content);

inline const std::vector<std::string> sensitivity_overview_columns{
    "Study", "Output", "Measure", "Most influential", "Value", "Interval", "Least influential", "Value", "Interval", "Runs",
    "Failed runs", "Noise fraction"};

}  // namespace report
