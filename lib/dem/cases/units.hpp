#pragma once
// Physical quantities as written in case files: "25 mm", "12 kN/mm", "750 kgf/cm^2", "38 deg".
//
// Values are converted to SI (kg, m, s, rad). Each quantity carries a Dimension (exponents of mass,
// length, time and angle) so that a case file cannot give, e.g., an angle where a length is expected.
// Angle is a separate pseudo-dimension: "38 deg" and "0.66 rad" are angles, and a bare number is
// accepted for an angle only if the unit is explicit (see to_si).
//
// Syntax accepted by parse_quantity (leading/trailing whitespace ignored):
//   quantity := number [unit-expression]
//   number   := std::from_chars general format with an optional leading '+' ("-9.80665", "1e-6",
//               ".5", "3.64e4"); NaN, infinities and values outside the double range are rejected.
//   unit-expression := factors separated by '*', '·' (U+00B7), '⋅' (U+22C5) or whitespace
//               (space, tab, U+00A0, U+202F), with '/' for division.
//               Division rule (kept simple): every factor after the FIRST '/' is in the denominator,
//               so "N/mm/s" = N/(mm·s) and "N·s/m m" = N·s/m². Brackets are not supported.
//               A leading "1/" or "/" means "one over": "5 1/s" = "5 /s" = 5 Hz.
//   factor   := symbol [exponent]; exponent := '^' ['+'|'-'] digits | ['⁻'] ('¹'|'²'|'³')
//               ("mm^2", "m^-3", "mm²", "cm³"). The exponent binds to the (prefixed) symbol:
//               "cm^3" = (0.01 m)^3.
//   Symbols are case-sensitive and must be separated from each other ("cms" is not "cm s").
//
// Supported symbols (SI factor):
//   length:   m, cm, mm, um, µm, μm (micro sign U+00B5 or Greek mu U+03BC), km
//   mass:     g, kg                      (no "t": too easily confused with time)
//   time:     s, ms, us, µs, μs, min (60 s), h (3600 s)
//   force:    N, kN, MN, mN, dyn (1e-5 N),
//             kgf (9.80665 N), gf (9.80665e-3 N), tf (9806.65 N) -- standard gravity
//             g_n = 9.80665 m/s² exactly, by definition (CGPM 1901)
//   pressure: Pa, kPa, MPa, GPa, bar (1e5 Pa)
//   energy:   J
//   angle:    rad, deg, ° (pi/180 rad)
//   frequency: Hz (1/s)

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace dem {

/// Exponents of mass (kg), length (m), time (s) and the angle pseudo-dimension (rad).
struct Dimension {
  std::int8_t mass = 0;
  std::int8_t length = 0;
  std::int8_t time = 0;
  std::int8_t angle = 0;

  friend constexpr bool operator==(const Dimension&, const Dimension&) = default;
};

constexpr Dimension operator*(Dimension a, Dimension b) {
  return {static_cast<std::int8_t>(a.mass + b.mass), static_cast<std::int8_t>(a.length + b.length),
          static_cast<std::int8_t>(a.time + b.time), static_cast<std::int8_t>(a.angle + b.angle)};
}
constexpr Dimension operator/(Dimension a, Dimension b) {
  return {static_cast<std::int8_t>(a.mass - b.mass), static_cast<std::int8_t>(a.length - b.length),
          static_cast<std::int8_t>(a.time - b.time), static_cast<std::int8_t>(a.angle - b.angle)};
}
constexpr Dimension power(Dimension a, int n) {  // not "pow": would hide ::pow in namespace dem
  return {static_cast<std::int8_t>(a.mass * n), static_cast<std::int8_t>(a.length * n),
          static_cast<std::int8_t>(a.time * n), static_cast<std::int8_t>(a.angle * n)};
}

/// Named dimensions. (In a nested namespace because Dimension's members are already called
/// mass/length/time/angle.)
namespace dims {
inline constexpr Dimension dimensionless{0, 0, 0, 0};
inline constexpr Dimension mass{1, 0, 0, 0};
inline constexpr Dimension length{0, 1, 0, 0};
inline constexpr Dimension time{0, 0, 1, 0};
inline constexpr Dimension angle{0, 0, 0, 1};
inline constexpr Dimension velocity = length / time;                        // m/s
inline constexpr Dimension acceleration = velocity / time;                  // m/s²
inline constexpr Dimension force = mass * acceleration;                     // N
inline constexpr Dimension stiffness = force / length;                      // N/m
inline constexpr Dimension force_per_length = stiffness;                    // N/m
inline constexpr Dimension pressure = force / (length * length);            // Pa; also 2D stiffness per thickness
inline constexpr Dimension density = mass / (length * length * length);     // kg/m³
inline constexpr Dimension damping = force * time / length;                 // N·s/m = kg/s
inline constexpr Dimension damping_per_thickness = pressure * time;         // N·s/m² = Pa·s
inline constexpr Dimension frequency = dimensionless / time;                // 1/s
inline constexpr Dimension energy = force * length;                         // J
inline constexpr Dimension angular_velocity = angle / time;                 // rad/s
}  // namespace dims

/// SI symbol form: "kg·m/s²", "kg/(m·s²)", "rad/s", "1/s"; "1" for dimensionless.
std::string to_string(Dimension d);

/// Human name for the named dimensions ("length", "stiffness (force per length)",
/// "pressure or 2D stiffness per unit thickness", ...); to_string(d) for any other dimension.
std::string describe(Dimension d);

/// A value in SI units (kg, m, s, rad) with its dimension.
struct Quantity {
  double value = 0.0;
  Dimension dim{};
};

/// Thrown for malformed quantities, unknown units and dimension mismatches. The message names the
/// problem and quotes the offending text, e.g. "unknown unit 'mmm' in '12 mmm'".
class UnitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses "number [unit-expression]" (grammar above) into SI. A bare number ("1e-6") gives a
/// dimensionless quantity. Throws UnitError.
Quantity parse_quantity(std::string_view text);

/// Parses `text` and returns its SI value, checking that its dimension is `expected`; on mismatch
/// throws UnitError("expected a <describe(expected)> (e.g. <unit>), got <dim> from '<text>'").
/// A bare number without a unit is taken as already SI for any expected dimension except
/// dims::angle, where it is rejected (write "38 deg" or "0.66 rad").
double to_si(std::string_view text, Dimension expected);

/// Every unit symbol parse_quantity knows ("m", "kgf", "\u00b0", ...), for the case schema's pattern.
std::vector<std::string> unit_symbols();

/// For plain numbers in case files (already SI): returns `plain_number` unchanged, except that it is
/// rejected (UnitError) if expected == dims::angle (unit must be explicit) or if it is not finite.
double to_si(double plain_number, Dimension expected);

}  // namespace dem
