#include "dem/core/simulation.hpp"
// Simulation: the constructor (the start's increments, the preloads' static zeroth step) and step(), Kiyama's
// cycle in order. Its parts: rebuild.cpp, contact_sweeps.cpp, integration.cpp, parallel_step.cpp,
// observables.cpp; the readable one-thread statement of the cycle, reference_step.cpp.

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "dem/core/stability.hpp"
#include "dem/core/step_loops.hpp"

namespace dem {

using step_detail::weight;

Simulation::Simulation(Model model) : m_(std::move(model)) {
  const Elements& e = m_.elements;
  if (m_.numerics.dt <= 0.0) throw std::invalid_argument("numerics.dt must be positive");
  double rmin = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < e.size(); ++i) rmin = std::min(rmin, e.radius[i]);
  skin_ = m_.numerics.skin > 0.0 ? m_.numerics.skin : (e.size() ? 0.25 * rmin : 0.0);
  // Initial increments (docs/references.md §1.4, "plain" start): Δx_0 = v(0)Δt.
  Elements& w = m_.elements;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w.motion[i] == Motion::fixed) {
      w.vx[i] = w.vy[i] = w.omega[i] = 0.0;
    } else if (w.motion[i] == Motion::driven) {
      const Vec2 v = m_.drives[static_cast<std::size_t>(w.drive[i])].at(0.0);
      w.vx[i] = v.x;
      w.vy[i] = v.y;
      w.omega[i] = 0.0;
    }
    w.dx[i] = w.vx[i] * m_.numerics.dt;
    w.dy[i] = w.vy[i] * m_.numerics.dt;
    w.dphi[i] = w.omega[i] * m_.numerics.dt;
  }
  for (Wall& wl : m_.walls)
    wl.increment = wl.drive >= 0 ? m_.drives[static_cast<std::size_t>(wl.drive)].at(0.0) * m_.numerics.dt
                                 : Vec2{};
  check_polygon_model();
  form_gap_springs();  // (B1): the bonds of the start
  for (const PairLaw& law : m_.laws) linear_pairs_.with_rolling = linear_pairs_.with_rolling || law.rolling.enabled;
  rebuild();
  if (!m_.preloads.empty()) apply_preloads();
}

void Simulation::apply_preloads() {
  Elements& e = m_.elements;
  // The preload is the increment of a static zeroth step: contacts are formed and loaded by it with
  // 1/Δt = 0 (no dashpot forces); nothing is integrated. The increments of step 0 are then restored.
  std::vector<double> keep_dx = e.dx, keep_dy = e.dy, keep_dphi = e.dphi;
  std::fill(e.dx.begin(), e.dx.end(), 0.0);
  std::fill(e.dy.begin(), e.dy.end(), 0.0);
  std::fill(e.dphi.begin(), e.dphi.end(), 0.0);
  for (const Preload& p : m_.preloads) {
    const std::size_t i = index_of(p.element);  // the case's numbering (the elements may be reordered)
    const Vec2 c{e.x[i], e.y[i]}, d = c - p.about;
    const double cs = std::cos(p.rotation), sn = std::sin(p.rotation);
    const Vec2 moved = p.about + Vec2{cs * d.x - sn * d.y, sn * d.x + cs * d.y};
    e.dx[i] = moved.x - c.x;
    e.dy[i] = moved.y - c.y;
    e.dphi[i] = p.rotation;
    e.x[i] = moved.x;
    e.y[i] = moved.y;
    e.phi[i] += p.rotation;
  }
  for (Wall& w : m_.walls) w.force = {};
  std::vector<Vec2> wall_inc;
  for (Wall& w : m_.walls) {
    wall_inc.push_back(w.increment);
    w.increment = {};
  }
  preloading_ = true;
  if (threads_used() == 1) {
    sweep_scatter(0.0);  // onto the forces the elements hold
    sum_wall_forces();
    sweep_polygons(0.0);
  } else {
    if (shares_.threads != threads_used()) share_work(threads_used());
    WorkerThreads& pool = workers(threads_used());
    auto body = [&](int t) {
      sweep_share(0.0, static_cast<std::size_t>(t), false);  // onto the forces the elements hold
      pool.signal_done(t);
      pool.wait_earlier(t);  // the slots that touch t's shared elements belong to the threads before it
      gather_shared(static_cast<std::size_t>(t), false);
    };
    pool.run(body);
    sum_wall_forces();
  }
  preloading_ = false;
  for (std::size_t k = 0; k < m_.walls.size(); ++k) m_.walls[k].increment = wall_inc[k];
  e.dx = keep_dx;
  e.dy = keep_dy;
  e.dphi = keep_dphi;
  rebuild();
}

void Simulation::open_wall(std::uint32_t w) {
  m_.walls[w].open = true;
  std::erase_if(linear_walls_, [w](const LinearSlot& s) { return s.j == w; });
  std::erase_if(face_walls_, [w](const FaceSlot& s) { return s.j == w; });
  std::erase_if(polygon_walls_, [w](const PolygonSlot& s) { return s.j == w; });
  tested_step_ = -1;
  index_contacts();  // the slot lists changed
}

int Simulation::threads_asked() const {
  if (polygons_) return 1;  // polygon contacts are swept on one thread (polygon_sweep.cpp)
  if (!gap_springs_.empty()) return 1;  // so are gap springs (gap_springs.cpp)
  const std::size_t most = std::max<std::size_t>(1, m_.elements.size() / min_per_thread_);
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads_), most));
}

int Simulation::threads_used() const {
  const int asked = threads_asked();
  return governed_ && governor_.most() == asked ? std::min(asked, governor_.threads()) : asked;
}

double Simulation::velocity_dt() const {
  // docs/references.md §1.4: a staggered start takes half a velocity step first, v_0 = v(Δt/2).
  const double dt = m_.numerics.dt;
  return (step_ == 0 && m_.numerics.velocity_start == VelocityStart::staggered) ? 0.5 * dt : dt;
}

void Simulation::move_walls() {
  const double dt = m_.numerics.dt;
  for (Wall& w : m_.walls) {
    w.increment = w.drive >= 0 ? m_.drives[static_cast<std::size_t>(w.drive)].at(time_ + 0.5 * dt) * dt : Vec2{};
    w.a = w.a + w.increment;
    w.b = w.b + w.increment;
  }
}

double Simulation::next_rebuild_limit2() const {
  if (m_.base_plate.enabled) return -1.0;  // integrated after base friction, in a second pass
  for (const Wall& w : m_.walls)
    if (w.drive >= 0) return -1.0;  // the limit of the next step depends on where the walls move to
  return rebuild_limit2();          // static walls: the limit after this step's rebuild, if any, holds
}

void Simulation::step() {
  const bool clocked = timings_.on || (governed_ && threads_asked() > 1);
  const double wall0 = clocked ? phase_clock() : 0.0;
  const double jobs0 = timings_.on && workers_.pool ? workers_.pool->job_seconds() : 0.0;
  const std::int64_t rebuilds0 = rebuilds_;
  if (governed_ && governor_.most() != threads_asked()) governor_.start(threads_asked());
  const int nt = threads_used();
  if (timings_.on && timings_.threads.empty()) timings_.threads.resize(1);
  // The rebuild test of this step (needs_rebuild) was made by the last step's integration, element by
  // element in the same pass, if nothing changed the state since (tested_step_ == step_).
  const bool tested = step_ > 0 && tested_step_ == step_;
  if (tested) {
    std::uint8_t any = 0;
    for (std::uint8_t d : displaced_) any |= d;
    if (any) rebuild();
  }
  tested_step_ = -1;
  if (nt == 1 && step_ > 0 && !tested && needs_rebuild()) rebuild();  // on several threads: inside the job below
  for (Wall& w : m_.walls) w.force = {};
  const double inv_dt = 1.0 / m_.numerics.dt;
  const std::size_t n = m_.elements.size();
  // Base friction (M21) acts between the contact forces and the integration, on one thread; without
  // it each thread integrates the elements it has just summed.
  const bool plate = m_.base_plate.enabled;
  const double dt_v = velocity_dt();
  const double limit2_step = m_.numerics.max_step_fraction * m_.numerics.max_step_fraction;
  const double limit2_next = plate ? -1.0 : next_rebuild_limit2();  // < 0: the next step tests by itself
  if (nt == 1) {  // each slot adds its forces at once, in slot order
    Elements& e = m_.elements;
    const double t0 = timings_.on ? phase_clock() : 0.0;
    weight(e.fx.data(), e.fy.data(), e.mass.data(), m_.gravity, n);  // (K15): gravity
    std::fill(e.moment.begin(), e.moment.end(), 0.0);
    sweep_scatter(inv_dt);
    sum_wall_forces();
    sweep_polygons(inv_dt);  // (P5–P8): after the other sweeps, as in the reference step
    sweep_gap_springs(inv_dt);  // (B2–B5): last, as in the reference step
    const double t1 = timings_.on ? phase_clock() : 0.0;
    if (!plate) {
      range_tests_.assign(1, RangeTests{});
      oversteps_.assign(1, integrate_range(0, n, dt_v, freedom(0, n), limit2_step, limit2_next, range_tests_[0]));
      displaced_.assign(1, range_tests_[0].displaced);
    }
    if (timings_.on) {
      timings_.threads[0].sweep += t1 - t0;
      timings_.threads[0].integrate += phase_clock() - t1;
    }
  } else {  // the same sums, shared as thread_shares.hpp says (parallel_step.cpp)
    step_on_threads(nt, tested, inv_dt, dt_v, limit2_step, limit2_next, plate);
  }
  if (plate) {
    travel_ = kTravelUnknown;  // (the next step tests by itself)
    advance_base_plate();
    RangeTests unused;
    if (nt == 1) {
      oversteps_.assign(1, integrate_range(0, n, dt_v, freedom(0, n), limit2_step, -1.0, unused));
    } else {
      oversteps_.assign(static_cast<std::size_t>(nt), Overstep{});
      auto body = [&](int t) {
        const std::size_t k = static_cast<std::size_t>(t);
        RangeTests none;
        oversteps_[k] = integrate_range(shares_.first[k], shares_.first[k + 1], dt_v, freedom(shares_.first[k], shares_.first[k + 1]), limit2_step, -1.0, none);
      };
      workers(nt).run(body);
    }
  } else {  // every element moved by at most the largest increment of the step's ranges
    double most = 0.0;
    for (const RangeTests& r : range_tests_) {
      most = r.max_d2 > most ? r.max_d2 : most;
      rebuild_tests_skipped_ += r.skipped;
    }
    // x += Δx rounds each coordinate by up to half an ulp, ≤ 2⁻⁵³ |x|: the position moved by at most
    // |Δx| + 2⁻⁵²·max(|x|, |y|), and no active element's coordinate exceeds the extent at the last
    // rebuild plus its travel since.
    const double step = std::sqrt(most);
    travel_ += step + kRoundoff * (search_.extent() + travel_ + step);
  }
  move_walls();
  if (limit2_next >= 0.0) tested_step_ = step_ + 1;
  ++step_;
  if (clocked) {
    const double wall = phase_clock() - wall0;
    if (timings_.on) {
      timings_.step_wall += wall;
      if (workers_.pool) timings_.step_jobs += workers_.pool->job_seconds() - jobs0;
      ++timings_.steps;
      timings_.rebuilds += rebuilds_ - rebuilds0;
    }
    if (governed_ && threads_asked() > 1) govern(wall);
  }
  forces_step_ = keep_forces_ ? step_ : -1;
  time_ = static_cast<double>(step_) * m_.numerics.dt;
}

void Simulation::advance_base_plate() {
  // (M21) on the velocities of the array, v_{k−1}: the velocity over [t − Δt, t], so the plate's is
  // taken at t − Δt/2; then the plate moves by its velocity over [t, t + Δt] (as a driven wall does).
  const double dt = m_.numerics.dt;
  add_base_friction(m_.elements, m_.base_plate, plate_velocity(m_.base_plate, m_.drives, time_ - 0.5 * dt));
  const Vec2 d = plate_velocity(m_.base_plate, m_.drives, time_ + 0.5 * dt) * dt;
  plate_travel_.displacement = plate_travel_.displacement + d;
  plate_travel_.travel += norm(d);
}

}  // namespace dem

// ---------------------------------------------------------------------------------------------------
// Time-step guard: the bound over every contact the case can form (stability.cpp).
namespace dem {

StabilityBound Simulation::stability_bound() const {
  return assembly_stability_bound(m_, registered_stability_terms(m_));
}

double Simulation::stability_limit() const { return stability_bound().limit; }

}  // namespace dem
