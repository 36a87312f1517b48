// Formatting of numbers and JSON values for the report, and escaping for HTML and Markdown.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace report {

inline constexpr std::string_view missing_value = "\u2014";  // em dash for null / absent

std::string format_number(double x);                        // %.6g style; integers without ".0"
std::string format_number(const std::optional<double>& x);  // missing_value if absent
std::string format_value(const nlohmann::json& v);          // strings raw, numbers %.6g, null "—"

// "1.01 vs 1 ± 0.15", "1.01", "— vs 2" or "—".
std::string format_order(const std::optional<double>& observed,
                         const std::optional<double>& expected, const std::optional<double>& band);

std::string html_escape(std::string_view text);
std::string markdown_escape(std::string_view text);  // inline text and table cells
std::string slug(std::string_view text);             // [A-Za-z0-9_-] only, for ids and file names

std::string utc_now_iso8601();

// A file's whole text ("" if it cannot be read).
std::string read_text_file(const std::filesystem::path& path);

}  // namespace report
