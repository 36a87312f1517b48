#pragma once
// Small text helpers shared by the case reader, the quantity names and the study engine.
#include <string>
#include <vector>

namespace dem {

/// Splits at every `sep` (empty fields kept): "a.b..c" → {"a", "b", "", "c"}.
inline std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t k = 0; k <= s.size(); ++k)
    if (k == s.size() || s[k] == sep) {
      out.push_back(s.substr(start, k - start));
      start = k + 1;
    }
  return out;
}

/// One CSV field, quoted if it holds a comma or a quote (RFC 4180).
inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// Splits one CSV line into fields, honouring quotes (RFC 4180).
inline std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted) {
      if (c == '"' && k + 1 < line.size() && line[k + 1] == '"') out.back() += '"', ++k;
      else if (c == '"') quoted = false;
      else out.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

}  // namespace dem
