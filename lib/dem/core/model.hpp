#pragma once
// Everything a run needs, resolved to SI: materials, contact laws per material pair, elements,
// walls, numerics. Built by the case reader (case_file.hpp) or directly in tests.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "dem/core/base_friction.hpp"
#include "dem/core/discharge.hpp"
#include "dem/core/elements.hpp"
#include "dem/core/polygon.hpp"
#include "dem/contact/face_contact.hpp"
#include "dem/contact/linear_contact.hpp"
#include "dem/contact/gap_spring.hpp"
#include "dem/contact/rolling_resistance.hpp"
#include "dem/core/vec2.hpp"
#include "dem/core/velocity_history.hpp"
#include "dem/core/wall.hpp"

namespace dem {

enum class Integrator : std::uint8_t {
  k18,  // Δu_t = v_t Δt: Cundall's symplectic Euler (K18)
  k19   // Δu_t = (Δu_{t−Δt} + v_t Δt)/2: Kiyama's averaged increment (K19)
};
enum class VelocityStart : std::uint8_t {
  plain,     // v_{−1} = v(0)
  staggered  // v_{−1} = v(0) − a(0)Δt/2, so that v_0 = v(Δt/2) (docs/references.md §1.4)
};
enum class LawKind : std::uint8_t { linear, face };
enum class MassBasis : std::uint8_t {
  reduced,  // η = 2ζ√(m_eff K): ζ is the damping ratio of the pair
  particle  // Kiyama's η = 2ζ√(m K) with the particle mass (K20); m = mean of the pair, m for walls
};

struct Material {
  std::string name;
  double density = 0.0;  // [kg/m³]
};

/// The contact law of one material pair.
struct PairLaw {
  LawKind kind = LawKind::linear;
  LinearSpringDashpot linear;  // kind == linear: kn, ks [N/m], mu, end rule
  RollingLaw rolling;          // kind == linear: rolling resistance (R1–R6), off by default
  GapSpringLaw gap;            // kind == linear: gap springs between disks bonded at the start (B1–B5), off by default
  FaceLaw face;                // kind == face
  double face_kn = 0.0, face_ks = 0.0;  // kind == face: discrete springs per segment [N/m] (M6), or
  bool face_modulus = false;            //   if face_modulus: k_n, k_s per unit area per unit strain [Pa] (M4, M5)
  // Damping: explicit dashpots, or a damping ratio (h_n for the face law, (M7.3)).
  bool damping_from_ratio = true;
  double damping_ratio = 0.0;
  MassBasis mass_basis = MassBasis::reduced;
  double eta_n = 0.0, eta_s = 0.0;  // explicit dashpots [N·s/m] (per segment for the face law)
  Onset onset = Onset::increment;
  bool bond_at_start = false;  // face law: contacts present at the start are bonded (intact links),
                               // also with walls and across lattices
};

struct Numerics {
  Integrator integrator = Integrator::k18;
  VelocityStart velocity_start = VelocityStart::plain;
  double dt = 0.0;        // [s]
  double duration = 0.0;  // [s]
  double skin = 0.0;      // Verlet skin of the neighbour search [m] (0: a quarter of the smallest radius)
  bool allow_unstable = false;  // run even above the stability limit (for stability studies)
  double energy_limit = 0.0;    // stop when the total energy exceeds this [J] (0: automatic)
  double max_step_fraction = 0.25;  // blow-up: no element may move more than this × its radius in one step
  std::int64_t reorder_every = 0;   // reorder the elements in space every this many neighbour-list
                                    // rebuilds (spatial_order.hpp; 0: never, the default; linear laws only)
  // The time-step guard counts as partners only the elements a free element can reach when each free
  // element moves at most this far [m] (docs/model.md G7); the run evaluates the guard again when one
  // moves farther. +inf (the default): every element counts.
  double guard_reach = std::numeric_limits<double>::infinity();
};

/// A static preload: before the first step the element is moved rigidly (rotated by `rotation` about
/// `about`) and its contacts take that motion as a static increment (springs loaded, no dashpot
/// forces), e.g. "statically rotated by 0.1° about the face centre, then released" (docs/model.md §3 M-B).
struct Preload {
  std::uint32_t element = 0;
  double rotation = 0.0;  // [rad]
  Vec2 about;             // [m]
};

struct Model {
  std::vector<Preload> preloads;
  std::vector<Material> materials;
  std::vector<PairLaw> laws;
  std::vector<std::int32_t> law_of_pair;  // materials.size()² entries, index into laws or −1
  Elements elements;
  // Polygon elements (docs/model.md §5): their shapes, and per element the index of its shape (−1 for a disk
  // or a PRE). Empty while the model has no polygon.
  std::vector<PolygonShape> polygons;
  std::vector<std::int32_t> polygon_of;
  std::vector<Wall> walls;
  std::vector<VelocityHistory> drives;
  Vec2 gravity;             // [m/s²]
  BasePlate base_plate;     // base friction (M21), base_friction.hpp; disabled by default
  double thickness = 1.0;   // element depth l [m] (docs/model.md: "per unit thickness" is l = 1)
  Numerics numerics;
  Discharge discharge;      // a silo's discharge stage (discharge.hpp); disabled by default

  std::int32_t law_index(std::int32_t mat_a, std::int32_t mat_b) const {
    return law_of_pair[static_cast<std::size_t>(mat_a) * materials.size() + mat_b];
  }
};

/// Adds one element with its mass and inertia from the material density: a disk (K: m = ρπr²l,
/// I = ½mr²), or a PRE with square mass (M17: m = 4r²lρ, I = (2/3)r²m) or disk mass (M18).
/// mass_override > 0 replaces the computed mass (inertia scales with it). Returns its index.
enum class PreMass : std::uint8_t { square, disk };
std::size_t add_element(Model& m, Shape shape, std::int32_t material, double radius, Vec2 position,
                        Vec2 velocity = {}, double omega = 0.0, PreMass pre_mass = PreMass::square,
                        double mass_override = 0.0);

/// Adds a rigid convex polygon element (docs/model.md §5): `vertices` counter-clockwise, relative to
/// `position` (any origin); the element's centre is their centroid (P1), its mass ρ A l and inertia ρ l J_c
/// (P2), or mass_override with the inertia of that mass in the same shape. Throws std::invalid_argument if
/// the vertices are not a convex polygon (polygon_problem). Returns its index.
std::size_t add_polygon(Model& m, std::int32_t material, const std::vector<Vec2>& vertices, Vec2 position,
                        Vec2 velocity = {}, double omega = 0.0, double mass_override = 0.0);

/// The corners of polygon element i in the world frame (P3), counter-clockwise (into `out`, its storage reused).
std::vector<Vec2> element_corners(const Model& m, std::size_t i);
void element_corners(const Model& m, std::size_t i, std::vector<Vec2>& out);

/// How deep elements i and j overlap (the largest penetration of their contact points, P5–P7, for a polygon;
/// r_i + r_j − D for two circles), and how deep element i overlaps wall w (≤ 0: apart).
double element_overlap(const Model& m, std::size_t i, std::size_t j);
double wall_overlap(const Model& m, std::size_t i, const Wall& w);

}  // namespace dem
