// The Lanczos eigenvalue of the bonded-structure guard (stability_eigen.cpp, docs/model.md G2) on a
// network built by hand whose spectrum is known: a chain of n bodies joined by axial springs k and held
// by a spring at each end. Its x block is (k/m)·tridiag(−1, 2, −1), λ_max = (k/m)(2 + 2cos(π/(n+1))).
// n = 40 bodies (120 DOFs) needs Lanczos steps beyond the first Ritz check (every 10 steps), so the
// tridiagonal eigen-solver runs on matrices of 10 to 100 rows. Planted bug: its forward elimination
// started at row 0 (reading before three arrays, g728335-013) throws here (checked access).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "dem/core/stability_eigen.hpp"

using Catch::Matchers::WithinRel;

namespace {

dem::StartNetwork spring_chain(int n, double k, double mass) {
  dem::StartNetwork net;
  net.dofs = 3 * n;
  const double s = 1.0 / std::sqrt(mass);  // mass-normalised lever of an x translation
  for (int i = 0; i <= n; ++i) {           // n + 1 springs: ground, 0–1, …, (n−1)–ground
    dem::NetworkSpring sp;
    sp.k = k;
    if (i > 0) sp.dof_a = 3 * (i - 1), sp.ba[0] = -s;
    if (i < n) sp.dof_b = 3 * i, sp.bb[0] = s;
    net.springs.push_back(sp);
  }
  return net;
}

}  // namespace

TEST_CASE("The guard's eigenvalue of a spring chain is (k/m)(2 + 2cos(pi/(n+1)))", "[stability]") {
  for (const auto& [n, k, mass] : {std::tuple{40, 1e5, 0.5}, std::tuple{7, 3e6, 2.0}}) {
    CAPTURE(n, k, mass);
    const dem::StartNetwork net = spring_chain(n, k, mass);
    const double exact = k / mass * (2.0 + 2.0 * std::cos(std::numbers::pi / (n + 1)));
    const double lambda = dem::network_eigenvalue(net, false, false);
    CHECK(lambda >= exact * (1.0 - 1e-12));  // an upper estimate (Ritz value plus its residual)
    CHECK_THAT(lambda, WithinRel(exact, 1e-6));
  }
}
