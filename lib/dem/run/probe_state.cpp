#include "dem/run/probe_state.hpp"

#include <cmath>

#include <fmt/format.h>

namespace dem {

namespace {

// i, j: element ids (the case's numbering), mapped to the arrays' indices here (spatial_order.hpp)
Vec2 contact_normal(const Simulation& s, std::uint32_t i, std::uint32_t j, bool wall) {
  i = s.index_of(i);
  if (!wall) j = s.index_of(j);
  const Elements& e = s.model().elements;
  const Vec2 c{e.x[i], e.y[i]};
  const Vec2 o = wall ? closest_point(s.model().walls[j], c) : Vec2{e.x[j], e.y[j]};
  const Vec2 d = o - c;
  return d * (1.0 / norm(d));
}

Vec2 body_velocity(const Simulation& s, std::uint32_t j, bool wall) {
  const Model& m = s.model();
  if (wall) {
    const Wall& w = m.walls[j];
    return w.drive >= 0 ? m.drives[static_cast<std::size_t>(w.drive)].at(s.time()) : Vec2{};
  }
  j = s.index_of(j);
  return {m.elements.vx[j], m.elements.vy[j]};
}

/// Normal relative velocity of i towards j (or wall j) along n, approach positive.
double approach_velocity(const Simulation& s, std::uint32_t i, std::uint32_t j, bool wall, Vec2 n) {
  const Elements& e = s.model().elements;
  const std::uint32_t ii = s.index_of(i);
  const Vec2 vi{e.vx[ii], e.vy[ii]};
  return dot(vi - body_velocity(s, j, wall), n);
}

/// value: the quantity at `at`, interpolated linearly between the samples around it.
void sample_value(ProbeState& p, const Simulation& sim) {
  const ProbeSpec& s = *p.spec;
  if (s.at && !p.value) {
    const double v = p.q(sim);
    if (sim.time() >= *s.at - 1e-12 * sim.model().numerics.dt) {
      const double w = (sim.time() - *s.at) / (sim.time() - p.prev_t);
      p.value = w <= 0.0 ? v : v + (p.prev_v - v) * w;
    }
    p.prev_t = sim.time();
    p.prev_v = v;
  }
}

/// slope: the least-squares sums over the window, against t or the `against` quantity.
void sample_slope(ProbeState& p, const Simulation& sim) {
  const ProbeSpec& s = *p.spec;
  const double t = sim.time();
  if (t >= s.from - 1e-12 && t <= s.to + 1e-12) {
    double tt = t - s.from;  // centred on `from` (or the first abscissa) for conditioning
    if (p.x) {
      if (p.sn == 0.0) p.x0 = p.x(sim);
      tt = p.x(sim) - p.x0;
    }
    const double v = p.q(sim);
    p.st += tt;
    p.sq += v;
    p.stt += tt * tt;
    p.stq += tt * v;
    p.sn += 1.0;
  }
}

/// max, min, time_of_max, time_of_min, mean, crossing: the samples inside the window from ≤ t ≤ to.
void sample_window(ProbeState& p, const Simulation& sim) {
  const ProbeSpec& s = *p.spec;
  const double t = sim.time();
  if (t >= s.from - 1e-12 && t <= s.to + 1e-12) {
    const double v = p.q(sim);
    if (s.kind == ProbeKind::mean) {
      p.sq += v;
      p.sn += 1.0;
    } else if (s.kind == ProbeKind::crossing) {
      const double a = p.prev_v - s.level, b = v - s.level;
      const bool up = a < 0.0 && b >= 0.0, down = a > 0.0 && b <= 0.0;
      if (!p.crossing && t > p.prev_t && ((s.direction >= 0 && up) || (s.direction <= 0 && down)))
        p.crossing = p.prev_t + (t - p.prev_t) * (a / (a - b));
    } else {
      const bool want_max = s.kind == ProbeKind::max || s.kind == ProbeKind::time_of_max;
      if (!p.have_extreme || (want_max ? v > p.extreme : v < p.extreme)) {
        p.extreme = v;
        p.extreme_t = t;
      }
      p.have_extreme = true;
    }
    p.prev_t = t;
    p.prev_v = v;
  } else if (s.kind == ProbeKind::crossing && t < s.from) {
    p.prev_t = t;  // the sample before the window starts the first interval
    p.prev_v = p.q(sim);
  }
}

/// restitution, contact_duration: the contact between element and other (element or wall).
void sample_contact(ProbeState& p, const Simulation& sim) {
  const ProbeSpec& s = *p.spec;
  const ContactView cv = sim.contact(sim.index_of(s.element), s.other_is_wall ? s.other : sim.index_of(s.other),
                                     s.other_is_wall);
  p.in_contact = cv.fn != 0.0;
  if (p.in_contact) ++p.force_steps;
  if (s.kind == ProbeKind::restitution) {
    // the first contact event, along the normal at first touch: the approach velocity of the
    // state before the first step with force, the separation velocity after the first step
    // without force that follows (velocities are v_k, after the step's forces)
    if (!p.touched && p.in_contact) {
      p.touched = true;
      p.n_in = p.n_prev;
      p.vn_in = p.vn_prev;
    } else if (p.touched && !p.separated && !p.in_contact) {
      p.separated = true;
      p.vn_out = approach_velocity(sim, s.element, s.other, s.other_is_wall, p.n_in);
    }
    if (!p.touched) {
      p.n_prev = contact_normal(sim, s.element, s.other, s.other_is_wall);
      p.vn_prev = approach_velocity(sim, s.element, s.other, s.other_is_wall, p.n_prev);
    }
  }
}

}  // namespace

std::vector<ProbeState> start_probes(const Case& c, const Simulation& sim) {
  const Model& m = sim.model();
  std::vector<ProbeState> probes;
  for (const auto& p : c.probes) {
    ProbeState s;
    s.spec = &p;
    if (!p.quantity.empty()) {
      s.q = compile_quantity(p.quantity, m);
      s.prev_v = s.q(sim);
    } else if (p.kind != ProbeKind::ratio) {  // a ratio has nothing to sample (ratio_results)
      s.n_prev = contact_normal(sim, p.element, p.other, p.other_is_wall);  // ids (the case's numbering)
      s.vn_prev = approach_velocity(sim, p.element, p.other, p.other_is_wall, s.n_prev);
    }
    probes.push_back(s);
  }
  for (auto& p : probes)
    if (!p.spec->against.empty()) {
      try {
        p.x = compile_quantity(p.spec->against, m);
      } catch (const std::invalid_argument& e) {
        throw CaseError(
            fmt::format("{}: probe \"{}\": against: {}", c.path.string(), p.spec->name, e.what()));
      }
    }
  return probes;
}

void sample_probe(ProbeState& p, const Simulation& sim) {
  switch (p.spec->kind) {
    case ProbeKind::value:
      sample_value(p, sim);
      break;
    case ProbeKind::slope:
      sample_slope(p, sim);
      break;
    case ProbeKind::max:
    case ProbeKind::min:
    case ProbeKind::time_of_max:
    case ProbeKind::time_of_min:
    case ProbeKind::mean:
    case ProbeKind::crossing:
      sample_window(p, sim);
      break;
    case ProbeKind::restitution:
    case ProbeKind::contact_duration:
      sample_contact(p, sim);
      break;
    case ProbeKind::ratio:
      break;
  }
}

std::optional<double> probe_result(const ProbeState& p, const Simulation& sim) {
  const ProbeSpec& s = *p.spec;
  std::optional<double> v;
  switch (s.kind) {
    case ProbeKind::value:
      v = s.at ? p.value : std::optional<double>(p.q(sim));
      break;
    case ProbeKind::max:
    case ProbeKind::min:
      if (p.have_extreme) v = p.extreme;
      break;
    case ProbeKind::time_of_max:
    case ProbeKind::time_of_min:
      if (p.have_extreme) v = p.extreme_t;
      break;
    case ProbeKind::mean:
      if (p.sn > 0.0) v = p.sq / p.sn;
      break;
    case ProbeKind::crossing:
      v = p.crossing;
      break;
    case ProbeKind::slope:
      if (p.sn >= 2.0) v = (p.sn * p.stq - p.st * p.sq) / (p.sn * p.stt - p.st * p.st);
      break;
    case ProbeKind::restitution:
      // the first contact event only; none if it never touched, never separated, or did not approach
      if (p.touched && p.separated && p.vn_in > 0.0) v = -p.vn_out / p.vn_in;
      break;
    case ProbeKind::contact_duration:
      if (!p.in_contact && p.force_steps > 0) v = static_cast<double>(p.force_steps) * sim.model().numerics.dt;
      break;
    case ProbeKind::ratio:  // from the other probes' results (ratio_results)
      break;
  }
  if (v && !std::isfinite(*v)) v.reset();
  return v;
}

void ratio_results(const std::vector<ProbeState>& probes, std::map<std::string, std::optional<double>>& results) {
  for (const auto& p : probes)
    if (p.spec->kind == ProbeKind::ratio) {
      const auto& a = results.at(p.spec->of);
      const auto& b = results.at(p.spec->over);
      std::optional<double> v;
      if (a && b && *b != 0.0 && std::isfinite(*a / *b)) v = *a / *b;
      results[p.spec->name] = v;
    }
}

}  // namespace dem
