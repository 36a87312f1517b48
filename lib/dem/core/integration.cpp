// Simulation's integration (simulation.hpp): velocities (K17), increments (K18 or K19) and positions over an
// element range, in vectorised passes where every element is free; the blow-up test (overstep) and the
// next step's rebuild test made in the same pass.
#include "dem/core/simulation.hpp"

#include <bit>
#include <cmath>

#include "dem/core/step_loops.hpp"

namespace dem {

namespace step_detail {

bool any_displaced(const double* __restrict x, const double* __restrict y, const double* __restrict xr,
                   const double* __restrict yr, double limit2, std::size_t n) {
  std::uint64_t all_negative = ~std::uint64_t{0};
  for (std::size_t i = 0; i < n; ++i) {
    const double ddx = x[i] - xr[i], ddy = y[i] - yr[i];
    all_negative &= std::bit_cast<std::uint64_t>(ddx * ddx + ddy * ddy - limit2);
  }
  return (all_negative >> 63) == 0;
}
/// Whether (|Δx|/r)² may exceed limit2 for some element of [0, n): overstep_bits over the increments,
/// The first NaN, else the first largest (the order in which oversteps of successive ranges combine).
void take_worse(Simulation::Overstep& worst, const Simulation::Overstep& o) {
  if (o.index == Simulation::Overstep::npos) return;
  if (worst.index == Simulation::Overstep::npos || (!std::isnan(worst.fraction2) && !(o.fraction2 <= worst.fraction2))) worst = o;
}

}  // namespace step_detail

using step_detail::any_displaced;
using step_detail::take_worse;

namespace {

// Element loops of the hot path as functions of restrict-qualified parameters, so that the compiler
// vectorises them (it does not trust restrict on local pointers). Every lane performs the scalar code's
// operations in the same order, and nothing is contracted into FMAs: results are bit-identical. The free
// integration also has an AVX2 clone (DEM2D_CLONES_AVX2: 4 lanes instead of 2, AVX2 has no FMA).

/// One degree of freedom of free elements: v += (h f) w (K17, w = 1/m or 1/I), then the increment
/// d = v Δt (K18) or d = (d + v Δt)/2 (K19), then x += d.
template <bool K19>
inline double advance_dof(double& v, double f, double w, double& d, double& x, double h, double dt) {
  v += h * f * w;
  d = K19 ? 0.5 * (d + v * dt) : v * dt;
  x += d;
  return d;
}
/// The blow-up prefilter of one element (may_overstep): bits whose sign bit is clear if (|Δx|/r)² may exceed
/// the limit, and bits with a set exponent if it is not finite. limit2r = limit2 (1 − 1e-12), so that no
/// division is needed: (dx² + dy²)/r² > limit2 implies dx² + dy² > limit2r · r² after rounding.
/// Also the largest squared increment |Δx|² so far, as its bit pattern (max_bits: the travel bound,
/// Simulation::travel_): for doubles ≥ 0 the patterns, read as integers, order as the values do, and an
/// integer maximum vectorises where a floating-point one does not. (A NaN d2 is caught by not_finite.)
inline void overstep_bits(double ddx, double ddy, double r, double limit2r, std::uint64_t& all_below,
                          std::uint64_t& not_finite, std::int64_t& max_bits) {
  const double d2 = ddx * ddx + ddy * ddy;
  all_below &= std::bit_cast<std::uint64_t>(d2 - limit2r * (r * r));
  not_finite |= std::bit_cast<std::uint64_t>(d2 * 0.0);
  const std::int64_t bits = std::bit_cast<std::int64_t>(d2);
  max_bits = bits > max_bits ? bits : max_bits;
}
inline bool may_overstep(std::uint64_t all_below, std::uint64_t not_finite) {
  return (all_below >> 63) == 0 || (not_finite & 0x7fffffffffffffffULL) != 0;
}
/// Free elements (K17–K19), the three degrees of freedom in one pass, with the blow-up prefilter on the
/// increments just computed (the bytes pass the core once). The same operations per element as one
/// degree of freedom at a time: bit-identical.
/// With `active` (Masked): elements removed from the run (a silo's outlet) keep their state, as the
/// element-by-element loop leaves them; the others advance with the same operations (a select per value).
template <bool K19, bool Masked = false>
DEM2D_CLONES_AVX2 bool integrate_free(double* __restrict vx, double* __restrict vy, double* __restrict om,
                                      const double* __restrict fx, const double* __restrict fy,
                                      const double* __restrict mom, const double* __restrict wm,
                                      const double* __restrict wi, double* __restrict dx, double* __restrict dy,
                                      double* __restrict dphi, double* __restrict x, double* __restrict y,
                                      double* __restrict phi, const double* __restrict r, double h, double dt,
                                      double limit2r, std::size_t n,
                                      const std::uint8_t* __restrict active, double& max_d2) {
  std::uint64_t all_below = ~std::uint64_t{0}, not_finite = 0;
  std::int64_t md = 0;  // the bits of +0.0
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (!Masked) {
      const double ddx = advance_dof<K19>(vx[i], fx[i], wm[i], dx[i], x[i], h, dt);
      const double ddy = advance_dof<K19>(vy[i], fy[i], wm[i], dy[i], y[i], h, dt);
      advance_dof<K19>(om[i], mom[i], wi[i], dphi[i], phi[i], h, dt);
      overstep_bits(ddx, ddy, r[i], limit2r, all_below, not_finite, md);
    } else {
      const bool on = active[i] != 0;
      double v[3] = {vx[i], vy[i], om[i]}, d[3] = {dx[i], dy[i], dphi[i]}, q[3] = {x[i], y[i], phi[i]};
      advance_dof<K19>(v[0], fx[i], wm[i], d[0], q[0], h, dt);
      advance_dof<K19>(v[1], fy[i], wm[i], d[1], q[1], h, dt);
      advance_dof<K19>(v[2], mom[i], wi[i], d[2], q[2], h, dt);
      vx[i] = on ? v[0] : vx[i], vy[i] = on ? v[1] : vy[i], om[i] = on ? v[2] : om[i];
      dx[i] = on ? d[0] : dx[i], dy[i] = on ? d[1] : dy[i], dphi[i] = on ? d[2] : dphi[i];
      x[i] = on ? q[0] : x[i], y[i] = on ? q[1] : y[i], phi[i] = on ? q[2] : phi[i];
      // (the increments of removed elements are old: they move no more, and count in no maximum)
      overstep_bits(on ? dx[i] : 0.0, on ? dy[i] : 0.0, r[i], limit2r, all_below, not_finite, md);
    }
  }
  max_d2 = std::bit_cast<double>(md);
  return may_overstep(all_below, not_finite);
}
/// Whether an element moved by at least √limit2 from its reference position: d² − limit2 ≥ 0 has a clear
/// sign bit (an AND of the bit patterns, which the compiler vectorises; a comparison it does not).
/// without branches or comparisons, which the compiler vectorises.
bool may_overstep(const double* __restrict dx, const double* __restrict dy, const double* __restrict r,
                  double limit2r, std::size_t n, double& max_d2) {
  std::uint64_t all_below = ~std::uint64_t{0}, not_finite = 0;
  std::int64_t md = 0;  // the bits of +0.0
  for (std::size_t i = 0; i < n; ++i) overstep_bits(dx[i], dy[i], r[i], limit2r, all_below, not_finite, md);
  max_d2 = std::bit_cast<double>(md);
  return may_overstep(all_below, not_finite);
}
/// The kinematic blow-up test over elements [b, end) (Simulation::overstep()), exact, element by element.
Simulation::Overstep find_overstep(const Elements& e, std::size_t b, std::size_t end, double limit2) {
  Simulation::Overstep worst;
  for (std::size_t i = b; i < end; ++i) {
    const double q = (e.dx[i] * e.dx[i] + e.dy[i] * e.dy[i]) / (e.radius[i] * e.radius[i]);
    if (!(q <= limit2) && e.active[i]) take_worse(worst, {i, q});
  }
  return worst;
}
inline double prefilter_limit(double limit2) { return limit2 * (1.0 - 1e-12); }

}  // namespace

Simulation::Freedom Simulation::freedom(std::size_t b, std::size_t end) const {
  // The usual cases, every element free and active (or removed from the run): the same operations per
  // element, in branch-free loops that the compiler vectorises (the lanes round exactly as the scalar
  // code; no FMA contraction). Each thread asks it of its own elements (inside the step's job, not
  // serially before it).
  const Elements& e = m_.elements;
  std::uint8_t all = 1, active_free = 1;
  const std::uint8_t* __restrict act = e.active.data();
  const Motion* __restrict mot = e.motion.data();
  for (std::size_t i = b; i < end; ++i) {
    all &= (act[i] != 0) & (mot[i] == Motion::free);
    active_free &= (act[i] == 0) | (mot[i] == Motion::free);
  }
  return all ? Freedom::all_free : active_free ? Freedom::active_free : Freedom::general;
}

Simulation::Overstep Simulation::integrate_range(std::size_t b, std::size_t end, double dt_v, Freedom freedom,
                                                 double limit2, double limit2_next, RangeTests& tests) {
  Elements& e = m_.elements;
  const double dt = m_.numerics.dt;
  const bool k19 = m_.numerics.integrator == Integrator::k19;
  if (limit2_next >= 0.0) {  // right after the integration, while the positions are in the caches
    const Overstep o = integrate_range(b, end, dt_v, freedom, limit2, -1.0, tests);
    // No element of the range can have moved √limit2_next from its reference position if the travel bound
    // of the steps before plus this step's largest increment stays below it: the exact test would say no,
    // so it is not made (travel_ in simulation.hpp). Otherwise (or if the bound is unknown: ∞) it is.
    tests.skipped = travel_ + std::sqrt(tests.max_d2) < kTravelMargin * std::sqrt(limit2_next);
    tests.displaced = tests.skipped ? 0 : any_displaced(e.x.data() + b, e.y.data() + b, x_ref_.data() + b,
                                                        y_ref_.data() + b, limit2_next, end - b);
    return o;
  }
  if (freedom != Freedom::general) {
    const bool masked = freedom == Freedom::active_free;
    auto all = k19 ? (masked ? integrate_free<true, true> : integrate_free<true, false>)
                   : (masked ? integrate_free<false, true> : integrate_free<false, false>);
    const bool may = all(e.vx.data() + b, e.vy.data() + b, e.omega.data() + b, e.fx.data() + b, e.fy.data() + b,
                         e.moment.data() + b, e.inv_mass.data() + b, e.inv_inertia.data() + b, e.dx.data() + b,
                         e.dy.data() + b, e.dphi.data() + b, e.x.data() + b, e.y.data() + b, e.phi.data() + b,
                         e.radius.data() + b, dt_v, dt, prefilter_limit(limit2), end - b, e.active.data() + b, tests.max_d2);
    return may ? find_overstep(e, b, end, limit2) : Overstep{};
  }
  for (std::size_t i = b; i < end; ++i) {
    if (!e.active[i]) continue;
    switch (e.motion[i]) {
      case Motion::free:  // (K17): v_t = v_{t−Δt} + a_t Δt
        e.vx[i] += dt_v * e.fx[i] * e.inv_mass[i];
        e.vy[i] += dt_v * e.fy[i] * e.inv_mass[i];
        e.omega[i] += dt_v * e.moment[i] * e.inv_inertia[i];
        break;
      case Motion::fixed:
        e.vx[i] = e.vy[i] = e.omega[i] = 0.0;
        break;
      case Motion::driven: {
        const Vec2 v = m_.drives[static_cast<std::size_t>(e.drive[i])].at(time_ + 0.5 * dt);
        e.vx[i] = v.x;
        e.vy[i] = v.y;
        e.omega[i] = 0.0;
        break;
      }
    }
    if (k19 && e.motion[i] == Motion::free) {  // (K19): averaged increment
      e.dx[i] = 0.5 * (e.dx[i] + e.vx[i] * dt);
      e.dy[i] = 0.5 * (e.dy[i] + e.vy[i] * dt);
      e.dphi[i] = 0.5 * (e.dphi[i] + e.omega[i] * dt);
    } else {  // (K18)
      e.dx[i] = e.vx[i] * dt;
      e.dy[i] = e.vy[i] * dt;
      e.dphi[i] = e.omega[i] * dt;
    }
    e.x[i] += e.dx[i];
    e.y[i] += e.dy[i];
    e.phi[i] += e.dphi[i];
  }
  const bool may = may_overstep(e.dx.data() + b, e.dy.data() + b, e.radius.data() + b, prefilter_limit(limit2), end - b, tests.max_d2);
  return may ? find_overstep(e, b, end, limit2) : Overstep{};
}

Simulation::Overstep Simulation::overstep() const {
  Overstep worst;
  for (const Overstep& o : oversteps_) take_worse(worst, o);  // shares in element order
  return worst;
}

}  // namespace dem
