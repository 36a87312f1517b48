// Simulation's observables (simulation.hpp): energies, the contacts and their forces for outputs, the
// force on a band of a wall.
#include "dem/core/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "dem/core/step_loops.hpp"

namespace dem {

using step_detail::key;

Energies Simulation::energies() const {
  // Summed in chunks of kEnergyChunk elements, and of kEnergyChunk slots of the slot lists taken one after
  // another (linear pairs, linear walls, face pairs, face walls): each chunk in order from zero, the chunk
  // sums in chunk order. The chunks do not depend on the threads, so neither does any bit of the sums; with
  // one chunk (up to kEnergyChunk elements and slots) the sums are those of a single pass in order.
  const Elements& e = m_.elements;
  const LinearPairSlots& lp = linear_pairs_;
  const std::size_t n = e.size();
  const std::size_t n_lp = lp.size(), n_lw = linear_walls_.size(), n_fp = face_pairs_.size(), n_fw = face_walls_.size();
  const std::size_t slots = n_lp + n_lw + n_fp + n_fw;
  const std::size_t element_chunks = (n + kEnergyChunk - 1) / kEnergyChunk;
  const std::size_t chunks = element_chunks + (slots + kEnergyChunk - 1) / kEnergyChunk;
  energy_chunks_.resize(chunks);
  auto sum_elements = [&](std::size_t b, std::size_t end, Energies& en) {
    for (std::size_t i = b; i < end; ++i) {
      if (!e.active[i]) continue;
      en.kinetic += 0.5 * e.mass[i] * (e.vx[i] * e.vx[i] + e.vy[i] * e.vy[i]) +
                    0.5 * e.inertia[i] * e.omega[i] * e.omega[i];
      en.potential -= e.mass[i] * (m_.gravity.x * e.x[i] + m_.gravity.y * e.y[i]);
    }
  };
  auto sum_slots = [&](std::size_t b, std::size_t end, Energies& en) {  // slots [b, end) of the lists in turn
    auto lin = [&](std::uint8_t touching, std::int32_t law, const LinearContactHistory& h, const RollingState* ro) {
      if (!touching) return;
      const PairLaw& pl = m_.laws[static_cast<std::size_t>(law)];
      const LinearSpringDashpot& l = pl.linear;
      if (l.kn > 0.0) en.elastic += 0.5 * h.en * h.en / l.kn;
      if (l.ks > 0.0) en.elastic += 0.5 * h.es * h.es / l.ks;
      if (pl.rolling.enabled && ro->kr > 0.0) en.elastic += 0.5 * ro->mk * ro->mk / ro->kr;  // (R3): the rolling spring
    };
    auto face = [&](const FaceSlot& s) {
      if (!s.touching) return;
      const int segments = m_.laws[static_cast<std::size_t>(s.law)].face.segments;
      for (int k = 0; k < segments; ++k) {
        const SegmentState& g = s.h.seg[static_cast<std::size_t>(k)];
        if (!g.linked) continue;
        if (s.c.kn > 0.0) en.elastic += 0.5 * g.pe * g.pe / s.c.kn;
        if (s.c.ks > 0.0) en.elastic += 0.5 * g.qe * g.qe / s.c.ks;
      }
    };
    std::size_t at = 0;  // where the list starts in the sequence
    for (std::size_t k = std::max(b, at); k < std::min(end, at + n_lp); ++k)
      lin(lp.touching[k - at], lp.law[k - at], lp.state[k - at].h, lp.with_rolling ? &lp.rolling[k - at] : nullptr);
    at += n_lp;
    for (std::size_t k = std::max(b, at); k < std::min(end, at + n_lw); ++k) {
      const LinearSlot& s = linear_walls_[k - at];
      lin(s.touching, s.law, s.h, &s.rolling);
    }
    at += n_lw;
    for (std::size_t k = std::max(b, at); k < std::min(end, at + n_fp); ++k) face(face_pairs_[k - at]);
    at += n_fp;
    for (std::size_t k = std::max(b, at); k < std::min(end, at + n_fw); ++k) face(face_walls_[k - at]);
  };
  auto sum_chunks = [&](std::size_t c0, std::size_t c1) {
    for (std::size_t c = c0; c < c1; ++c) {
      Energies en;  // a local: the sums stay in registers
      if (c < element_chunks) {
        sum_elements(c * kEnergyChunk, std::min(n, (c + 1) * kEnergyChunk), en);
      } else {
        const std::size_t b = (c - element_chunks) * kEnergyChunk;
        sum_slots(b, std::min(slots, b + kEnergyChunk), en);
      }
      energy_chunks_[c] = en;
    }
  };
  const int nt = threads_used();
  if (nt == 1 || chunks < 2) {
    sum_chunks(0, chunks);
  } else {
    auto body = [&](int t) {  // a share of the element chunks and one of the slot chunks (they cost differently)
      const auto q = static_cast<std::size_t>(t), m = static_cast<std::size_t>(nt);
      const std::size_t ec = element_chunks, sc = chunks - element_chunks;
      sum_chunks(ec * q / m, ec * (q + 1) / m);
      sum_chunks(ec + sc * q / m, ec + sc * (q + 1) / m);
    };
    workers(nt).run(body);
  }
  Energies en;
  for (std::size_t c = 0; c < element_chunks; ++c) {
    en.kinetic += energy_chunks_[c].kinetic;
    en.potential += energy_chunks_[c].potential;
  }
  for (std::size_t c = element_chunks; c < chunks; ++c) en.elastic += energy_chunks_[c].elastic;
  if (polygons_) en.elastic += polygon_elastic_energy();  // (one thread: the sum is the same for any thread count)
  en.elastic += gap_spring_energy();  // (B2): the bonds' springs, tension or compression
  return en;
}

void Simulation::require_contact_forces(const char* reader) const {
  if (!contact_forces_current())
    throw std::logic_error(fmt::format("Simulation::{}: the contact forces of step {} were not kept (keep_contact_forces)",
                                       reader, step_));
}

double Simulation::linear_pair_rolling_moment(std::size_t k) const {
  const LinearPairSlots& lp = linear_pairs_;
  return lp.with_rolling && m_.laws[static_cast<std::size_t>(lp.law[k])].rolling.enabled ? lp.rolling[k].m : 0.0;
}

std::vector<ContactView> Simulation::contacts() const {
  require_contact_forces("contacts");
  std::vector<ContactView> out;
  const LinearPairSlots& lp = linear_pairs_;
  for (std::size_t k = 0; k < lp.size(); ++k) {
    if (!lp.touching[k]) continue;
    const LinearContactResultant& s = lp.resultant[k];
    out.push_back({lp.pair[k].i, lp.pair[k].j, false, s.nx, s.ny, s.fn, s.fs, 1, linear_pair_rolling_moment(k)});
  }
  for (const auto& s : face_pairs_)
    if (s.touching) out.push_back({s.i, s.j, false, s.nx, s.ny, s.f.p, s.f.q, s.f.links});
  for (const auto& s : linear_walls_)
    if (s.touching) out.push_back({s.i, s.j, true, s.nx, s.ny, s.f.fn, s.f.fs, 1, s.rolling.m});
  for (const auto& s : face_walls_)
    if (s.touching) out.push_back({s.i, s.j, true, s.nx, s.ny, s.f.p, s.f.q, s.f.links});
  polygon_contacts(out);  // one per contact point of a polygon
  return out;
}

Simulation::BandForce Simulation::wall_band_force(std::uint32_t w, double s0, double s1) const {
  const Wall& wall = m_.walls[w];
  const Vec2 ab = wall.b - wall.a;
  const double len = wall.kind == WallKind::segment ? norm(ab) : 0.0;
  const Vec2 along = len > 0.0 ? ab * (1.0 / len) : Vec2{0.0, 0.0};
  const Elements& e = m_.elements;
  BandForce out;
  auto add = [&](std::uint32_t i, std::uint32_t j, std::uint8_t touching, double nx, double ny, double fn, double fs) {
    if (j != w || !touching) return;
    const Vec2 n{nx, ny}, t{-ny, nx};                                   // t = n rotated by +90°
    const Vec2 point = closest_point(wall, Vec2{e.x[i], e.y[i]});       // where the element touches it
    const double s = len > 0.0 ? dot(point - wall.a, along) : 0.0;
    if (s < s0 || s >= s1) return;
    out.normal += fn;                                                   // compression positive
    out.max_normal = std::max(out.max_normal, fn);
    out.tangential += dot(n * fn + t * fs, along);                      // force on the wall along a→b
    ++out.contacts;
  };
  for (const auto& c : linear_walls_) add(c.i, c.j, c.touching, c.nx, c.ny, c.f.fn, c.f.fs);
  for (const auto& c : face_walls_) add(c.i, c.j, c.touching, c.nx, c.ny, c.f.p, c.f.q);
  for (const PolygonSlot& p : polygon_walls_) {  // each contact point of a polygon where it touches (P6)
    if (p.j != w) continue;
    for (const CornerSlot& c : p.corners) {
      const Vec2 n{c.nx, c.ny}, t{-c.ny, c.nx};
      const double s = len > 0.0 ? dot(closest_point(wall, Vec2{c.px, c.py}) - wall.a, along) : 0.0;
      if (s < s0 || s >= s1) continue;
      out.normal += c.f.fn;
      out.max_normal = std::max(out.max_normal, c.f.fn);
      out.tangential += dot(n * c.f.fn + t * c.f.fs, along);
      ++out.contacts;
    }
  }
  return out;
}

std::size_t Simulation::contact_count() const {
  std::size_t n = 0;
  for (std::uint8_t t : linear_pairs_.touching) n += t;
  for (const auto& s : face_pairs_) n += s.touching;
  for (const auto& s : linear_walls_) n += s.touching;
  for (const auto& s : face_walls_) n += s.touching;
  for (const auto* list : {&polygon_pairs_, &polygon_walls_})
    for (const PolygonSlot& s : *list) n += s.corners.size();  // each contact point of a polygon
  return n;
}

std::pair<double, std::size_t> Simulation::contact_force_sum() const {
  require_contact_forces("contact_force_sum");
  double sum = 0.0;
  std::size_t n = 0;
  auto add = [&](bool touching, double fn, double fs) {
    if (!touching || (fn == 0.0 && fs == 0.0)) return;
    sum += std::hypot(fn, fs);
    ++n;
  };
  for (std::size_t k = 0; k < linear_pairs_.size(); ++k)
    add(linear_pairs_.touching[k], linear_pairs_.resultant[k].fn, linear_pairs_.resultant[k].fs);
  for (const auto& s : linear_walls_) add(s.touching, s.f.fn, s.f.fs);
  for (const auto& s : face_pairs_) add(s.touching, s.f.p, s.f.q);
  for (const auto& s : face_walls_) add(s.touching, s.f.p, s.f.q);
  for (const auto* list : {&polygon_pairs_, &polygon_walls_})
    for (const PolygonSlot& s : *list)
      for (const CornerSlot& c : s.corners) add(true, c.f.fn, c.f.fs);
  return {sum, n};
}

ContactView Simulation::contact(std::uint32_t i, std::uint32_t j, bool wall) const {
  if (!wall && j < i) std::swap(i, j);
  auto find = [&](const auto& slots) -> const auto* {
    auto it = std::lower_bound(slots.begin(), slots.end(), key(i, j),
                               [](const auto& s, std::uint64_t k) { return key(s.i, s.j) < k; });
    return (it != slots.end() && it->i == i && it->j == j && it->touching) ? &*it : nullptr;
  };
  if (wall) {
    if (const auto* s = find(linear_walls_)) return {i, j, wall, s->nx, s->ny, s->f.fn, s->f.fs, 1, s->rolling.m};
  } else {
    const std::vector<SlotPair>& p = linear_pairs_.pair;
    const auto it = std::lower_bound(p.begin(), p.end(), key(i, j),
                                     [](const SlotPair& s, std::uint64_t k) { return key(s.i, s.j) < k; });
    const std::size_t k = static_cast<std::size_t>(it - p.begin());
    if (it != p.end() && it->i == i && it->j == j && linear_pairs_.touching[k]) {
      require_contact_forces("contact");
      const LinearContactResultant& s = linear_pairs_.resultant[k];
      return {i, j, wall, s.nx, s.ny, s.fn, s.fs, 1, linear_pair_rolling_moment(k)};
    }
  }
  if (const auto* s = find(wall ? face_walls_ : face_pairs_))
    return {i, j, wall, s->nx, s->ny, s->f.p, s->f.q, s->f.links};
  if (const PolygonSlot* p = polygons_ ? polygon_slot(i, j, wall) : nullptr) {
    // a polygon's contact points together: the sums of their normal and shear forces, each in its own
    // frame, and the normal of the first point (from i towards j)
    ContactView v{i, j, wall, 0.0, 0.0, 0.0, 0.0, static_cast<int>(p->corners.size())};
    const double sign = p->swapped ? -1.0 : 1.0;
    v.nx = sign * p->corners[0].nx, v.ny = sign * p->corners[0].ny;
    for (const CornerSlot& c : p->corners) v.fn += c.f.fn, v.fs += c.f.fs;
    return v;
  }
  return {i, j, wall, 0.0, 0.0, 0.0, 0.0, 0};
}


}  // namespace dem
