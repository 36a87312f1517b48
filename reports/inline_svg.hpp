// Turning a standalone SVG file (as written by gnuplot) into an element to inline in HTML.
#pragma once

#include <string>
#include <string_view>

namespace report {

// Drops the XML prolog, DOCTYPE and namespace declarations (HTML needs none of them), and prefixes
// every id (and its #references) with id_prefix so several inlined plots do not share ids.
std::string inline_svg(std::string_view svg, std::string_view id_prefix);

}  // namespace report
