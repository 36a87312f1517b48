// The report as Markdown: same content as the HTML page, figures linked as figures/*.svg.
#pragma once

#include <string>

#include "report_content.hpp"

namespace report {

std::string markdown_page(const ReportContent& content);

}  // namespace report
