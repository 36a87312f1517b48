#include "dem/cases/case_reader.hpp"

#include <algorithm>
#include <cmath>
#include <vector>
#include <fmt/format.h>

#include "dem/cases/key_log.hpp"

namespace dem {

std::string where(const toml::node& n, const std::string& fallback_file) {
  const auto& src = n.source();
  const std::string file = src.path ? *src.path : fallback_file;
  if (file.rfind("--set", 0) == 0) return file;
  return fmt::format("{}:{}", file, src.begin.line);
}

namespace {
/// What a getter reads, for the KeyLog (key_log.hpp).
KeyUse use(KeyKind kind, std::vector<Dimension> dims, nlohmann::json fallback, bool required) {
  return {kind, std::move(dims), {}, std::move(fallback), required};
}
constexpr bool kRequired = true, kOptional = false;
}  // namespace

TableReader::TableReader(const toml::table& t, std::string path, std::string file, std::string help)
    : t_(t), path_(std::move(path)), file_(std::move(file)), help_(std::move(help)) {}

void TableReader::fail_at(const toml::node& n, const std::string& key, const std::string& what) const {
  throw CaseError(fmt::format("{}: {}: {}", where(n, file_), key_path(key), what));
}

void TableReader::fail(const std::string& key, const std::string& what) const {
  const toml::node* n = t_.get(key);
  const std::string loc = n ? where(*n, file_) : where(t_, file_);
  std::string hint;  // a key that is missing may be there, misspelled
  if (!n)
    for (const auto& [k, v] : t_)
      if (const std::string other(k.str()); !used_.count(other) && !nearest_word(other, {key}).empty())
        hint = fmt::format(" (is '{}', line {}, a misspelling of '{}'?)", other, v.source().begin.line, key);
  throw CaseError(fmt::format("{}: {}: {}{}", loc, key_path(key), what, hint));
}

void TableReader::fail_here(const std::string& what) const {
  throw CaseError(fmt::format("{}: {}: {}", where(t_, file_), path_.empty() ? "(top level)" : path_, what));
}

const toml::node& TableReader::need(const std::string& key) const {
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) fail(key, "missing (required)");
  return *n;
}

double TableReader::to_quantity(const toml::node& n, const std::string& key, Dimension dim) const {
  try {
    double v = 0.0;
    bool got = false;
    if (auto s = n.value_exact<std::string>()) {
      v = to_si(std::string_view(*s), dim);
      got = true;
    } else if (auto d = n.value<double>()) {
      v = to_si(*d, dim);
      got = true;
    }
    if (got) {
      if (!std::isfinite(v)) fail(key, fmt::format("expected a finite {}, got {}", describe(dim), v));
      return v;
    }
  } catch (const UnitError& e) {
    fail(key, e.what());
  }
  fail(key, fmt::format("expected {} as a number (SI) or a string with a unit, got a {}", describe(dim),
                        toml::impl::node_type_friendly_names[static_cast<int>(n.type())]));
}

double TableReader::quantity(const std::string& key, Dimension dim) const {
  KeyLog::Guard g(path_, key, use(KeyKind::quantity, {dim}, nullptr, kRequired));
  return to_quantity(need(key), key, dim);
}
double TableReader::quantity(const std::string& key, Dimension dim, double fallback) const {
  KeyLog::Guard g(path_, key, use(KeyKind::quantity, {dim}, fallback, kOptional));
  used_.insert(key);
  const toml::node* n = t_.get(key);
  return n ? to_quantity(*n, key, dim) : fallback;
}
std::optional<double> TableReader::optional_quantity(const std::string& key, Dimension dim) const {
  KeyLog::Guard g(path_, key, use(KeyKind::quantity, {dim}, nullptr, kOptional));
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) return std::nullopt;
  return to_quantity(*n, key, dim);
}

std::pair<double, Dimension> TableReader::quantity_either(const std::string& key, Dimension a, Dimension b) const {
  KeyLog::Guard g(path_, key, use(KeyKind::quantity, {a, b}, nullptr, kRequired));
  const toml::node& n = need(key);
  const auto finite = [&](std::pair<double, Dimension> r) {
    if (!std::isfinite(r.first)) fail(key, fmt::format("expected a finite {}, got {}", describe(r.second), r.first));
    return r;
  };
  if (auto s = n.value_exact<std::string>()) {
    Quantity q;
    try {
      q = parse_quantity(*s);
    } catch (const UnitError& e) {
      fail(key, e.what());
    }
    if (q.dim == a) return finite({q.value, a});
    if (q.dim == b) return finite({q.value, b});
    if (q.dim == dims::dimensionless) return finite({q.value, a});  // a bare number: SI of the first kind
    fail(key, fmt::format("expected {} or {}, got {} from '{}'", describe(a), describe(b), to_string(q.dim), *s));
  }
  if (auto d = n.value<double>()) return finite({*d, a});
  fail(key, fmt::format("expected {} as a number or a string with a unit", describe(a)));
}

Vec2 TableReader::vector(const std::string& key, Dimension dim) const {
  KeyLog::Guard g(path_, key, use(KeyKind::vector, {dim}, nullptr, kRequired));
  const toml::node& n = need(key);
  const toml::array* arr = n.as_array();
  if (!arr || arr->size() != 2)
    fail(key, fmt::format("expected a 2D vector [x, y] of {} (e.g. [\"0 m\", \"1 cm\"])", describe(dim)));
  return {to_quantity(*arr->get(0), key, dim), to_quantity(*arr->get(1), key, dim)};
}
Vec2 TableReader::vector(const std::string& key, Dimension dim, Vec2 fallback) const {
  KeyLog::Guard g(path_, key, use(KeyKind::vector, {dim}, {fallback.x, fallback.y}, kOptional));
  used_.insert(key);
  return t_.contains(key) ? vector(key, dim) : fallback;
}

double TableReader::number(const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::number, {}, nullptr, kRequired));
  const toml::node& n = need(key);
  if (auto d = n.value<double>(); d && std::isfinite(*d)) return *d;
  if (auto s = n.value_exact<std::string>()) {
    try {
      return to_si(std::string_view(*s), dims::dimensionless);
    } catch (const UnitError& e) {
      fail(key, e.what());
    }
  }
  fail(key, "expected a plain number");
}
double TableReader::number(const std::string& key, double fallback) const {
  KeyLog::Guard g(path_, key, use(KeyKind::number, {}, fallback, kOptional));
  used_.insert(key);
  return t_.contains(key) ? number(key) : fallback;
}

double TableReader::number_in(const std::string& key, double lo, double hi, double fallback, bool open_lo,
                              bool open_hi) const {
  KeyLog::Guard g(path_, key, use(KeyKind::number, {}, fallback, kOptional));
  used_.insert(key);
  if (!t_.contains(key)) return fallback;
  const double v = number(key);
  if (v < lo || v > hi || (open_lo && v == lo) || (open_hi && v == hi))
    fail(key, fmt::format("expected a number in {}{:g}, {:g}{}, got {:g}", open_lo ? "(" : "[", lo, hi, open_hi ? ")" : "]", v));
  return v;
}

Quantity TableReader::any_quantity_of(const toml::node& n, const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::element, {}, nullptr, kOptional));
  Quantity q;
  if (auto s = n.value_exact<std::string>()) {
    try {
      q = parse_quantity(*s);
    } catch (const UnitError& e) {
      fail_at(n, key, e.what());
    }
  } else if (auto d = n.value<double>()) {
    q.value = *d;
    q.dim = dims::dimensionless;
  } else {
    fail_at(n, key, "expected a number or a string with a unit");
  }
  if (!std::isfinite(q.value)) fail_at(n, key, fmt::format("expected a finite number, got {}", q.value));
  return q;
}

Quantity TableReader::any_quantity(const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::quantity, {}, nullptr, kRequired));
  return any_quantity_of(need(key), key);
}

void TableReader::mark(const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::other, {}, nullptr, kOptional));
  used_.insert(key);
}

double TableReader::quantity_of(const toml::node& n, const std::string& key, Dimension dim) const {
  KeyLog::Guard g(path_, key, use(KeyKind::element, {dim}, nullptr, kOptional));
  return to_quantity(n, key, dim);
}

std::optional<Quantity> TableReader::optional_any_quantity(const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::quantity, {}, nullptr, kOptional));
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) return std::nullopt;
  return any_quantity_of(*n, key);
}

std::map<std::string, double> TableReader::quantity_table(const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::table, {}, nullptr, kOptional));
  std::map<std::string, double> out;
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) return out;
  const toml::table* a = n->as_table();
  if (!a) fail(key, "expected a table of numbers, e.g. { zeta = 0.3 }");
  for (const auto& [k, v] : *a) out[std::string(k.str())] = any_quantity_of(v, key + "." + std::string(k.str())).value;
  return out;
}

std::int64_t TableReader::integer(const std::string& key, std::int64_t lo, std::int64_t hi) const {
  KeyUse u = use(KeyKind::integer, {}, nullptr, kRequired);
  u.min = lo, u.max = hi;
  KeyLog::Guard g(path_, key, std::move(u));
  const toml::node& n = need(key);
  auto v = n.value_exact<std::int64_t>();
  if (!v || *v < lo || *v > hi) fail(key, fmt::format("expected a whole number from {} to {}", lo, hi));
  return *v;
}
std::int64_t TableReader::integer(const std::string& key, std::int64_t lo, std::int64_t hi,
                                  std::int64_t fallback) const {
  KeyUse u = use(KeyKind::integer, {}, fallback, kOptional);
  u.min = lo, u.max = hi;
  KeyLog::Guard g(path_, key, std::move(u));
  used_.insert(key);
  return t_.contains(key) ? integer(key, lo, hi) : fallback;
}

bool TableReader::boolean(const std::string& key, bool fallback) const {
  KeyLog::Guard g(path_, key, use(KeyKind::boolean, {}, fallback, kOptional));
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) return fallback;
  auto v = n->value_exact<bool>();
  if (!v) fail(key, "expected true or false");
  return *v;
}

std::string TableReader::string(const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::string, {}, nullptr, kRequired));
  const toml::node& n = need(key);
  auto v = n.value_exact<std::string>();
  if (!v) fail(key, "expected a string");
  return *v;
}
std::string TableReader::string(const std::string& key, const std::string& fallback) const {
  KeyLog::Guard g(path_, key, use(KeyKind::string, {}, fallback, kOptional));
  used_.insert(key);
  return t_.contains(key) ? string(key) : fallback;
}

std::string TableReader::choice(const std::string& key, const std::vector<std::string>& allowed,
                                const std::string& fallback) const {
  KeyUse u = use(KeyKind::choice, {}, fallback.empty() ? nlohmann::json() : nlohmann::json(fallback), fallback.empty());
  u.choices = allowed;
  KeyLog::Guard g(path_, key, std::move(u));
  const std::string v = fallback.empty() ? string(key) : string(key, fallback);
  for (const auto& a : allowed)
    if (a == v) return v;
  const std::string near = nearest_word(v, allowed);
  fail(key, fmt::format("expected one of \"{}\", got \"{}\"{}", fmt::join(allowed, "\", \""), v,
                        near.empty() ? "" : fmt::format("; did you mean \"{}\"?", near)));
}

std::vector<std::string> TableReader::strings(const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::strings, {}, nullptr, kOptional));
  used_.insert(key);
  std::vector<std::string> out;
  const toml::node* n = t_.get(key);
  if (!n) return out;
  const toml::array* arr = n->as_array();
  if (!arr) fail(key, "expected an array of strings");
  for (const auto& item : *arr) {
    auto s = item.value_exact<std::string>();
    if (!s) fail(key, "expected an array of strings");
    out.push_back(*s);
  }
  return out;
}

const toml::table* TableReader::table(const std::string& key) const {
  KeyLog::Guard g(path_, key, use(KeyKind::table, {}, nullptr, kOptional));
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) return nullptr;
  if (!n->is_table()) fail(key, "expected a table");
  return n->as_table();
}

void TableReader::finish() const {
  for (const auto& [k, v] : t_) {
    const std::string key(k.str());
    if (used_.count(key)) continue;
    std::vector<std::string> candidates(used_.begin(), used_.end());
    candidates.insert(candidates.end(), known_.begin(), known_.end());
    const std::string near = nearest_word(key, candidates);
    if (!near.empty()) fail(key, fmt::format("unknown key; did you mean '{}'? (see {})", near, help_));
    fail(key, fmt::format("unknown key (a typo? see {} for the keys of this table)", help_));
  }
}

std::string nearest_word(const std::string& word, const std::vector<std::string>& known) {
  // Levenshtein distance with a transposition counted as one edit (optimal string alignment).
  auto distance = [](const std::string& a, const std::string& b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
      for (std::size_t j = 1; j <= b.size(); ++j) {
        const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
        d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
        if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    return d[a.size()][b.size()];
  };
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& k : known)
    if (const std::size_t dk = distance(word, k); dk < best_d) {
      best = k;
      best_d = dk;
    }
  return best;
}

toml::table parse_toml_file(const std::filesystem::path& path, const std::string& from) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw CaseError(fmt::format("file not found: {}{}", file, from.empty() ? "" : " (from " + from + ")"));
  try {
    return toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    throw CaseError(fmt::format("{}:{}: syntax: {}", file, e.source().begin.line, e.description()));
  } catch (const std::exception& e) {
    throw CaseError(fmt::format("{}: cannot read: {}", file, e.what()));
  }
}

toml::table parse_toml_text(std::string_view text, const std::filesystem::path& path) {
  const std::string file = path.string();
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw CaseError(fmt::format("{}:{}: syntax: {}", file, e.source().begin.line, e.description()));
  } catch (const std::exception& e) {
    throw CaseError(fmt::format("{}: cannot read: {}", file, e.what()));
  }
}

}  // namespace dem
