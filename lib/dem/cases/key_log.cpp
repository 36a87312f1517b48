#include "dem/cases/key_log.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace dem {

namespace {
thread_local KeyUses* active = nullptr;
thread_local int depth = 0;
}  // namespace

const char* to_string(KeyKind k) {
  switch (k) {
    case KeyKind::quantity: return "quantity";
    case KeyKind::element: return "array element quantity";
    case KeyKind::number: return "number";
    case KeyKind::integer: return "integer";
    case KeyKind::boolean: return "boolean";
    case KeyKind::string: return "string";
    case KeyKind::choice: return "choice";
    case KeyKind::strings: return "array of strings";
    case KeyKind::vector: return "vector";
    case KeyKind::table: return "table";
    case KeyKind::other: return "other";
  }
  return "?";
}

std::string table_kind(const std::string& path) {
  std::string out, part;
  auto flush = [&] {
    const bool index = !part.empty() && std::all_of(part.begin(), part.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    if (!part.empty() && !index) out += (out.empty() ? "" : ".") + part;
    part.clear();
  };
  for (char c : path) {
    if (c == '.') flush();
    else part += c;
  }
  flush();
  return out;
}

KeyLog::KeyLog() {
  if (active) throw std::logic_error("KeyLog: another log is already recording on this thread");
  active = &uses_;
}
KeyLog::~KeyLog() { active = nullptr; }

KeyLog::Guard::Guard(const std::string& path, const std::string& key, KeyUse use) {
  if (active && depth == 0) (*active)[table_kind(path)][key].push_back(std::move(use));
  ++depth;
}
KeyLog::Guard::~Guard() { --depth; }

}  // namespace dem
