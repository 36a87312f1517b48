#pragma once
// Argument checks shared by the reference solvers. Every public function of ref:: validates its
// inputs and throws std::invalid_argument naming the function and the offending argument.

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ref::detail {

[[noreturn]] inline void fail(std::string_view where, std::string_view what, double value) {
  std::ostringstream message;
  message.precision(10);
  message << where << ": " << what << " (got " << value << ")";
  throw std::invalid_argument(message.str());
}

inline void require_finite(std::string_view where, std::string_view name, double value) {
  if (!std::isfinite(value)) fail(where, std::string(name) + " must be finite", value);
}

inline void require_positive(std::string_view where, std::string_view name, double value) {
  if (!(std::isfinite(value) && value > 0.0))
    fail(where, std::string(name) + " must be finite and > 0", value);
}

inline void require_non_negative(std::string_view where, std::string_view name, double value) {
  if (!(std::isfinite(value) && value >= 0.0))
    fail(where, std::string(name) + " must be finite and >= 0", value);
}

}  // namespace ref::detail
