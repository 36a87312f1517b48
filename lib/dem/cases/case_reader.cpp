#include "dem/cases/case_reader.hpp"

#include <cmath>
#include <fmt/format.h>

namespace dem {

std::string where(const toml::node& n, const std::string& fallback_file) {
  const auto& src = n.source();
  const std::string file = src.path ? *src.path : fallback_file;
  if (file.rfind("--set", 0) == 0) return file;
  return fmt::format("{}:{}", file, src.begin.line);
}

TableReader::TableReader(const toml::table& t, std::string path, std::string file)
    : t_(t), path_(std::move(path)), file_(std::move(file)) {}

void TableReader::fail(const std::string& key, const std::string& what) const {
  const toml::node* n = t_.get(key);
  const std::string loc = n ? where(*n, file_) : where(t_, file_);
  throw CaseError(fmt::format("{}: {}: {}", loc, key_path(key), what));
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
  return to_quantity(need(key), key, dim);
}
double TableReader::quantity(const std::string& key, Dimension dim, double fallback) const {
  used_.insert(key);
  const toml::node* n = t_.get(key);
  return n ? to_quantity(*n, key, dim) : fallback;
}
std::optional<double> TableReader::optional_quantity(const std::string& key, Dimension dim) const {
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) return std::nullopt;
  return to_quantity(*n, key, dim);
}

std::pair<double, Dimension> TableReader::quantity_either(const std::string& key, Dimension a, Dimension b) const {
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
  const toml::node& n = need(key);
  const toml::array* arr = n.as_array();
  if (!arr || arr->size() != 2)
    fail(key, fmt::format("expected a 2D vector [x, y] of {} (e.g. [\"0 m\", \"1 cm\"])", describe(dim)));
  return {to_quantity(*arr->get(0), key, dim), to_quantity(*arr->get(1), key, dim)};
}
Vec2 TableReader::vector(const std::string& key, Dimension dim, Vec2 fallback) const {
  used_.insert(key);
  return t_.contains(key) ? vector(key, dim) : fallback;
}

double TableReader::number(const std::string& key) const {
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
  used_.insert(key);
  return t_.contains(key) ? number(key) : fallback;
}

std::int64_t TableReader::integer(const std::string& key, std::int64_t lo, std::int64_t hi) const {
  const toml::node& n = need(key);
  auto v = n.value_exact<std::int64_t>();
  if (!v || *v < lo || *v > hi) fail(key, fmt::format("expected a whole number from {} to {}", lo, hi));
  return *v;
}
std::int64_t TableReader::integer(const std::string& key, std::int64_t lo, std::int64_t hi,
                                  std::int64_t fallback) const {
  used_.insert(key);
  return t_.contains(key) ? integer(key, lo, hi) : fallback;
}

bool TableReader::boolean(const std::string& key, bool fallback) const {
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) return fallback;
  auto v = n->value_exact<bool>();
  if (!v) fail(key, "expected true or false");
  return *v;
}

std::string TableReader::string(const std::string& key) const {
  const toml::node& n = need(key);
  auto v = n.value_exact<std::string>();
  if (!v) fail(key, "expected a string");
  return *v;
}
std::string TableReader::string(const std::string& key, const std::string& fallback) const {
  used_.insert(key);
  return t_.contains(key) ? string(key) : fallback;
}

std::string TableReader::choice(const std::string& key, const std::vector<std::string>& allowed,
                                const std::string& fallback) const {
  const std::string v = fallback.empty() ? string(key) : string(key, fallback);
  for (const auto& a : allowed)
    if (a == v) return v;
  fail(key, fmt::format("expected one of \"{}\", got \"{}\"", fmt::join(allowed, "\", \""), v));
}

std::vector<std::string> TableReader::strings(const std::string& key) const {
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
  used_.insert(key);
  const toml::node* n = t_.get(key);
  if (!n) return nullptr;
  if (!n->is_table()) fail(key, "expected a table");
  return n->as_table();
}

void TableReader::finish() const {
  for (const auto& [k, v] : t_) {
    const std::string key(k.str());
    if (!used_.count(key)) fail(key, "unknown key (a typo? see cases/README.md for the keys of this table)");
  }
}

}  // namespace dem
