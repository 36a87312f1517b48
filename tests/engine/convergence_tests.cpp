// Unit tests of the convergence analysis (verification/engine/convergence.hpp) on synthetic
// sequences Q(h) = Q* + C h^p (+ D h^(p+1)), Celik et al. (2008)'s worked example and bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "engine/convergence.hpp"

namespace {

std::vector<double> power_law(const std::vector<double>& h, double exact, double c, double p,
                              double d = 0.0) {
  std::vector<double> q;
  for (double hk : h) q.push_back(exact + c * std::pow(hk, p) + d * std::pow(hk, p + 1.0));
  return q;
}

std::vector<double> halving(double h0, int levels) {
  std::vector<double> h;
  for (int k = 0; k < levels; ++k) h.push_back(h0 / std::pow(2.0, k));
  return h;
}

const std::vector<double> varying_h{0.1, 0.07, 0.04, 0.025, 0.012};  // r = 1.43, 1.75, 1.6, 2.08

}  // namespace

TEST_CASE("pure power law: orders recovered, Richardson exact, asymptotic", "[convergence]") {
  const double p = GENERATE(1.0, 2.0, 3.0);
  const bool constant_ratio = GENERATE(true, false);
  CAPTURE(p, constant_ratio);
  const auto h = constant_ratio ? halving(0.1, 5) : varying_h;
  const double exact = 0.75;
  const auto q = power_law(h, exact, 0.4, p);

  ver::ConvergenceOptions options;
  options.reference = exact;
  options.expected_order = p;
  const auto s = ver::analyse_convergence(h, q, options, "Q", "h [-]");

  REQUIRE(s.observed_order.size() == h.size());
  CHECK_FALSE(s.observed_order[0]);
  for (std::size_t k = 1; k < h.size(); ++k) {
    REQUIRE(s.observed_order[k]);
    CHECK(*s.observed_order[k] == Approx(p).margin(1e-9));
  }
  REQUIRE(s.fitted_order);
  CHECK(*s.fitted_order == Approx(p).margin(1e-9));
  REQUIRE(s.three_level_order);
  CHECK(*s.three_level_order == Approx(p).margin(1e-8));
  CHECK(s.extrapolation_order_source == ver::OrderSource::three_level);
  REQUIRE(s.richardson);
  CHECK(*s.richardson == Approx(exact).epsilon(1e-11));
  CHECK_FALSE(s.errors_against_richardson);
  CHECK(s.safety_factor == 1.25);
  // For a pure power law the GCI ratio is Q_fine/Q_medium (relative GCIs), i.e. ~1.
  REQUIRE(s.asymptotic_ratio);
  CHECK(*s.asymptotic_ratio == Approx(q[q.size() - 1] / q[q.size() - 2]).epsilon(1e-9));
  CHECK(*s.asymptotic_ratio == Approx(1.0).margin(0.01));
  CHECK(s.asymptotic == true);
  for (std::size_t k = 0; k < h.size(); ++k) {
    REQUIRE(s.error[k]);
    CHECK(*s.error[k] == Approx(0.4 * std::pow(h[k], p)).epsilon(1e-9));
    REQUIRE(s.relative_error[k]);
    CHECK(*s.relative_error[k] == Approx(*s.error[k] / exact).epsilon(1e-14));
  }
  const auto check = ver::check_order(s, p, 0.01);
  CHECK(check.passed);
  CHECK(check.estimate.find("levels 0-4") != std::string::npos);
}

TEST_CASE("power law with a higher-order term: orders tend to p", "[convergence]") {
  const double p = GENERATE(1.0, 2.0, 3.0);
  CAPTURE(p);
  const auto h = halving(0.1, 6);
  const auto q = power_law(h, 1.0, 1.0, p, 1.0);  // e = h^p (1 + h): p_k = p + log2((1+2h)/(1+h))

  ver::ConvergenceOptions options;
  options.reference = 1.0;
  const auto s = ver::analyse_convergence(h, q, options);
  for (std::size_t k = 2; k < h.size(); ++k)
    CHECK(std::abs(*s.observed_order[k] - p) < std::abs(*s.observed_order[k - 1] - p));
  const double expected_finest = p + std::log2((1.0 + 2.0 * h[5]) / (1.0 + h[5]));
  CHECK(*s.observed_order[5] == Approx(expected_finest).margin(1e-9));
  CHECK(std::abs(*s.observed_order[5] - p) < 0.005);
  REQUIRE(s.fitted_order);
  CHECK(std::abs(*s.fitted_order - p) < 0.05);
  CHECK(ver::check_order(s, p, 0.05).passed);
  CHECK_FALSE(ver::check_order(s, p, 0.001).passed);

  SECTION("fit over the finest levels only is closer to p") {
    options.fit_levels = {3, 4, 5};
    const auto fine = ver::analyse_convergence(h, q, options);
    CHECK(std::abs(*fine.fitted_order - p) < std::abs(*s.fitted_order - p));
    CHECK(std::abs(*fine.fitted_order - p) < 0.01);
    CHECK(ver::check_order(fine, p, 0.01).estimate.find("levels 3-5") != std::string::npos);
  }
  SECTION("Richardson with the observed order beats the finest level") {
    REQUIRE(s.richardson);
    CHECK(std::abs(*s.richardson - 1.0) < 0.1 * *s.error[5]);
  }
}

TEST_CASE("no reference: errors against Richardson of the finest three levels", "[convergence]") {
  const double p = GENERATE(1.0, 2.0, 3.0);
  const bool constant_ratio = GENERATE(true, false);
  CAPTURE(p, constant_ratio);
  const auto h = constant_ratio ? halving(0.2, 4) : varying_h;
  const auto q = power_law(h, -2.5, 3.0, p);
  const auto s = ver::analyse_convergence(h, q);

  CHECK(s.errors_against_richardson);
  CHECK_FALSE(s.reference);
  REQUIRE(s.richardson);
  CHECK(*s.richardson == Approx(-2.5).epsilon(1e-10));
  CHECK_FALSE(s.observed_order[0]);
  CHECK_FALSE(s.observed_order[1]);
  for (std::size_t k = 2; k < h.size(); ++k) CHECK(*s.observed_order[k] == Approx(p).margin(1e-8));
  for (std::size_t k = 0; k < h.size(); ++k)
    CHECK(*s.error[k] == Approx(3.0 * std::pow(h[k], p)).epsilon(1e-7));
  CHECK(*s.fitted_order == Approx(p).margin(1e-7));
  CHECK(ver::check_order(s, p, 0.01).estimate.find("Richardson") != std::string::npos);
  CHECK(ver::to_json(s)["reference"].is_null());
}

TEST_CASE("Celik et al. (2008) worked example, Table 1 (phi = reattachment length)",
          "[convergence]") {
  // N1 = 18000, N2 = 8000, N3 = 4500 cells, h = N^(-1/2) (2D); r21 = 1.5, r32 = 1.333.
  const std::vector<double> h{1.0 / std::sqrt(4500.0), 1.0 / std::sqrt(8000.0),
                              1.0 / std::sqrt(18000.0)};
  const std::vector<double> phi{5.863, 5.972, 6.063};
  const auto s = ver::analyse_convergence(h, phi);

  // The paper's rounded values: p = 1.53, phi_ext = 6.1685, GCI_fine = 2.2 %.
  REQUIRE(s.three_level_order);
  CHECK(*s.three_level_order == Approx(1.53).margin(0.005));
  REQUIRE(s.richardson);
  CHECK(*s.richardson == Approx(6.1685).margin(5e-5));
  REQUIRE(s.gci_fine);
  CHECK(*s.gci_fine == Approx(0.022).margin(5e-4));
  CHECK(s.safety_factor == 1.25);
  // Hand computation (fixed point to convergence, same formulas, double precision).
  CHECK(*s.three_level_order == Approx(1.53396902062819).epsilon(1e-12));
  CHECK(*s.richardson == Approx(6.16849557233016).epsilon(1e-13));
  CHECK(*s.gci_fine == Approx(0.0217498705942109).epsilon(1e-11));
  REQUIRE(s.gci_coarse);
  CHECK(*s.gci_coarse == Approx(0.0411285106183355).epsilon(1e-11));
  REQUIRE(s.asymptotic_ratio);
  CHECK(*s.asymptotic_ratio == Approx(1.01523777628935).epsilon(1e-11));
  CHECK(s.asymptotic == true);  // |1.015 - 1| <= 0.1
  // e_ext^21 = 1.7 % in the paper.
  CHECK(*s.relative_error[2] == Approx(0.0171023179141734).epsilon(1e-10));

  SECTION("tighter asymptotic tolerance flips the flag") {
    ver::ConvergenceOptions options;
    options.asymptotic_tolerance = 0.01;
    CHECK(ver::analyse_convergence(h, phi, options).asymptotic == false);
  }
}

TEST_CASE("two levels: safety factor 3 and an assumed order", "[convergence]") {
  // Hand computed: eps = (0.96854 - 0.9705)/0.9705, GCI = 3 |eps| / (2^2 - 1) = |eps|.
  ver::ConvergenceOptions options;
  options.assumed_order = 2.0;
  const auto s = ver::analyse_convergence({0.2, 0.1}, {0.96854, 0.9705}, options);
  CHECK(s.safety_factor == 3.0);
  CHECK(s.extrapolation_order_source == ver::OrderSource::assumed);
  REQUIRE(s.gci_fine);
  CHECK(*s.gci_fine == Approx((0.9705 - 0.96854) / 0.9705).epsilon(1e-13));
  CHECK(*s.richardson == Approx(0.9705 + (0.9705 - 0.96854) / 3.0).epsilon(1e-14));
  CHECK_FALSE(s.asymptotic_ratio);  // needs three levels
  CHECK_FALSE(s.fitted_order);      // no reference, two levels: errors unknown
  CHECK_FALSE(s.error[0]);
  CHECK_FALSE(ver::check_order(s, 2.0, 1.0).passed);

  SECTION("with a reference the two-level order is used") {
    ver::ConvergenceOptions with_reference;
    with_reference.reference = 1.0;
    const auto t = ver::analyse_convergence({0.2, 0.1}, {1.04, 1.01}, with_reference);
    CHECK(*t.observed_order[1] == Approx(2.0).epsilon(1e-12));
    CHECK(*t.fitted_order == Approx(2.0).epsilon(1e-12));
    CHECK(t.extrapolation_order_source == ver::OrderSource::two_level_reference);
    CHECK(*t.richardson == Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("three-level order with strongly varying ratio (fixed point fails, bisection)",
          "[convergence]") {
  const double p = GENERATE(0.5, 1.0, 2.0, 4.0);
  CAPTURE(p);
  const std::vector<double> h{1.0, 0.1, 0.08};  // r32 = 10, r21 = 1.25
  const auto q = power_law(h, 0.0, 1.0, p);
  const auto order = ver::three_level_order(h[0], h[1], h[2], q[0], q[1], q[2]);
  REQUIRE(order);
  CHECK(*order == Approx(p).margin(1e-8));
}

TEST_CASE("degenerate sequences", "[convergence]") {
  ver::ConvergenceOptions options;
  options.reference = 1.0;

  SECTION("an exactly zero error gives null orders and is skipped by the fit") {
    const auto s = ver::analyse_convergence({1.0, 0.5, 0.25, 0.125},
                                            {2.0, 1.0, 1.0 + 1.0 / 16, 1.0 + 1.0 / 64}, options);
    CHECK(*s.error[1] == 0.0);
    CHECK_FALSE(s.observed_order[1]);
    CHECK_FALSE(s.observed_order[2]);
    CHECK(*s.observed_order[3] == Approx(2.0).epsilon(1e-12));
    CHECK(s.zero_error_levels == std::vector<std::size_t>{1});
    CHECK(s.fit_levels == std::vector<std::size_t>{0, 2, 3});
    CHECK(*s.fitted_order == Approx(2.0).epsilon(1e-12));
    CHECK_FALSE(s.notes.empty());
    const auto j = ver::to_json(s);
    CHECK(j["observed_order"][1].is_null());
    CHECK(j["observed_order"].size() == 4);
  }
  SECTION("non-monotone errors: orders still reported") {
    const auto s = ver::analyse_convergence({0.4, 0.2, 0.1}, {1.1, 1.2, 1.05}, options);
    REQUIRE(s.observed_order[1]);
    CHECK(*s.observed_order[1] == Approx(-1.0).epsilon(1e-12));
    CHECK(*s.observed_order[2] == Approx(2.0).epsilon(1e-12));
    REQUIRE(s.fitted_order);
    bool noted = false;
    for (const auto& note : s.notes) noted |= note.find("monoton") != std::string::npos;
    CHECK(noted);
  }
  SECTION("oscillatory convergence is computed and noted") {
    const auto s = ver::analyse_convergence({0.4, 0.2, 0.1}, {1.4, 0.9, 1.025}, options);
    REQUIRE(s.three_level_order);
    CHECK(*s.three_level_order == Approx(2.0).epsilon(1e-12));  // |-0.5/0.125| = 4
    bool noted = false;
    for (const auto& note : s.notes) noted |= note.find("oscillatorily") != std::string::npos;
    CHECK(noted);
  }
  SECTION("monotone convergence, falling or rising, is not noted as oscillatory") {
    for (const std::vector<double>& v : {std::vector<double>{1.4, 1.1, 1.025}, std::vector<double>{0.6, 0.9, 0.975}}) {
      const auto s = ver::analyse_convergence({0.4, 0.2, 0.1}, v, options);
      REQUIRE(s.three_level_order);
      CHECK(*s.three_level_order == Approx(2.0).epsilon(1e-12));  // differences 0.3, 0.075: ratio 4
      for (const auto& note : s.notes) CHECK(note.find("oscillatorily") == std::string::npos);
    }
  }
  SECTION("all errors zero: no orders, no Richardson, JSON still NaN-free") {
    const auto s = ver::analyse_convergence({0.4, 0.2, 0.1}, {1.0, 1.0, 1.0}, options);
    CHECK_FALSE(s.fitted_order);
    CHECK_FALSE(s.three_level_order);
    CHECK_FALSE(s.richardson);
    CHECK_FALSE(s.gci_fine);
    const std::string text = ver::to_json(s).dump();
    CHECK(text.find("NaN") == std::string::npos);
    CHECK(text.find("nan") == std::string::npos);
    CHECK(nlohmann::json::parse(text)["fitted_order"].is_null());
  }
  SECTION("finest value zero: relative GCI undefined") {
    ver::ConvergenceOptions zero_reference;
    zero_reference.reference = 0.0;
    const auto s = ver::analyse_convergence({0.4, 0.2, 0.1}, {0.16, 0.04, 0.0}, zero_reference);
    CHECK_FALSE(s.relative_error[0]);
    CHECK_FALSE(s.gci_fine);
  }
}

TEST_CASE("bad input throws", "[convergence]") {
  using ver::analyse_convergence;
  CHECK_THROWS_AS(analyse_convergence({0.1}, {1.0}), std::invalid_argument);
  CHECK_THROWS_AS(analyse_convergence({}, {}), std::invalid_argument);
  CHECK_THROWS_AS(analyse_convergence({0.1, 0.2}, {1.0, 1.1}), std::invalid_argument);
  CHECK_THROWS_AS(analyse_convergence({0.1, 0.1}, {1.0, 1.1}), std::invalid_argument);
  CHECK_THROWS_AS(analyse_convergence({0.2, 0.1, 0.15}, {1, 2, 3}), std::invalid_argument);
  CHECK_THROWS_AS(analyse_convergence({0.2, 0.1}, {1.0}), std::invalid_argument);
  CHECK_THROWS_AS(analyse_convergence({0.2, 0.0}, {1.0, 1.1}), std::invalid_argument);
  CHECK_THROWS_AS(analyse_convergence({0.2, 0.1}, {1.0, std::nan("")}), std::invalid_argument);
  ver::ConvergenceOptions options;
  options.fit_levels = {0, 5};
  CHECK_THROWS_AS(analyse_convergence({0.2, 0.1}, {1.0, 1.1}, options), std::invalid_argument);
}

TEST_CASE("to_json writes the RESULT_FORMAT series keys", "[convergence]") {
  ver::ConvergenceOptions options;
  options.reference = 0.5;
  options.expected_order = 1.0;
  const auto h = halving(1e-3, 3);
  const auto j = ver::to_json(
      ver::analyse_convergence(h, power_law(h, 0.5, 2.0, 1.0), options, "e, zeta=0.3", "dt [s]"));
  for (const char* key :
       {"name", "parameter", "h", "value", "reference", "error", "observed_order", "fitted_order",
        "expected_order", "richardson", "gci_fine", "asymptotic_ratio", "asymptotic"})
    CHECK(j.contains(key));
  CHECK(j["name"] == "e, zeta=0.3");
  CHECK(j["parameter"] == "dt [s]");
  CHECK(j["h"].size() == 3);
  CHECK(j["error"].size() == 3);
  CHECK(j["observed_order"][0].is_null());
  CHECK(j["expected_order"] == 1.0);
  CHECK(j["asymptotic"] == true);
  CHECK(j["errors_against"] == "reference");
}
