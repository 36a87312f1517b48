#include "dem/cases/units.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <system_error>

namespace dem {
namespace {

// Standard acceleration of gravity, exact by definition (3rd CGPM, 1901); used for kgf, gf and tf.
constexpr double g_n = 9.80665;

// A unit's SI value is mul/div; prefixes below 1 are written as divisors (cm = 1/100 m) so that the
// integer factors are exact and e.g. "1 kgf/cm^2" gives exactly 98066.5 Pa.
struct UnitDef {
  std::string_view symbol;
  double mul;
  double div;
  Dimension dim;
};

// UTF-8 spellings used below.
constexpr std::string_view micro_sign = "\xC2\xB5";  // µ U+00B5
constexpr std::string_view greek_mu = "\xCE\xBC";    // μ U+03BC
constexpr std::string_view degree_sign = "\xC2\xB0"; // ° U+00B0

// Concatenation by appending to one buffer (also sidesteps GCC 12's false -Wrestrict positives on
// `"literal" + std::string` at -O3).
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string out;
  (out.append(std::string_view(parts)), ...);
  return out;
}

constexpr UnitDef unit_table[] = {
    // length
    {"m", 1, 1, dims::length},
    {"cm", 1, 1e2, dims::length},
    {"mm", 1, 1e3, dims::length},
    {"um", 1, 1e6, dims::length},
    {"\xC2\xB5m", 1, 1e6, dims::length},
    {"\xCE\xBCm", 1, 1e6, dims::length},
    {"km", 1e3, 1, dims::length},
    // mass ("t" for tonne deliberately omitted: too easily confused with time)
    {"g", 1, 1e3, dims::mass},
    {"kg", 1, 1, dims::mass},
    // time
    {"s", 1, 1, dims::time},
    {"ms", 1, 1e3, dims::time},
    {"us", 1, 1e6, dims::time},
    {"\xC2\xB5s", 1, 1e6, dims::time},
    {"\xCE\xBCs", 1, 1e6, dims::time},
    {"min", 60, 1, dims::time},
    {"h", 3600, 1, dims::time},
    // force
    {"N", 1, 1, dims::force},
    {"kN", 1e3, 1, dims::force},
    {"MN", 1e6, 1, dims::force},
    {"mN", 1, 1e3, dims::force},
    {"dyn", 1, 1e5, dims::force},
    {"kgf", g_n, 1, dims::force},
    {"gf", g_n, 1e3, dims::force},
    {"tf", g_n * 1e3, 1, dims::force},
    // pressure
    {"Pa", 1, 1, dims::pressure},
    {"kPa", 1e3, 1, dims::pressure},
    {"MPa", 1e6, 1, dims::pressure},
    {"GPa", 1e9, 1, dims::pressure},
    {"bar", 1e5, 1, dims::pressure},
    // energy
    {"J", 1, 1, dims::energy},
    // angle
    {"rad", 1, 1, dims::angle},
    {"deg", std::numbers::pi, 180, dims::angle},
    {"\xC2\xB0", std::numbers::pi, 180, dims::angle},
    // frequency
    {"Hz", 1, 1, dims::frequency},
};

const UnitDef* find_unit(std::string_view symbol) {
  for (const UnitDef& u : unit_table)
    if (u.symbol == symbol) return &u;
  return nullptr;
}

}  // namespace

std::vector<std::string> unit_symbols() {
  std::vector<std::string> out;
  for (const UnitDef& u : unit_table) out.emplace_back(u.symbol);
  return out;
}

namespace {

char ascii_lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (ascii_lower(a[i]) != ascii_lower(b[i])) return false;
  return true;
}

bool is_ascii_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

struct ParseResult {
  Quantity q;
  bool has_unit = false;
};

class Parser {
 public:
  explicit Parser(std::string_view text) : text_(text) {}

  ParseResult run() {
    // Trim.
    skip_space();
    std::size_t end = text_.size();
    while (end > pos_) {
      std::size_t w = space_width_before(end);
      if (w == 0) break;
      end -= w;
    }
    body_end_ = end;
    if (pos_ >= body_end_) fail("empty quantity: expected a number with an optional unit, e.g. '25 mm'");

    double value = parse_number();
    ParseResult r;
    r.q.value = value;
    parse_units(r);
    return r;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t body_end_ = 0;

  [[noreturn]] void fail(const std::string& what) const {
    throw UnitError(cat(what, " in '", text_, "'"));
  }

  bool at_end() const { return pos_ >= body_end_; }
  std::string_view rest() const { return text_.substr(pos_, body_end_ - pos_); }
  bool starts_with(std::string_view s) const { return rest().substr(0, s.size()) == s; }

  // Width in bytes of a whitespace character at position p (0 if none).
  std::size_t space_width_at(std::size_t p) const {
    std::string_view s = text_.substr(p);
    if (s.empty()) return 0;
    if (s[0] == ' ' || s[0] == '\t' || s[0] == '\r' || s[0] == '\n') return 1;
    if (s.substr(0, 2) == "\xC2\xA0") return 2;      // no-break space U+00A0
    if (s.substr(0, 3) == "\xE2\x80\xAF") return 3;  // narrow no-break space U+202F
    if (s.substr(0, 3) == "\xE2\x80\x89") return 3;  // thin space U+2009
    return 0;
  }
  std::size_t space_width_before(std::size_t end) const {
    for (std::size_t w : {std::size_t{1}, std::size_t{2}, std::size_t{3}})
      if (end >= w && space_width_at(end - w) == w) return w;
    return 0;
  }
  bool skip_space() {
    bool any = false;
    while (pos_ < text_.size()) {
      std::size_t w = space_width_at(pos_);
      if (w == 0) break;
      pos_ += w;
      any = true;
    }
    return any;
  }

  // The UTF-8 character at position p, for error messages.
  std::string char_at(std::size_t p) const {
    auto c = static_cast<unsigned char>(text_[p]);
    std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 1;
    return std::string(text_.substr(p, n));
  }

  double parse_number() {
    std::size_t start = pos_;
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + body_end_;
    if (first != last && *first == '+' && last - first > 1 && first[1] != '+' && first[1] != '-') ++first;

    // The characters that could belong to a number, for "malformed number '1.2.3'" messages.
    std::size_t run = pos_;
    while (run < body_end_ && (is_digit(text_[run]) || text_[run] == '.' || text_[run] == 'e' ||
                               text_[run] == 'E' || text_[run] == '+' || text_[run] == '-'))
      ++run;
    std::string_view run_text = text_.substr(start, run - start);

    double value = 0.0;
    auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
    if (ec == std::errc::invalid_argument) {
      if (run_text.empty()) fail("missing number");
      fail(cat("malformed number '", run_text, "'"));
    }
    std::size_t consumed = static_cast<std::size_t>(ptr - text_.data()) - start;
    std::string_view num_text = text_.substr(start, consumed);
    if (ec == std::errc::result_out_of_range)
      fail(cat("number '", num_text, "' is out of the range of double"));
    if (!std::isfinite(value)) fail(cat("not a finite number '", num_text, "'"));
    if (consumed < run_text.size()) fail(cat("malformed number '", run_text, "'"));
    if (ptr < last && *ptr == ',' && ptr + 1 < last && is_digit(ptr[1]))
      fail(cat("malformed number (use '.' as the decimal separator) '",
               text_.substr(start, consumed + 2), "'"));
    pos_ = start + consumed;
    return value;
  }

  // Parses "^n", "^-n", "²", "³", "⁻²", ...; returns 1 if there is no exponent.
  int parse_exponent(std::string_view symbol) {
    if (!at_end() && text_[pos_] == '^') {
      ++pos_;
      int sign = 1;
      if (!at_end() && (text_[pos_] == '-' || text_[pos_] == '+')) {
        if (text_[pos_] == '-') sign = -1;
        ++pos_;
      }
      std::size_t digits_start = pos_;
      int n = 0;
      while (!at_end() && is_digit(text_[pos_])) {
        n = 10 * n + (text_[pos_] - '0');
        ++pos_;
        if (pos_ - digits_start > 2) fail(cat("exponent too large after '", symbol, "'"));
      }
      if (pos_ == digits_start) fail(cat("missing exponent after '", symbol, "^'"));
      return sign * n;
    }
    int sign = 1;
    bool minus = false;
    if (starts_with("\xE2\x81\xBB")) {  // superscript minus U+207B
      minus = true;
      sign = -1;
      pos_ += 3;
    }
    if (starts_with("\xC2\xB9")) { pos_ += 2; return sign * 1; }  // ¹
    if (starts_with("\xC2\xB2")) { pos_ += 2; return sign * 2; }  // ²
    if (starts_with("\xC2\xB3")) { pos_ += 2; return sign * 3; }  // ³
    if (minus) fail(cat("superscript minus must be followed by \xC2\xB9, \xC2\xB2 or \xC2\xB3 after '",
                        symbol, "'"));
    return 1;
  }

  // Reads a unit symbol: ASCII letters, optionally after a micro prefix µ/μ; or the degree sign.
  std::string_view read_symbol() {
    std::size_t start = pos_;
    if (starts_with(degree_sign)) {
      pos_ += degree_sign.size();
      return text_.substr(start, pos_ - start);
    }
    if (starts_with(micro_sign)) pos_ += micro_sign.size();
    else if (starts_with(greek_mu)) pos_ += greek_mu.size();
    while (!at_end() && is_ascii_letter(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  bool at_multiply_sign(std::size_t* width) const {
    if (starts_with("*")) { *width = 1; return true; }
    if (starts_with("\xC2\xB7")) { *width = 2; return true; }      // middle dot U+00B7
    if (starts_with("\xE2\x8B\x85")) { *width = 3; return true; }  // dot operator U+22C5
    return false;
  }

  [[noreturn]] void unknown_unit(std::string_view symbol) const {
    std::string msg = cat("unknown unit '", symbol, "'");
    std::string hints;
    for (const UnitDef& u : unit_table) {
      if (iequals(u.symbol, symbol)) {
        hints.append(hints.empty() ? "'" : " or '").append(u.symbol).append("'");
      }
    }
    if (!hints.empty()) msg.append(cat(" (units are case-sensitive; did you mean ", hints, "?)"));
    else if (symbol == "t") msg.append(" (tonnes are not supported; use kg)");
    throw UnitError(cat(msg, " in '", text_, "'"));
  }

  void parse_units(ParseResult& r) {
    skip_space();
    if (at_end()) return;
    r.has_unit = true;

    // The SI factor is accumulated as num/den (see UnitDef) and applied once at the end.
    double num = 1.0, den = 1.0;
    int exp[4] = {0, 0, 0, 0};  // mass, length, time, angle
    bool in_denominator = false;
    bool have_factor = false;             // at least one factor so far
    std::string_view pending_op;           // "*" or "/" awaiting its right operand
    std::string_view last_symbol;

    while (true) {
      skip_space();
      if (at_end()) {
        if (!pending_op.empty()) fail(cat("missing unit after '", pending_op, "'"));
        break;
      }
      std::size_t w = 0;
      if (text_[pos_] == '/') {
        if (pending_op == "*") fail("'/' directly after '*'");
        if (pending_op == "/") fail("missing unit between '/' and '/'");
        in_denominator = true;
        pending_op = "/";
        ++pos_;
        continue;
      }
      if (at_multiply_sign(&w)) {
        if (!have_factor) fail(cat("'", text_.substr(pos_, w), "' without a unit before it"));
        if (!pending_op.empty())
          fail(cat("missing unit after '", pending_op, "'"));
        pending_op = "*";
        pos_ += w;
        continue;
      }

      // "1/s": a literal 1 as the whole numerator.
      if (!have_factor && !in_denominator && text_[pos_] == '1') {
        std::size_t save = pos_;
        ++pos_;
        skip_space();
        if (!at_end() && text_[pos_] == '/') continue;  // the '/' is handled above
        pos_ = save;
      }

      std::size_t sym_pos = pos_;
      std::string_view symbol = read_symbol();
      if (symbol.empty()) {
        std::string c = char_at(sym_pos);
        if (have_factor && pending_op.empty())
          fail(cat("unexpected '", c, "' after '", last_symbol, "'"));
        fail(cat("unexpected '", c, "' where a unit was expected"));
      }
      const UnitDef* unit = find_unit(symbol);
      if (unit == nullptr) unknown_unit(symbol);
      int e = parse_exponent(symbol);
      if (in_denominator) e = -e;

      const Dimension d = unit->dim;
      const int parts[4] = {d.mass, d.length, d.time, d.angle};
      for (int k = 0; k < 4; ++k) {
        exp[k] += parts[k] * e;
        if (exp[k] > 99 || exp[k] < -99) fail("unit exponent too large");
      }
      for (int k = 0; k < (e < 0 ? -e : e); ++k) {
        (e < 0 ? den : num) *= unit->mul;
        (e < 0 ? num : den) *= unit->div;
      }

      have_factor = true;
      pending_op = {};
      last_symbol = text_.substr(sym_pos, pos_ - sym_pos);

      // The next thing must be a separator or the end: "cms" is one (unknown) symbol, "m2" is wrong.
      if (at_end()) break;
      if (space_width_at(pos_) != 0 || text_[pos_] == '/' || at_multiply_sign(&w)) continue;
      std::string c = char_at(pos_);
      if (is_digit(text_[pos_]) || text_[pos_] == '-')
        fail(cat("unexpected '", c, "' after '", last_symbol, "' (write exponents as ", symbol,
                 "^2 or ", symbol, "\xC2\xB2)"));
      fail(cat("unexpected '", c, "' after '", last_symbol, "'"));
    }

    if (!have_factor) fail("missing unit after '/'");
    const double v = r.q.value * num / den;
    if (!std::isfinite(v) || (v == 0.0 && r.q.value != 0.0))
      fail("value out of the range of double after unit conversion");
    r.q.value = v;
    r.q.dim = Dimension{static_cast<std::int8_t>(exp[0]), static_cast<std::int8_t>(exp[1]),
                        static_cast<std::int8_t>(exp[2]), static_cast<std::int8_t>(exp[3])};
  }
};

struct NamedDimension {
  Dimension dim;
  std::string_view name;
  std::string_view example;
};

constexpr NamedDimension named_dimensions[] = {
    {dims::dimensionless, "dimensionless number", "0.5"},
    {dims::length, "length", "mm"},
    {dims::mass, "mass", "g"},
    {dims::time, "time", "s"},
    {dims::angle, "angle", "deg or rad"},
    {dims::velocity, "velocity", "m/s"},
    {dims::acceleration, "acceleration", "m/s^2"},
    {dims::force, "force", "N"},
    {dims::stiffness, "stiffness (force per length)", "kN/mm"},
    {dims::pressure, "pressure or 2D stiffness per unit thickness", "MPa"},
    {dims::density, "density", "g/cm^3"},
    {dims::damping, "damping coefficient (force\xC2\xB7time per length)", "N*s/m"},
    {dims::damping_per_thickness, "damping per unit thickness (pressure\xC2\xB7time)", "Pa*s"},
    {dims::frequency, "frequency", "Hz"},
    {dims::energy, "energy", "J"},
    {dims::angular_velocity, "angular velocity", "rad/s"},
};

const NamedDimension* find_named(Dimension d) {
  for (const auto& n : named_dimensions)
    if (n.dim == d) return &n;
  return nullptr;
}

std::string with_article(std::string_view name) {
  const bool vowel = !name.empty() && std::string_view("aeiou").find(name[0]) != std::string_view::npos;
  return cat(vowel ? "an " : "a ", name);
}

std::string superscript(int n) {
  static constexpr std::array<std::string_view, 10> digits{
      "\xE2\x81\xB0", "\xC2\xB9", "\xC2\xB2", "\xC2\xB3", "\xE2\x81\xB4",
      "\xE2\x81\xB5", "\xE2\x81\xB6", "\xE2\x81\xB7", "\xE2\x81\xB8", "\xE2\x81\xB9"};
  std::string s = std::to_string(n);
  std::string out;
  for (char c : s) out += digits[static_cast<std::size_t>(c - '0')];
  return out;
}

std::string expected_text(Dimension expected) {
  if (const auto* n = find_named(expected))
    return cat("expected ", with_article(n->name), " (e.g. ", n->example, ")");
  return cat("expected a quantity in ", to_string(expected));
}

[[noreturn]] void reject_bare_angle(std::string_view number_text) {
  throw UnitError(cat(expected_text(dims::angle), ", got the bare number '", number_text,
                      "': write the angle unit explicitly, e.g. '", number_text, " deg' or '",
                      number_text, " rad'"));
}

}  // namespace

std::string to_string(Dimension d) {
  static constexpr std::array<std::string_view, 4> symbols{"kg", "m", "s", "rad"};
  const int e[4] = {d.mass, d.length, d.time, d.angle};
  std::string num, den;
  int den_count = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    if (e[k] == 0) continue;
    std::string& out = e[k] > 0 ? num : den;
    if (!out.empty()) out.append("\xC2\xB7");  // ·
    out.append(symbols[k]);
    const int a = e[k] > 0 ? e[k] : -e[k];
    if (a != 1) out += superscript(a);
    if (e[k] < 0) ++den_count;
  }
  if (num.empty()) num.push_back('1');
  if (den.empty()) return num;
  if (den_count > 1) return cat(num, "/(", den, ")");
  return cat(num, "/", den);
}

std::string describe(Dimension d) {
  if (const auto* n = find_named(d)) return std::string(n->name);
  return to_string(d);
}

Quantity parse_quantity(std::string_view text) { return Parser(text).run().q; }

double to_si(std::string_view text, Dimension expected) {
  const ParseResult r = Parser(text).run();
  if (!r.has_unit) {
    if (expected == dims::angle) {
      std::size_t b = text.find_first_not_of(" \t\r\n");
      std::size_t e = text.find_last_not_of(" \t\r\n");
      reject_bare_angle(b == std::string_view::npos ? text : text.substr(b, e - b + 1));
    }
    return r.q.value;
  }
  if (r.q.dim != expected) {
    std::string got = to_string(r.q.dim);
    if (const auto* n = find_named(r.q.dim)) got.append(cat(" (", n->name, ")"));
    throw UnitError(cat(expected_text(expected), ", got ", got, " from '", text, "'"));
  }
  return r.q.value;
}

double to_si(double plain_number, Dimension expected) {
  if (!std::isfinite(plain_number)) {
    throw UnitError(cat(expected_text(expected), ", got the non-finite number ",
                        std::isnan(plain_number) ? "nan" : plain_number > 0 ? "inf" : "-inf"));
  }
  if (expected == dims::angle) {
    char buf[32];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, plain_number);
    reject_bare_angle(ec == std::errc{} ? std::string_view(buf, static_cast<std::size_t>(ptr - buf))
                                        : std::string_view("?"));
  }
  return plain_number;
}

}  // namespace dem
