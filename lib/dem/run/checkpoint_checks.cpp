#include "dem/run/checkpoint_checks.hpp"

#include <cmath>

#include <fmt/format.h>

#include "dem/cases/extent.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/output_files.hpp"

namespace dem {

void corrupt_checkpoint(const std::string& file, const std::string& field, const std::string& what) {
  throw CaseError(fmt::format("{}: corrupt checkpoint ({}: {})", file, field, what));
}

void check_checkpoint_header(const Checkpoint& ck) {
  if (ck.step < 0) corrupt_checkpoint(ck.file, "step", fmt::format("{} is negative", ck.step));
  if (!std::isfinite(ck.time) || ck.time < 0.0) corrupt_checkpoint(ck.file, "time", fmt::format("{} s", ck.time));
  if (!std::isfinite(ck.dt) || !(ck.dt > 0.0)) corrupt_checkpoint(ck.file, "dt", fmt::format("{} s", ck.dt));
}

void check_flag(const std::string& file, const std::string& field, unsigned value) {
  if (value > 1u) corrupt_checkpoint(file, field, fmt::format("flag byte {} (0 or 1)", value));
}

void check_finite(const std::string& file, const std::string& field, double v) {
  if (!std::isfinite(v)) corrupt_checkpoint(file, field, fmt::format("{} is not finite", v));
}

void check_finite(const std::string& file, const std::string& field, const std::vector<double>& v) {
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k])) corrupt_checkpoint(file, fmt::format("{}[{}]", field, k), fmt::format("{} is not finite", v[k]));
}

void check_element_state(const std::string& file, const Elements& e) {
  const char* names[] = {"x", "y", "phi", "dx", "dy", "dphi", "vx", "vy", "omega", "fx", "fy", "moment"};
  const std::vector<double>* arrays[] = {&e.x, &e.y, &e.phi, &e.dx, &e.dy, &e.dphi, &e.vx, &e.vy, &e.omega, &e.fx, &e.fy, &e.moment};
  for (std::size_t a = 0; a < std::size(arrays); ++a) check_finite(file, fmt::format("element {}", names[a]), *arrays[a]);
  if (e.active.size() != e.size())
    corrupt_checkpoint(file, "element active", fmt::format("{} flags for {} elements", e.active.size(), e.size()));
  for (std::size_t k = 0; k < e.active.size(); ++k) check_flag(file, fmt::format("element active[{}]", k), e.active[k]);
  for (std::size_t k = 0; k < e.size(); ++k)
    if (!within_extent({e.x[k], e.y[k]}))
      corrupt_checkpoint(file, fmt::format("element position[{}]", k), outside_extent({e.x[k], e.y[k]}));
}

void check_wall_state(const std::string& file, const std::vector<Wall>& walls) {
  for (std::size_t w = 0; w < walls.size(); ++w)
    for (const Vec2& v : {walls[w].a, walls[w].b, walls[w].increment, walls[w].force}) {
      check_finite(file, fmt::format("wall {} ({})", w, walls[w].name), v.x);
      check_finite(file, fmt::format("wall {} ({})", w, walls[w].name), v.y);
    }
  for (std::size_t w = 0; w < walls.size(); ++w)
    for (const Vec2& p : {walls[w].a, walls[w].b})
      if (!within_extent(p)) corrupt_checkpoint(file, fmt::format("wall {} ({})", w, walls[w].name), outside_extent(p));
}

namespace {

// Element i < j < n (pairs) or element i < n and wall j < n_walls; (i, j) after the previous slot's.
void check_pair(const std::string& file, const std::string& field, std::uint32_t i, std::uint32_t j, std::size_t n,
                std::size_t n_walls, bool walls, const std::uint32_t* prev) {
  if (i >= n) corrupt_checkpoint(file, field, fmt::format("element index {} of {} elements", i, n));
  if (walls && j >= n_walls) corrupt_checkpoint(file, field, fmt::format("wall index {} of {} walls", j, n_walls));
  if (!walls && (j >= n || j <= i))
    corrupt_checkpoint(file, field, fmt::format("element pair ({}, {}) of {} elements (i < j < n)", i, j, n));
  if (prev && (i < prev[0] || (i == prev[0] && j <= prev[1])))
    corrupt_checkpoint(file, field, fmt::format("({}, {}) after ({}, {}): not sorted", i, j, prev[0], prev[1]));
}

void check_law(const std::string& file, const std::string& field, std::int32_t law, const Model& m, LawKind kind) {
  if (law < 0 || static_cast<std::size_t>(law) >= m.laws.size())
    corrupt_checkpoint(file, field, fmt::format("law index {} of {} laws", law, m.laws.size()));
  if (m.laws[static_cast<std::size_t>(law)].kind != kind)
    corrupt_checkpoint(file, field, fmt::format("law {} is not a {} law", law, kind == LawKind::linear ? "linear" : "face"));
}

void check_numbers(const std::string& file, const std::string& field, std::initializer_list<double> v) {
  for (double x : v) check_finite(file, field, x);
}

}  // namespace

void check_candidates(const std::string& file, const std::vector<CandidatePair>& c, std::size_t n) {
  for (std::size_t k = 0; k < c.size(); ++k) {
    const std::uint32_t prev[2] = {k ? c[k - 1].i : 0, k ? c[k - 1].j : 0};
    check_pair(file, fmt::format("candidate pair {}", k), c[k].i, c[k].j, n, 0, false, k ? prev : nullptr);
  }
}

/// A rolling state (R1–R6): finite numbers, constants that are not negative, a spring within its limit's
/// reach (|M_k| ≤ arm × any finite force cannot be checked without the force: only finiteness and signs).
static void check_rolling(const std::string& file, const std::string& field, const RollingState& r) {
  check_numbers(file, field + " rolling", {r.mk, r.kr, r.cr, r.arm, r.m});
  if (r.kr < 0.0 || r.cr < 0.0 || r.arm < 0.0)
    corrupt_checkpoint(file, field + " rolling", fmt::format("negative constant (k_r {}, C_r {}, μ_r R_r {})", r.kr, r.cr, r.arm));
}

void check_slots(const std::string& file, const LinearPairSlots& s, const Model& m, bool laws) {
  const std::size_t n = m.elements.size();
  for (std::size_t k = 0; k < s.size(); ++k) {
    const std::string field = fmt::format("linear pair slot {}", k);
    const std::uint32_t prev[2] = {k ? s.pair[k - 1].i : 0, k ? s.pair[k - 1].j : 0};
    check_pair(file, field, s.pair[k].i, s.pair[k].j, n, 0, false, k ? prev : nullptr);
    if (laws) check_law(file, field, s.law[k], m, LawKind::linear);
    check_flag(file, field + " touching", s.touching[k]);
    const LinearContactState& c = s.state[k];
    const LinearContactResultant& f = s.resultant[k];
    check_numbers(file, field, {c.eta_n, c.eta_s, c.h.en, c.h.es, f.fn, f.fs, f.nx, f.ny});
    if (s.with_rolling) check_rolling(file, field, s.rolling[k]);
  }
}

void check_slots(const std::string& file, const std::vector<LinearSlot>& s, const Model& m, bool laws) {
  for (std::size_t k = 0; k < s.size(); ++k) {
    const std::string field = fmt::format("linear wall slot {}", k);
    const std::uint32_t prev[2] = {k ? s[k - 1].i : 0, k ? s[k - 1].j : 0};
    check_pair(file, field, s[k].i, s[k].j, m.elements.size(), m.walls.size(), true, k ? prev : nullptr);
    if (laws) check_law(file, field, s[k].law, m, LawKind::linear);
    check_flag(file, field + " touching", s[k].touching);
    check_numbers(file, field, {s[k].eta_n, s[k].eta_s, s[k].h.en, s[k].h.es, s[k].f.fn, s[k].f.fs, s[k].nx, s[k].ny});
    check_rolling(file, field, s[k].rolling);
  }
}

void check_slots(const std::string& file, const std::vector<FaceSlot>& s, const Model& m, bool walls, bool laws) {
  for (std::size_t k = 0; k < s.size(); ++k) {
    const std::string field = fmt::format("face {} slot {}", walls ? "wall" : "pair", k);
    const FaceSlot& f = s[k];
    const std::uint32_t prev[2] = {k ? s[k - 1].i : 0, k ? s[k - 1].j : 0};
    check_pair(file, field, f.i, f.j, m.elements.size(), m.walls.size(), walls, k ? prev : nullptr);
    if (laws) check_law(file, field, f.law, m, LawKind::face);
    check_flag(file, field + " touching", f.touching);
    check_flag(file, field + " geometric_start", f.h.geometric_start);
    check_numbers(file, field, {f.c.kn, f.c.ks, f.c.eta_n, f.c.eta_s, f.c.half_length, f.c.segment_area, f.h.theta1,
                                f.h.theta2, f.f.p, f.f.q, f.f.p_moment, f.nx, f.ny});
    for (const SegmentState& g : f.h.seg) {
      check_numbers(file, field + " segment", {g.u, g.pe, g.qe});
      check_flag(file, field + " segment linked", g.linked);
      check_flag(file, field + " segment intact", g.intact);
    }
    if (f.f.links < 0 || f.f.links > kMaxSegments)
      corrupt_checkpoint(file, field, fmt::format("{} links (0 to {})", f.f.links, kMaxSegments));
  }
}

void check_references(const std::string& file, const std::vector<double>& x_ref, const std::vector<double>& y_ref,
                      const std::vector<Vec2>& wall_ref, std::size_t n, std::size_t n_walls) {
  if (x_ref.size() != n || y_ref.size() != n)
    corrupt_checkpoint(file, "reference positions", fmt::format("{} and {} for {} elements", x_ref.size(), y_ref.size(), n));
  if (wall_ref.size() != n_walls)
    corrupt_checkpoint(file, "wall references", fmt::format("{} for {} walls", wall_ref.size(), n_walls));
  check_finite(file, "reference x", x_ref);
  check_finite(file, "reference y", y_ref);
  for (std::size_t w = 0; w < wall_ref.size(); ++w)
    check_numbers(file, fmt::format("wall reference {}", w), {wall_ref[w].x, wall_ref[w].y});
}

}  // namespace dem
