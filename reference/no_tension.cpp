// Active-set solve of unilateral contacts (see ref/no_tension.hpp).
#include "ref/no_tension.hpp"

#include <algorithm>
#include <cmath>

#include "ref/require.hpp"

namespace ref {

namespace {
void set_contact(RigidSpringNetwork& net, const UnilateralContact& c, bool closed) {
  net.set_active(c.normal, closed);
  if (c.tangential >= 0) net.set_active(c.tangential, closed);
}
}  // namespace

NoTensionSolution solve_no_tension(RigidSpringNetwork& net, const std::vector<UnilateralContact>& contacts) {
  constexpr const char* fn = "solve_no_tension";
  constexpr double tol = 1e-12;
  NoTensionSolution out;
  out.open.assign(contacts.size(), false);
  for (const UnilateralContact& c : contacts) {
    if (c.normal < 0) detail::fail(fn, "a contact needs its normal spring", c.normal);
    set_contact(net, c, true);
  }
  const int max_solves = 4 * (static_cast<int>(contacts.size()) + 1);
  for (out.iterations = 1; out.iterations <= max_solves; ++out.iterations) {
    out.u = net.solve();
    double f_scale = 0.0, u_scale = 0.0;
    for (const UnilateralContact& c : contacts) f_scale = std::max(f_scale, std::abs(net.spring_force(out.u, c.normal)));
    for (double v : out.u) u_scale = std::max(u_scale, std::abs(v));
    // the closed contact pulling hardest opens; an open one that would penetrate closes
    int worst = -1;
    double worst_f = tol * f_scale;
    bool changed = false;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      if (out.open[i]) {
        if (net.extension(out.u, contacts[i].normal) < -tol * u_scale) {
          out.open[i] = false;
          set_contact(net, contacts[i], true);
          changed = true;
        }
      } else if (const double f = net.spring_force(out.u, contacts[i].normal); f > worst_f) {
        worst_f = f;
        worst = static_cast<int>(i);
      }
    }
    if (worst >= 0) {
      out.open[static_cast<std::size_t>(worst)] = true;
      set_contact(net, contacts[static_cast<std::size_t>(worst)], false);
      changed = true;
    }
    if (!changed) return out;
  }
  detail::fail(fn, "the active set did not settle; solves", max_solves);
}

}  // namespace ref
