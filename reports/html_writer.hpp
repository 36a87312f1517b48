// The report as one self-contained HTML page: inline CSS, figures inlined as SVG, no external
// resources.
#pragma once

#include <string>

#include "report_content.hpp"

namespace report {

std::string html_page(const ReportContent& content);

}  // namespace report
