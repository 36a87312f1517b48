// The Owen-scrambled Sobol' design (no origin artefact), second-order indices on Ishigami and the
// g-function, and the Morris bootstrap intervals (verification/engine/sensitivity_*; issue 36).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <set>

#include "engine/sensitivity_estimators.hpp"
#include "engine/sensitivity_functions.hpp"
#include "engine/sensitivity_sampling.hpp"
#include "engine/sensitivity_second_order.hpp"

using namespace ver::sens;

namespace {

using Model = std::function<double(const std::vector<double>&)>;

struct Outputs {
  std::vector<double> fa, fb;
  std::vector<std::vector<double>> fab, fba;
};

Outputs on_design(const Model& f, std::size_t n, std::size_t d, std::uint64_t scramble, bool second) {
  const SaltelliDesign des = saltelli_design(n, d, scramble, second);
  Outputs y;
  y.fab.resize(d);
  y.fba.resize(second ? d : 0);
  for (std::size_t j = 0; j < n; ++j) {
    y.fa.push_back(f(des.a[j]));
    y.fb.push_back(f(des.b[j]));
    for (std::size_t i = 0; i < d; ++i) y.fab[i].push_back(f(des.ab[i][j]));
    for (std::size_t i = 0; i < y.fba.size(); ++i) y.fba[i].push_back(f(des.ba[i][j]));
  }
  return y;
}

// A heavy corner: f is largest by far at the origin of (x1, x2); x3 has no effect at all.
double corner(const std::vector<double>& u) { return 1.0 / ((u[0] + u[1] + 1e-3) * (u[0] + u[1] + 1e-3)); }

double ishigami(const std::vector<double>& u) {
  const double pi = std::numbers::pi;
  return evaluate({"ishigami", {7.0, 0.1}}, {-pi + 2 * pi * u[0], -pi + 2 * pi * u[1], -pi + 2 * pi * u[2]});
}

const std::vector<double> g_coefficients = {0.0, 1.0, 4.5, 9.0, 99.0, 99.0};
double g_function(const std::vector<double>& u) { return evaluate({"g", g_coefficients}, u); }

}  // namespace

TEST_CASE("Owen-scrambled Sobol points: reproducible for a seed and different between seeds, inside the open cube", "[sensitivity]") {
  const Matrix a = sobol_points(256, 6, 5), b = sobol_points(256, 6, 5), c = sobol_points(256, 6, 6);
  CHECK(a == b);
  CHECK(a != c);
  for (const auto& row : a)
    for (double x : row) {
      CHECK(x > 0.0);
      CHECK(x < 1.0);
    }
  // Scrambling keeps the net: the first two axes (t = 0) put one of 256 points in each 16 × 16 cell.
  std::set<int> cells;
  for (const auto& row : a) cells.insert(static_cast<int>(row[0] * 16) * 16 + static_cast<int>(row[1] * 16));
  CHECK(cells.size() == 256);
}

TEST_CASE("Sobol design: an input without effect has S and S(Janon) near 0 and S at most S_T, not near 1 as at the raw origin", "[sensitivity]") {
  const std::size_t n = 256, d = 3;
  // The raw sequence (the old design): row 0 is the origin in A, B and every AB_i, where f = 1e6; that
  // one row makes f(A) and f(B) look correlated and Janon's index of the inert x3 read near 1.
  const Outputs raw = on_design(corner, n, d, kUnscrambled, false);
  const SobolIndices r = sobol_indices(raw.fa, raw.fb, raw.fab, 0);
  CHECK(r.total[2].estimate == 0.0);        // x3 changes nothing: f(AB_3) = f(A) row by row
  CHECK(r.first_janon[2].estimate > 0.5);   // the artefact
  // Owen-scrambled (three seeds): no common point; the inert input's first-order indices are noise
  // around 0 and within their interval of S_T = 0.
  for (std::uint64_t seed : {1, 2, 3}) {
    const Outputs y = on_design(corner, n, d, seed, false);
    const SobolIndices s = sobol_indices(y.fa, y.fb, y.fab, 1000);
    INFO("seed " << seed << ": S(Janon) " << s.first_janon[2].estimate << " [" << s.first_janon[2].low << ", " << s.first_janon[2].high
                 << "], S " << s.first[2].estimate);
    CHECK(s.total[2].estimate == 0.0);
    CHECK(std::abs(s.first_janon[2].estimate) < 0.1);
    CHECK(s.first_janon[2].low <= 0.0);
    CHECK(s.first[2].low <= s.total[2].estimate);
  }
}

/// Every S_ij within `tol` of the exact value, and inside its bootstrap interval.
template <class Indices>
void check_second_order(const Indices& s2, const ExactIndices& ex, double tol) {
  for (const auto& p : s2) {
    const double exact = ex.second[p.i][p.j];
    INFO("S" << p.i + 1 << p.j + 1 << " = " << p.s2.estimate << " [" << p.s2.low << ", " << p.s2.high << "], exact " << exact);
    CHECK(std::abs(p.s2.estimate - exact) <= tol);
    CHECK(p.s2.low <= exact);
    CHECK(exact <= p.s2.high);
  }
}

TEST_CASE("Second-order Sobol indices: Ishigami S13 = 0.2437 and S12 = S23 = 0 within 0.05 and the bootstrap interval", "[sensitivity]") {
  // Tolerance 0.05: SALib's own test of its second-order estimator on Ishigami accepts ±0.05; N = 4096.
  const double pi = std::numbers::pi;
  const ExactIndices ex = exact_indices({"ishigami", {7.0, 0.1}}, {-pi, -pi, -pi}, {pi, pi, pi});
  REQUIRE(ex.second[0][2] == Approx(0.2437).margin(5e-5));
  const Outputs y = on_design(ishigami, 4096, 3, 1, true);
  const auto s2 = sobol_second_order(y.fa, y.fb, y.fab, y.fba, 300);
  REQUIRE(s2.size() == 3);
  check_second_order(s2, ex, 0.05);
}

TEST_CASE("Second-order Sobol indices: g-function S_ij = V_i V_j / V within 0.01 and the bootstrap interval", "[sensitivity]") {
  // Tolerance 0.01: SALib's own tolerance on the g-function; the largest, S_12, is 0.0597 here.
  const ExactIndices ex = exact_indices({"g", g_coefficients}, std::vector<double>(6, 0.0), std::vector<double>(6, 1.0));
  REQUIRE(ex.second[0][1] == Approx((1.0 / 3.0) * (1.0 / 12.0) / 0.465326).epsilon(1e-5));  // V_1 V_2 / V
  const Outputs y = on_design(g_function, 8192, 6, 1, true);
  const auto s2 = sobol_second_order(y.fa, y.fb, y.fab, y.fba, 300);
  REQUIRE(s2.size() == 15);
  check_second_order(s2, ex, 0.01);
}

TEST_CASE("Morris bootstrap: zero width for a linear model, the SALib half-width z sd(|EE|)/sqrt(r) otherwise", "[sensitivity]") {
  const std::size_t r = 400, d = 2;
  const auto tr = morris_trajectories(r, d, 4, 7);
  auto outputs = [&](const Model& f) {
    std::vector<std::vector<double>> out(r);
    for (std::size_t t = 0; t < r; ++t)
      for (const auto& p : tr[t].points) out[t].push_back(f(p));
    return out;
  };
  // Linear: every effect is the coefficient, every resample the same μ*.
  const MorrisEffects lin = morris_effects(tr, outputs([](const std::vector<double>& u) { return 3.0 * u[0] - 2.0 * u[1]; }), d, 500);
  CHECK(lin.mu_star_ci[0].low == Approx(3.0));
  CHECK(lin.mu_star_ci[0].high == Approx(3.0));
  CHECK(lin.mu_star_conf[1] == Approx(0.0).margin(1e-12));
  // f = x1²: the effect of x1 between grid points a and b is (b² − a²)/(b − a) = a + b, which varies
  // from trajectory to trajectory; the bootstrap sd of μ* is sd(|EE|)/√r (sd over the effects drawn).
  const MorrisEffects q = morris_effects(tr, outputs([](const std::vector<double>& u) { return u[0] * u[0]; }), d, 4000);
  std::vector<double> ee;
  for (std::size_t t = 0; t < r; ++t)
    for (std::size_t k = 0; k < d; ++k)
      if (tr[t].order[k] == 0) {
        const double a = tr[t].points[k][0], b = tr[t].points[k + 1][0];
        ee.push_back(std::abs((b * b - a * a) / (b - a)));
      }
  double m = 0.0, v = 0.0;
  for (double e : ee) m += e;
  m /= static_cast<double>(ee.size());
  for (double e : ee) v += (e - m) * (e - m);
  const double sd = std::sqrt(v / static_cast<double>(ee.size()));
  CHECK(q.mu_star[0] == Approx(m).epsilon(1e-12));
  // Bootstrap of 4000 resamples: its sd has relative noise about 1/√(2 × 4000) = 1.1 %; 5 % allowed.
  CHECK(q.mu_star_conf[0] == Approx(1.959964 * sd / std::sqrt(static_cast<double>(ee.size()))).epsilon(0.05));
  CHECK(q.mu_star_ci[0].low < m);
  CHECK(q.mu_star_ci[0].high > m);
  CHECK(q.mu_star_ci[0].high - q.mu_star_ci[0].low == Approx(2.0 * q.mu_star_conf[0]).epsilon(0.1));  // percentile ≈ normal here
}
