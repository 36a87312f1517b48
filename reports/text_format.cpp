// Number formatting and escaping.
#include "text_format.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <ctime>

namespace report {

std::string format_number(double x) {
  if (!std::isfinite(x)) return std::string(missing_value);
  return fmt::format("{:.6g}", x);
}

std::string format_number(const std::optional<double>& x) {
  return x ? format_number(*x) : std::string(missing_value);
}

std::string format_value(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return v.dump();
  if (v.is_number()) return format_number(v.get<double>());
  if (v.is_null()) return std::string(missing_value);
  if (v.is_array()) {  // short arrays of scalars read better as "a, b, c"
    std::string out;
    for (const auto& item : v) {
      if (item.is_structured()) return v.dump();
      if (!out.empty()) out += ", ";
      out += format_value(item);
    }
    return out;
  }
  return v.dump();
}

std::string format_order(const std::optional<double>& observed,
                         const std::optional<double>& expected, const std::optional<double>& band) {
  if (!observed && !expected) return std::string(missing_value);
  std::string out = format_number(observed);
  if (expected) {
    out += " vs " + format_number(*expected);
    if (band) out += " \u00b1 " + format_number(*band);
  }
  return out;
}

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string markdown_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '\\':
      case '`':
      case '*':
      case '_':
      case '[':
      case ']':
      case '<':
      case '>':
      case '|':
      case '#':
        out += '\\';
        out += c;
        break;
      case '\n':
      case '\r':
        out += ' ';
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string slug(std::string_view text) {
  std::string out;
  for (char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '_' || c == '-';
    out += keep ? c : '-';
  }
  return out.empty() ? std::string("x") : out;
}

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  if (in) buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace report
