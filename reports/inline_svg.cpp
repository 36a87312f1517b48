// SVG inlining: strip the prolog, make ids unique.
#include "inline_svg.hpp"

#include <cctype>
#include <regex>
#include <set>

namespace report {

std::string inline_svg(std::string_view svg, std::string_view id_prefix) {
  std::string out(svg);
  const auto start = out.find("<svg");
  if (start == std::string::npos) return {};
  out.erase(0, start);  // XML declaration, DOCTYPE, leading comments
  out = std::regex_replace(out, std::regex(R"(\s+xmlns(:\w+)?\s*=\s*("[^"]*"|'[^']*'))"), "");

  // Collect the ids, then rewrite id='x' / id="x" and references '#x' "#x" #x) .
  std::set<std::string> ids;
  const std::regex id_attribute(R"(\bid\s*=\s*(["'])([^"']+)\1)");
  for (auto it = std::sregex_iterator(out.begin(), out.end(), id_attribute);
       it != std::sregex_iterator(); ++it)
    ids.insert((*it)[2].str());
  std::string result;
  result.reserve(out.size() + ids.size() * 16);
  std::size_t i = 0;
  while (i < out.size()) {
    // id="x" or id='x'
    if (out.compare(i, 3, "id=") == 0 && i + 3 < out.size() &&
        (out[i + 3] == '"' || out[i + 3] == '\'') &&
        (i == 0 || !std::isalnum(static_cast<unsigned char>(out[i - 1])))) {
      const char quote = out[i + 3];
      const auto end = out.find(quote, i + 4);
      if (end != std::string::npos && ids.count(out.substr(i + 4, end - i - 4))) {
        result += "id=";
        result += quote;
        result += id_prefix;
        result += out.substr(i + 4, end - i - 3);
        i = end + 1;
        continue;
      }
    }
    // #x followed by a quote or ')'
    if (out[i] == '#') {
      std::size_t end = i + 1;
      while (end < out.size() && out[end] != '"' && out[end] != '\'' && out[end] != ')' &&
             !std::isspace(static_cast<unsigned char>(out[end])))
        ++end;
      if (end < out.size() && end > i + 1 && ids.count(out.substr(i + 1, end - i - 1)) &&
          (out[end] == '"' || out[end] == '\'' || out[end] == ')')) {
        result += '#';
        result += id_prefix;
        result += out.substr(i + 1, end - i - 1);
        i = end;
        continue;
      }
    }
    result += out[i++];
  }
  return result;
}

}  // namespace report
