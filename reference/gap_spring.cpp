// A gap spring stretched at constant speed (ref/gap_spring.hpp).
#include "ref/gap_spring.hpp"

#include "ref/require.hpp"

namespace ref {

double gap_pull_force(double k, double eta, double v, double t, double strength) {
  constexpr const char* where = "ref::gap_pull_force";
  detail::require_positive(where, "k", k);
  detail::require_non_negative(where, "eta", eta);
  detail::require_positive(where, "v", v);
  detail::require_non_negative(where, "t", t);
  detail::require_positive(where, "strength", strength);
  const double elastic = k * v * t;  // the spring's share (B2): its stretch v t times k
  return elastic > strength ? 0.0 : elastic + eta * v;  // broken past its strength (B4), else spring + dashpot (B3)
}

double gap_break_time(double k, double v, double strength) {
  constexpr const char* where = "ref::gap_break_time";
  detail::require_positive(where, "k", k);
  detail::require_positive(where, "v", v);
  detail::require_positive(where, "strength", strength);
  return strength / (k * v);
}

}  // namespace ref
