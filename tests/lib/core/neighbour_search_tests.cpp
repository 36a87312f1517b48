// The cell-list neighbour search (docs/model.md §1, K27) against an all-pairs oracle written here, on random
// element sets: sizes, radius distributions, inactive elements, skins, sparse clouds and degenerate
// layouts. The result must be the same set of pairs, each once with i < j, sorted by (i, j).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "dem/core/neighbour_search.hpp"

namespace {

enum class Radii { equal, uniform, wide, one_giant };
enum class Layout { box, sparse, line, same_point };

dem::Elements random_elements(std::size_t n, Radii radii, Layout layout, double inactive_share, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  dem::Elements e;
  // box side chosen so that the area fraction is about 0.5 for unit-ish radii
  const double side = std::sqrt(static_cast<double>(n) * 3.14 / 0.5) + 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    double r = 1.0;
    switch (radii) {
      case Radii::equal:
        r = 1.0;
        break;
      case Radii::uniform:
        r = 0.5 + u01(rng);
        break;
      case Radii::wide:
        r = std::exp(std::log(0.05) + u01(rng) * std::log(200.0));
        break;  // 0.05 … 10
      case Radii::one_giant:
        r = i == n / 2 ? 0.2 * side : 0.3 + 0.4 * u01(rng);
        break;
    }
    double x = 0.0, y = 0.0;
    switch (layout) {
      case Layout::box:
        x = side * u01(rng);
        y = side * u01(rng);
        break;
      case Layout::sparse:
        x = 1e3 * side * u01(rng);
        y = 1e3 * side * u01(rng);
        break;  // the grid must not explode
      case Layout::line:
        x = side * u01(rng);
        y = 7.0;
        break;  // zero height
      case Layout::same_point:
        x = 3.0;
        y = -2.0;
        break;  // every pair touches
    }
    e.x.push_back(x);
    e.y.push_back(y);
    e.radius.push_back(r);
    e.active.push_back(u01(rng) < inactive_share ? 0 : 1);
  }
  return e;
}

/// The oracle: every pair of active elements with centre distance below r_i + r_j + skin.
std::vector<std::pair<std::uint32_t, std::uint32_t>> all_pairs(const dem::Elements& e, double skin) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t i = 0; i < e.x.size(); ++i)
    for (std::uint32_t j = i + 1; j < e.x.size(); ++j) {
      if (!e.active[i] || !e.active[j]) continue;
      const double dx = e.x[j] - e.x[i], dy = e.y[j] - e.y[i], cut = e.radius[i] + e.radius[j] + skin;
      if (dx * dx + dy * dy < cut * cut) out.emplace_back(i, j);
    }
  return out;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> as_pairs(const std::vector<dem::CandidatePair>& c) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& p : c) out.emplace_back(p.i, p.j);
  return out;
}

}  // namespace

TEST_CASE("neighbour search: the cell list finds exactly the pairs of the all-pairs oracle, sorted, once each",
          "[search]") {
  const std::size_t n = GENERATE(0, 1, 2, 3, 17, 200, 1500);
  const auto radii = GENERATE(Radii::equal, Radii::uniform, Radii::wide, Radii::one_giant);
  const auto layout = GENERATE(Layout::box, Layout::sparse, Layout::line);
  const double inactive = GENERATE(0.0, 0.2);
  const double skin = GENERATE(0.0, 0.1, 2.5);
  CAPTURE(n, static_cast<int>(radii), static_cast<int>(layout), inactive, skin);
  const auto e = random_elements(n, radii, layout, inactive, 1234 + n);
  dem::NeighbourSearch search;
  std::vector<dem::CandidatePair> found, brute;
  search.build(e, skin, found);
  const auto got = as_pairs(found);
  const auto expected = all_pairs(e, skin);

  // sorted by (i, j) with i < j: no duplicates possible then
  for (std::size_t k = 0; k < got.size(); ++k) {
    REQUIRE(got[k].first < got[k].second);
    if (k > 0) REQUIRE(got[k - 1] < got[k]);
  }
  CHECK(got == expected);
  // the library's own brute force agrees too
  dem::brute_force_pairs(e, skin, brute);
  CHECK(as_pairs(brute) == expected);
  // a second build with the same object (reused buffers) gives the same answer
  search.build(e, skin, found);
  CHECK(as_pairs(found) == expected);
}

TEST_CASE("neighbour search: elements at one point all pair up, inactive ones never appear", "[search]") {
  const auto e = random_elements(40, Radii::uniform, Layout::same_point, 0.25, 7);
  dem::NeighbourSearch search;
  std::vector<dem::CandidatePair> found;
  search.build(e, 0.0, found);
  std::size_t active = 0;
  for (auto a : e.active) active += a;
  CHECK(found.size() == active * (active - 1) / 2);
  for (const auto& p : found) {
    CHECK(e.active[p.i] == 1);
    CHECK(e.active[p.j] == 1);
  }
  CHECK(as_pairs(found) == all_pairs(e, 0.0));
}

TEST_CASE("neighbour search: a set that shrinks and grows between builds (buffer reuse)", "[search]") {
  dem::NeighbourSearch search;
  std::vector<dem::CandidatePair> found;
  for (std::size_t n : {500u, 20u, 1000u, 3u, 300u}) {
    CAPTURE(n);
    const auto e = random_elements(n, Radii::wide, Layout::box, 0.1, 99 + n);
    search.build(e, 0.3, found);
    CHECK(as_pairs(found) == all_pairs(e, 0.3));
  }
}

TEST_CASE("neighbour search: a pair exactly r_i + r_j + skin apart is no candidate - one closer by a hair is", "[search]") {
  // Radii 0.25 and skin 0.5: the cut is 1 exactly; 0 and 1 are 1 apart (as the oracle: below the cut only),
  // 2 and 3 are 1 − 2^-10 apart, 4 and 5 are 1 apart along y.
  dem::Elements e;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0.0, 0.0}, {1.0, 0.0}, {3.0, 0.0}, {3.9990234375, 0.0},
                                                                  {6.0, 2.0}, {6.0, 3.0}}) {
    e.x.push_back(x);
    e.y.push_back(y);
    e.radius.push_back(0.25);
    e.active.push_back(1);
  }
  dem::NeighbourSearch search;
  std::vector<dem::CandidatePair> found;
  search.build(e, 0.5, found);
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> expected = {{2, 3}};
  CHECK(as_pairs(found) == expected);
  CHECK(all_pairs(e, 0.5) == expected);
}
