#include "dem/run/loop_state.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace dem {

EnergyScale energy_scale(const Model& m, double e1) {
  EnergyScale es;
  const Elements& e = m.elements;
  const double g = norm(m.gravity);
  const double T = m.numerics.duration;
  double mass = 0.0, v0 = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i] || e.motion[i] != Motion::free) continue;
    mass += e.mass[i];
    v0 = std::max(v0, std::hypot(e.vx[i], e.vy[i]));
  }
  double v_drive = 0.0;
  for (const VelocityHistory& h : m.drives)
    for (const Vec2& v : h.v) v_drive = std::max(v_drive, norm(v));
  if (g > 0.0) {
    // the drop along g: across the region of the elements and walls; if no wall lies beyond every
    // element along g, an element may also fall freely for the whole run
    const Vec2 down = m.gravity * (1.0 / g);
    double lo = 1e300, hi = -1e300, elem_low = -1e300, wall_low = -1e300;
    for (std::size_t i = 0; i < e.size(); ++i) {
      const double p = dot(down, Vec2{e.x[i], e.y[i]});
      lo = std::min(lo, p - e.radius[i]);
      hi = std::max(hi, p + e.radius[i]);
      elem_low = std::max(elem_low, p + e.radius[i]);
    }
    for (const Wall& w : m.walls)
      for (const Vec2& q : {w.a, w.b}) {
        const double p = dot(down, q);
        lo = std::min(lo, p);
        hi = std::max(hi, p);
        wall_low = std::max(wall_low, p);
      }
    es.drop = hi - lo;
    const bool moving_walls = std::any_of(m.walls.begin(), m.walls.end(), [](const Wall& w) { return w.drive >= 0; });
    if (wall_low < elem_low || moving_walls) es.drop += (v0 + v_drive) * T + 0.5 * g * T * T;
    es.gravity_work = mass * g * es.drop;
  }
  // drives: an element thrown by a wall moving at v leaves at most at 2v; and the drive may lift the
  // weight of every element over its travel
  es.drive_work = v_drive > 0.0 ? 0.5 * mass * 4.0 * v_drive * v_drive + mass * g * v_drive * T : 0.0;
  // and each driven element carries the kinetic energy of its own drive's fastest velocity and may be
  // lifted by it over the run (the energies count every element, driven ones too)
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!e.active[i] || e.motion[i] != Motion::driven || e.drive[i] < 0) continue;
    double v_max = 0.0;
    for (const Vec2& v : m.drives[static_cast<std::size_t>(e.drive[i])].v) v_max = std::max(v_max, norm(v));
    es.drive_work += 0.5 * e.mass[i] * v_max * v_max + e.mass[i] * g * v_max * T;
  }
  es.total = e1 + es.gravity_work + es.drive_work;
  return es;
}

constexpr std::size_t kLoopNumbers = 11;  // then the probes' numbers, then 4 per keystone
constexpr std::size_t kProbeNumbers = 26;
std::vector<double> loop_state(const LoopState& l, const std::vector<ProbeState>& probes) {
  std::vector<double> v{l.energy_limit,       l.potential0, l.scale.total, l.scale.gravity_work, l.scale.drive_work,
                        l.scale.drop, static_cast<double>(l.quiet_steps), l.peak_so_far, l.last_release,
                        static_cast<double>(l.keystones.size()), l.slit_opened ? 1.0 : 0.0};
  for (const ProbeState& p : probes) {
    v.insert(v.end(), {p.prev_t, p.prev_v, p.value ? 1.0 : 0.0, p.value.value_or(0.0), p.extreme,
                       p.have_extreme ? 1.0 : 0.0, p.vn_prev, p.extreme_t, p.st, p.sq, p.stt, p.stq, p.sn,
                       p.crossing ? 1.0 : 0.0, p.crossing.value_or(0.0), p.n_prev.x, p.n_prev.y, p.n_in.x, p.n_in.y,
                       p.vn_in, p.vn_out, p.touched ? 1.0 : 0.0, p.separated ? 1.0 : 0.0,
                       static_cast<double>(p.force_steps), p.in_contact ? 1.0 : 0.0, p.x0});
  }
  for (const LoopState::Keystone& k : l.keystones) v.insert(v.end(), {k.t, k.element, k.x, k.y});
  return v;
}
namespace {
// A count, step number or flag stored as a double: a whole number in [0, max] (NaN is not).
bool whole_in(double x, double max) { return x >= 0.0 && x <= max && x == std::floor(x); }
}  // namespace

void restore_loop_state(const std::vector<double>& v, LoopState& l, std::vector<ProbeState>& probes, const std::string& what) {
  const std::size_t fixed = kLoopNumbers + kProbeNumbers * probes.size();
  if (v.size() < fixed || !whole_in(v[9], static_cast<double>(v.size())) ||
      v.size() != fixed + 4 * static_cast<std::size_t>(v[9]))
    throw CaseError(fmt::format("{}: restart: the checkpoint's run state does not match the case's probes", what));
  const std::size_t n_keystones = static_cast<std::size_t>(v[9]);
  auto whole = [&](std::size_t k, double max, const char* field) {
    if (!whole_in(v[k], max)) throw CaseError(fmt::format("{}: corrupt checkpoint (run state {}: {})", what, field, v[k]));
  };
  whole(6, 9e18, "quiet steps");
  whole(10, 1.0, "slit opened");
  for (std::size_t p = 0; p < probes.size(); ++p)
    for (std::size_t k : {2, 5, 13, 21, 22, 24}) whole(kLoopNumbers + kProbeNumbers * p + k, 1.0, "probe flag");
  for (std::size_t p = 0; p < probes.size(); ++p) whole(kLoopNumbers + kProbeNumbers * p + 23, 9e18, "probe force steps");
  l.energy_limit = v[0], l.potential0 = v[1];
  l.scale.total = v[2], l.scale.gravity_work = v[3], l.scale.drive_work = v[4], l.scale.drop = v[5];
  l.quiet_steps = static_cast<std::int64_t>(v[6]);
  l.peak_so_far = v[7];
  l.last_release = v[8];
  l.slit_opened = v[10] != 0.0;
  l.keystones.clear();
  for (std::size_t k = 0; k < n_keystones; ++k) {
    const double* q = v.data() + kLoopNumbers + kProbeNumbers * probes.size() + 4 * k;
    l.keystones.push_back({q[0], q[1], q[2], q[3]});
  }
  const double* x = v.data() + kLoopNumbers;
  for (ProbeState& p : probes) {
    p.prev_t = x[0], p.prev_v = x[1];
    if (x[2] != 0.0) p.value = x[3];
    else p.value.reset();
    p.extreme = x[4], p.have_extreme = x[5] != 0.0;
    p.vn_prev = x[6], p.extreme_t = x[7];
    p.st = x[8], p.sq = x[9], p.stt = x[10], p.stq = x[11], p.sn = x[12];
    if (x[13] != 0.0) p.crossing = x[14];
    else p.crossing.reset();
    p.n_prev = {x[15], x[16]}, p.n_in = {x[17], x[18]};
    p.vn_in = x[19], p.vn_out = x[20];
    p.touched = x[21] != 0.0, p.separated = x[22] != 0.0;
    p.force_steps = static_cast<std::int64_t>(x[23]), p.in_contact = x[24] != 0.0;
    p.x0 = x[25];
    x += kProbeNumbers;
  }
}

}  // namespace dem
