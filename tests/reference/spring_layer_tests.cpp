// The uniform spring layer's bending moment (ref/spring_layer.hpp) against a direct quadrature of the
// layer, and through the registry.
#include <catch2/catch.hpp>

#include "ref/registry.hpp"
#include "ref/spring_layer.hpp"

using Catch::Matchers::WithinRel;

TEST_CASE("spring layer: M = k a² θ / 3 equals the integral of the compressed layer", "[spring_layer]") {
  const double k = 2.5e7, a = 0.0125, theta = 1e-4;
  // Midpoint rule with many strips: Σ s (k/2a)(s θ) Δs over [−a, a].
  const int n = 200000;
  double m = 0.0;
  for (int i = 0; i < n; ++i) {
    const double s = -a + (i + 0.5) * (2.0 * a / n);
    m += s * (k / (2.0 * a)) * s * theta * (2.0 * a / n);
  }
  CHECK_THAT(ref::spring_layer_moment(k, a, theta), WithinRel(m, 1e-9));
  CHECK_THAT(ref::evaluate("face.bending_moment", {{"k", k}, {"a", a}, {"theta", theta}}), WithinRel(m, 1e-9));
  CHECK_THROWS(ref::spring_layer_moment(-1.0, a, theta));
}
