// Name-based table of the reference solvers (see ref/registry.hpp).
#include "ref/registry.hpp"

#include <cmath>
#include <iterator>
#include <numbers>
#include <stdexcept>

#include "ref/base_friction.hpp"
#include "ref/base_friction_m21.hpp"
#include "ref/base_friction_onset.hpp"
#include "ref/base_friction_pre_face.hpp"
#include "ref/base_friction_travel.hpp"
#include "ref/beam.hpp"
#include "ref/block_on_incline.hpp"
#include "ref/disk_on_slope.hpp"
#include "ref/elastic_contact_2d.hpp"
#include "ref/face_rotation.hpp"
#include "ref/free_fall.hpp"
#include "ref/impact.hpp"
#include "ref/lattice_beam.hpp"
#include "ref/oscillator.hpp"
#include "ref/pre_time_step.hpp"
#include "ref/require.hpp"
#include "ref/resting_overlap.hpp"
#include "ref/rocking_block.hpp"
#include "ref/gap_spring.hpp"
#include "ref/oblique_impact.hpp"
#include "ref/rolling_disk.hpp"
#include "ref/silo.hpp"
#include "ref/silo_fill.hpp"
#include "ref/spring_layer.hpp"
#include "ref/stability.hpp"

namespace ref {

namespace {

// Read access to validated arguments.
struct Args {
  const std::map<std::string, double>& values;
  double operator()(const std::string& name) const { return values.at(name); }
  Oscillator oscillator() const { return Oscillator((*this)("m"), (*this)("K"), (*this)("eta")); }
  // An argument that must hold a whole number in [1, 10^6].
  int count(const std::string& name) const {
    const double value = (*this)(name);
    if (!(value >= 1.0 && value <= 1e6 && value == std::floor(value)))
      detail::fail("ref::evaluate", name + " must be a whole number in [1, 1e6]", value);
    return static_cast<int>(value);
  }
};

FaceRotationForce face_rotation_force(const Args& a) {
  const double ends = a("ends");
  if (ends != 0.0 && ends != 1.0) detail::fail("ref::evaluate", "ends must be 0 or 1", ends);
  return face_rotation_wall_force(a("Kn"), a("Ks"), a("r"), a.count("N"), ends == 1.0, a("theta"));
}

struct Entry {
  SolverInfo info;
  double (*function)(const Args&);
};

namespace argument {
const SolverArgument zeta{"zeta", "1", "damping ratio eta/(2 sqrt(m K))"};
const SolverArgument mass{"m", "kg", "(effective) mass"};
const SolverArgument stiffness{"K", "N/m", "contact stiffness"};
const SolverArgument damping{"eta", "N s/m", "dashpot coefficient"};
const SolverArgument approach_speed{"v0", "m/s", "approach speed at first touch"};
const SolverArgument position0{"x0", "m", "initial position"};
const SolverArgument velocity0{"v0", "m/s", "initial velocity"};
const SolverArgument time{"t", "s", "time"};
const SolverArgument gravity{"g", "m/s^2", "gravitational acceleration"};
const SolverArgument slope{"alpha", "rad", "slope angle"};
const SolverArgument friction{"phi", "rad", "base friction angle"};
const SolverArgument tilt{"psi", "rad", "tilt of the block's base face, alpha + theta"};
const SolverArgument block_width{"W", "m", "block base (the face on the slope)"};
const SolverArgument block_height{"H", "m", "block height"};
const SolverArgument elements_w{"n_w", "1", "square elements along W (integer)"};
const SolverArgument elements_h{"n_h", "1", "square elements along H (integer)"};
const SolverArgument plate_travel{"delta_B", "m", "base-plate travel"};
const SolverArgument rotation{"theta", "rad", "rotation of the block, in [0, pi/2]"};
const SolverArgument beam_width{"b", "m", "beam width (the out-of-plane thickness)"};
const SolverArgument beam_depth{"h", "m", "beam depth"};
const SolverArgument beam_span{"L", "m", "span between the supports"};
const SolverArgument beam_rows{"n_h", "1", "element rows across the depth (integer)"};
const SolverArgument beam_segments{"N", "1", "segments per face (integer)"};
const SolverArgument beam_face_ends{"ends", "1", "0: segment centres (M13.1), 1: face ends (M13.2, N = 2)"};
const SolverArgument support_stiffness{"k_c", "N/m", "stiffness of each support contact (in series)"};

// a bonded face turned rigidly (ref/face_rotation.hpp)
const std::vector<SolverArgument> face_rotation{
    {"Kn", "N/m", "normal stiffness of one segment spring"}, {"Ks", "N/m", "shear stiffness of one segment spring"},
    {"r", "m", "half-length of the face (the element's radius)"}, {"N", "1", "number of segment springs"},
    {"ends", "1", "1: springs at the face ends (M13.2, N = 2); 0: at the segment centres (M13.1)"},
    {"theta", "rad", "rotation about the element's centre, counter-clockwise positive"}};
}  // namespace argument

// The arguments of the onset solvers (ref/base_friction_onset.hpp).
std::vector<SolverArgument> onset_arguments() {
  return {argument::slope, {"phi_w", "rad", "block-slope friction angle"}, argument::block_width,
          argument::block_height, argument::elements_w, argument::elements_h};
}

// The M-D lattice beam of ref/lattice_beam.hpp from registry arguments (radius r = h/(2 n_h)).
std::vector<SolverArgument> lattice_beam_arguments(bool strength) {
  std::vector<SolverArgument> list{
      argument::beam_width, argument::beam_depth, argument::beam_span,
      {"kn", "Pa", "face normal stiffness per unit strain"}, {"ks", "Pa", "face shear stiffness per unit strain"},
      argument::beam_rows, {"n_l", "1", "elements along the beam (even integer)"}, argument::beam_segments,
      argument::beam_face_ends, {"k_c", "N/m", "normal stiffness of each disk contact"},
      {"k_t", "N/m", "tangential stiffness of each disk contact (0: frictionless)"},
      {"k_pt", "N/m", "tangential stiffness of the platen on the load disk (0: frictionless)"},
      {"R_s", "m", "support disk radius"}, {"R_l", "m", "load disk radius"}};
  if (strength) list.push_back({"sigma_t", "Pa", "tensile strength of the face springs"});
  return list;
}

LatticeBeamModel lattice_beam_model(const Args& a) {
  LatticeBeamModel m;
  m.rows = a.count("n_h");
  m.columns = a.count("n_l");
  m.radius = a("h") / (2.0 * m.rows);
  m.thickness = a("b");
  m.kn = a("kn");
  m.ks = a("ks");
  m.segments = a.count("N");
  m.where = a("ends") != 0.0 ? SegmentPositions::face_ends : SegmentPositions::centres;
  m.span = a("L");
  m.support_radius = a("R_s");
  m.load_radius = a("R_l");
  m.contact_kn = a("k_c");
  m.contact_kt = a("k_t");
  m.platen_kt = a("k_pt");
  return m;
}

/// The solvers of single contacts: impact, oscillator, free fall, a face in bending, rest, stability limits (refs §1).
std::vector<Entry> contact_entries() {
  return {
    {{"impact.restitution_A",
      "restitution, contact ends at zero overlap (refs §1.2)",
      {argument::zeta},
      "1"},
     [](const Args& a) { return restitution(ContactEnd::elastic_force_zero, a("zeta")); }},
    {{"impact.restitution_B",
      "restitution, contact ends at zero total force (refs §1.2)",
      {argument::zeta},
      "1"},
     [](const Args& a) { return restitution(ContactEnd::total_force_zero, a("zeta")); }},
    {{"impact.duration_A",
      "contact duration, convention A; inf for zeta >= 1 (refs §1.2)",
      {argument::mass, argument::stiffness, argument::damping},
      "s"},
     [](const Args& a) {
       return contact_duration(ContactEnd::elastic_force_zero, a.oscillator());
     }},
    {{"impact.duration_B",
      "contact duration, convention B (refs §1.2)",
      {argument::mass, argument::stiffness, argument::damping},
      "s"},
     [](const Args& a) {
       return contact_duration(ContactEnd::total_force_zero, a.oscillator());
     }},
    {{"impact.max_overlap",
      "largest overlap during a normal impact (refs §1.2)",
      {argument::mass, argument::stiffness, argument::damping, argument::approach_speed},
      "m"},
     [](const Args& a) { return maximum_overlap(a.oscillator(), a("v0")).overlap; }},
    {{"oscillator.position",
      "x(t) of m x'' + eta x' + K x = 0 (refs §1.1)",
      {argument::mass, argument::stiffness, argument::damping, argument::position0,
       argument::velocity0, argument::time},
      "m"},
     [](const Args& a) {
       return oscillator_state(a.oscillator(), {a("x0"), a("v0")}, a("t")).position;
     }},
    {{"oscillator.velocity",
      "x'(t) of m x'' + eta x' + K x = 0 (refs §1.1)",
      {argument::mass, argument::stiffness, argument::damping, argument::position0,
       argument::velocity0, argument::time},
      "m/s"},
     [](const Args& a) {
       return oscillator_state(a.oscillator(), {a("x0"), a("v0")}, a("t")).velocity;
     }},
    {{"free_fall.position",
      "x0 + v0 t + g t^2/2 (refs §1.6)",
      {argument::position0, argument::velocity0, argument::gravity, argument::time},
      "m"},
     [](const Args& a) { return free_fall_position(a("x0"), a("v0"), a("g"), a("t")); }},
    {{"free_fall.velocity",
      "v0 + g t (refs §1.6)",
      {argument::velocity0, argument::gravity, argument::time},
      "m/s"},
     [](const Args& a) { return free_fall_velocity(a("v0"), a("g"), a("t")); }},
    {{"face.bending_moment",
      "moment of a uniform normal spring layer on a face of half-length a turned by theta: k a^2 theta / 3",
      {{"k", "N/m", "total normal stiffness of the face"}, {"a", "m", "half-length of the face"},
       {"theta", "rad", "small rotation about the face centre"}},
      "N m"},
     [](const Args& a) { return spring_layer_moment(a("k"), a("a"), a("theta")); }},
    {{"face.no_tension_moment",
      "moment of N no-tension springs (k/N each, at the segment centres) on a face pressed by the approach delta and "
      "turned by theta about its contact point; the centre's approach grows by (r - delta)(1 - cos theta)",
      {{"k", "N/m", "total normal stiffness of the face"}, {"a", "m", "half-length of the face"},
       {"N", "1", "segment count (integer)"}, {"delta", "m", "approach before the turn"}, {"r", "m", "element radius"},
       {"theta", "rad", "rotation about the contact point, >= 0"}},
      "N m"},
     [](const Args& a) { return no_tension_face_moment(a("k"), a("a"), a.count("N"), a("delta"), a("r"), a("theta")); }},
    {{"face.rotation_wall_fx",
      "force along the wall of a bonded face turned rigidly by theta about its centre (refs §4.7): sum K_s (s_i (cos theta - 1) + r sin theta)",
      argument::face_rotation,
      "N"},
     [](const Args& a) { return face_rotation_force(a).fx; }},
    {{"face.rotation_wall_fy",
      "force normal to the wall (+: pulled towards the element) of the same face: sum K_n (s_i sin theta + r (1 - cos theta))",
      argument::face_rotation,
      "N"},
     [](const Args& a) { return face_rotation_force(a).fy; }},
    {{"face.rotation_moment_wall_frame",
      "moment about its centre on an element whose bonded face is turned rigidly by theta, the spring forces acting at the wall's points (M19; refs §4.7)",
      argument::face_rotation,
      "N m"},
     [](const Args& a) { return face_rotation_force(a).moment; }},
    {{"rest.overlap",
      "equilibrium overlap m g / K on a linear spring (refs §1.6, §1.7)",
      {argument::mass, argument::gravity, argument::stiffness},
      "m"},
     [](const Args& a) { return resting_overlap(a("m"), a("g"), a("K")); }},
    {{"stability.K18_limit_W",
      "largest stable omega0 dt of K18 (refs §1.5)",
      {argument::zeta},
      "1"},
     [](const Args& a) { return stability_limit(Scheme::K18, a("zeta")); }},
    {{"stability.K19_limit_W",
      "largest stable omega0 dt of K19 (refs §1.5)",
      {argument::zeta},
      "1"},
     [](const Args& a) { return stability_limit(Scheme::K19, a("zeta")); }},
    {{"stability.K18_limit_dt",
      "largest stable dt of K18 for one mass on K, eta (refs §1.5)",
      {argument::mass, argument::stiffness, argument::damping},
      "s"},
     [](const Args& a) { return stability_limit_time_step(Scheme::K18, a.oscillator()); }},
    {{"stability.K19_limit_dt",
      "largest stable dt of K19 for one mass on K, eta (refs §1.5)",
      {argument::mass, argument::stiffness, argument::damping},
      "s"},
     [](const Args& a) { return stability_limit_time_step(Scheme::K19, a.oscillator()); }},
    {{"matsui.pair_time_step",
      "Matsui's dt < h_n sqrt(m/k) for one PRE contact, k the whole face's normal stiffness N K_n (M26)",
      {argument::zeta, argument::mass, argument::stiffness},
      "s"},
     [](const Args& a) { return matsui_time_step(a("zeta"), a("m"), a("K")); }},
  };
}

/// The solvers of blocks: on an incline (Sagaseta, Goodman & Bray) and in a base-friction model (M21; refs §2, §3).
std::vector<Entry> block_entries() {
  return {
    {{"incline.slide_distance",
      "slide of a block from rest, 0 if it holds (M20, refs §2.1)",
      {argument::slope, argument::friction, argument::gravity, argument::time},
      "m"},
     [](const Args& a) { return slide_distance(a("alpha"), a("phi"), a("g"), a("t")); }},
    {{"incline.mode",
      "Sagaseta mode: 0 stable, 1 slide, 2 topple, 3 slide+topple (refs §2.3)",
      {argument::slope,
       argument::friction,
       {"b", "m", "block base along the slope"},
       {"h", "m", "block height"}},
      "1"},
     [](const Args& a) {
       detail::require_positive("incline.mode", "h", a("h"));
       return static_cast<double>(mode_sagaseta(a("alpha"), a("phi"), a("b") / a("h")));
     }},
    {{"rocking.impact_time",
      "Housner's rocking block: time from release at tilt theta0 to the first impact (refs §2.4; GSL QAWS)",
      {{"b", "m", "half the block's width"}, {"h", "m", "half the block's height"}, {"theta0", "rad", "release tilt, in (0, atan(b/h))"},
       argument::gravity},
      "s"},
     [](const Args& a) { return rocking_impact_time(a("b"), a("h"), a("theta0"), a("g")); }},
    {{"rocking.impact_speed",
      "Housner's rocking block: angular speed |omega_1| at the first impact (refs §2.4)",
      {{"b", "m", "half the block's width"}, {"h", "m", "half the block's height"}, {"theta0", "rad", "release tilt, in (0, atan(b/h))"},
       argument::gravity},
      "rad/s"},
     [](const Args& a) { return rocking_impact_speed(a("b"), a("h"), a("theta0"), a("g")); }},
    {{"rocking.rebound_tilt",
      "Housner's rocking block: tilt on the other corner after the first impact, r = 1 - 1.5 sin^2 alpha (refs §2.4)",
      {{"b", "m", "half the block's width"}, {"h", "m", "half the block's height"}, {"theta0", "rad", "release tilt, in (0, atan(b/h))"}},
      "rad"},
     [](const Args& a) { return rocking_rebound_tilt(a("b"), a("h"), a("theta0")); }},
    {{"rocking.restitution",
      "Housner's coefficient of restitution of the angular velocity, r = 1 - 1.5 sin^2 alpha (refs §2.4)",
      {{"b", "m", "half the block's width"}, {"h", "m", "half the block's height"}},
      "1"},
     [](const Args& a) { return rocking_restitution(a("b"), a("h")); }},
    {{"incline.mode_gb",
      "Goodman & Bray mode: 0 stable, 1 slide, 2 topple, 3 slide+topple (refs §2.2)",
      {argument::slope,
       argument::friction,
       {"b", "m", "block base along the slope"},
       {"h", "m", "block height"}},
      "1"},
     [](const Args& a) {
       detail::require_positive("incline.mode_gb", "h", a("h"));
       return static_cast<double>(mode_goodman_bray(a("alpha"), a("phi"), a("b") / a("h")));
     }},
    {{"base_friction.rate",
      "Bray & Goodman rotation per plate travel dtheta/ddelta_B = -lambda, 0 if no toppling "
      "(M25, refs §3.1-3.2; nested quadrature)",
      {argument::tilt, argument::block_width, argument::block_height},
      "rad/m"},
     [](const Args& a) { return base_friction_rate(a("psi"), a("W"), a("H")); }},
    {{"base_friction.theta",
      "Bray & Goodman rotation at plate travel delta_B from tilt alpha, capped at pi/2 "
      "(M25, refs §3.3; Odeint dopri5)",
      {argument::slope, argument::plate_travel, argument::block_width, argument::block_height},
      "rad"},
     [](const Args& a) { return theta_at_travel(a("delta_B"), a("alpha"), a("W"), a("H")); }},
    {{"base_friction.travel",
      "plate travel that turns the block by theta from tilt alpha, inf if it does not topple "
      "(M25, refs §3.3; quadrature)",
      {argument::slope, argument::rotation, argument::block_width, argument::block_height},
      "m"},
     [](const Args& a) { return travel_at_theta(a("theta"), a("alpha"), a("W"), a("H")); }},
    {{"base_friction.m21_rate",
      "quasi-static dtheta/ddelta_B of a rigid block of n_w x n_h square elements under "
      "Matsui's element law (M21, refs §3.7)",
      {argument::tilt, argument::block_width, argument::block_height, argument::elements_w,
       argument::elements_h},
      "rad/m"},
     [](const Args& a) {
       return m21_rate(a("psi"), a("W"), a("H"), a.count("n_w"), a.count("n_h"));
     }},
    {{"base_friction.theta_m21",
      "rotation at plate travel delta_B under the M21 rate (refs §3.7; Odeint dopri5)",
      {argument::slope, argument::plate_travel, argument::block_width, argument::block_height,
       argument::elements_w, argument::elements_h},
      "rad"},
     [](const Args& a) {
       return theta_at_travel_m21(a("delta_B"), a("alpha"), a("W"), a("H"), a.count("n_w"),
                                  a.count("n_h"));
     }},
    {{"base_friction.slide_ratio",
      "slide per plate travel of a block on its long face, sin alpha - tan phi_w cos alpha, "
      "0 if it holds (M22, refs §3.5)",
      {argument::slope, {"phi_w", "rad", "block-slope friction angle"}},
      "1"},
     [](const Args& a) { return slide_ratio(a("alpha"), a("phi_w")); }},
  };
}

/// The solvers of Kiyama's contact stiffness, the lattice beam and the silo (refs §4, §5, §6).
std::vector<Entry> silo_and_beam_entries() {
  return {
    {{"kiyama.contact_stiffness",
      "K_n = q/delta of two equal cylinders (K22, K23, refs §5)",
      {{"E", "Pa", "Young's modulus"},
       {"nu", "1", "Poisson's ratio"},
       {"r", "m", "radius of both cylinders"},
       {"q", "N/m", "line load"},
       {"c", "1", "approach constant: 1.5 (K23) or 2/3 (K22.a)"}},
      "Pa"},
     [](const Args& a) {
       return contact_stiffness({.youngs_modulus = a("E"),
                                 .poisson_ratio = a("nu"),
                                 .radius1 = a("r"),
                                 .radius2 = a("r"),
                                 .line_load = a("q"),
                                 .approach_constant = a("c")});
     }},
    {{"beam.lattice_stiffness",
      "P/delta at mid-span of the square PRE lattice beam: Timoshenko with E = kn, G = ks/2, "
      "kappa = 5/6, I_eff (refs §4.3), on two support springs k_c",
      {argument::beam_width, argument::beam_depth, argument::beam_span,
       {"kn", "Pa", "face normal stiffness per unit strain"},
       {"ks", "Pa", "face shear stiffness per unit strain"}, argument::beam_rows,
       argument::beam_segments, argument::beam_face_ends, argument::support_stiffness},
      "N/m"},
     [](const Args& a) {
       const BeamSection s{a("b"), a("h"), a("L")};
       const auto where = a("ends") != 0.0 ? SegmentPositions::face_ends : SegmentPositions::centres;
       return stiffness_on_support_springs(
           lattice_beam_stiffness(s, a("kn"), a("ks"), a.count("n_h"), a.count("N"), where), a("k_c"));
     }},
    {{"beam.continuum_stiffness",
      "P/delta at mid-span of the continuum beam: Timoshenko with E, G = E/(2(1+nu)), kappa = 5/6 "
      "(refs §4.1), on two support springs k_c",
      {argument::beam_width, argument::beam_depth, argument::beam_span,
       {"E", "Pa", "Young's modulus"}, {"nu", "1", "Poisson's ratio"}, argument::support_stiffness},
      "N/m"},
     [](const Args& a) {
       const BeamSection s{a("b"), a("h"), a("L")};
       const double G = a("E") / (2.0 * (1.0 + a("nu")));
       return stiffness_on_support_springs(
           timoshenko_stiffness(s, a("E"), G, shear_coefficient_parabolic()), a("k_c"));
     }},
    {{"beam.peak_load",
      "P_max = 2 sigma_t b h^2 / (3 L) of a beam in three-point bending (refs §4.1)",
      {argument::beam_width, argument::beam_depth, argument::beam_span,
       {"sigma_t", "Pa", "flexural tensile strength"}},
      "N"},
     [](const Args& a) { return flexural_peak_load({a("b"), a("h"), a("L")}, a("sigma_t")); }},
    {{"beam.first_crack_ratio",
      "first-crack load of the lattice over P_max: 1 + 1/(n_h N) at segment centres, 1 + 2/n_h^2 "
      "at face ends (refs §4.4; an estimate)",
      {argument::beam_rows, argument::beam_segments, argument::beam_face_ends},
      "1"},
     [](const Args& a) {
       const auto where = a("ends") != 0.0 ? SegmentPositions::face_ends : SegmentPositions::centres;
       return lattice_first_crack_ratio(a.count("n_h"), a.count("N"), where);
     }},
    {{"beam.groove_first_crack_load",
      "first-crack load of the lattice with the load disk (radius R) wedged between the two top "
      "cores: beam theory with the wedge's thrust (ref/beam.hpp; refs §4.4 plus statics)",
      {argument::beam_width, argument::beam_depth, argument::beam_span,
       {"sigma_t", "Pa", "tensile strength of the face springs"}, argument::beam_rows,
       argument::beam_segments, argument::beam_face_ends, {"R", "m", "load disk radius"}},
      "N"},
     [](const Args& a) {
       const auto where = a("ends") != 0.0 ? SegmentPositions::face_ends : SegmentPositions::centres;
       return groove_first_crack_load({a("b"), a("h"), a("L")}, a("sigma_t"), a.count("n_h"), a.count("N"),
                                      where, a("R"));
     }},
    {{"silo.janssen_wall_force",
      "horizontal force per unit thickness on a side-wall band z1 <= z <= z2 below the free surface of a "
      "plane silo of width B, Janssen with lateral ratio K and wall friction mu_w (refs §6.1)",
      {{"z1", "m", "upper depth"}, {"z2", "m", "lower depth"}, {"rho_b", "kg/m^3", "bulk density"},
       {"g", "m/s^2", "gravity"}, {"B", "m", "silo width"}, {"K", "1", "lateral ratio"},
       {"mu_w", "1", "wall friction coefficient"}},
      "N/m"},
     [](const Args& a) { return janssen_wall_force(a("z1"), a("z2"), a("rho_b"), a("g"), a("B"), a("K"), a("mu_w")); }},
    {{"silo.k_geom",
      "K_geom = (d_x/2)^2/d_y^2 of the (s-1)/s packing of disks of radius r in a box of width B (refs §6.1)",
      {{"s", "1", "disks in a full row"}, {"B", "m", "silo width"}, {"r", "m", "disk radius"}},
      "1"},
     [](const Args& a) { return ordered_packing(a.count("s"), a("B"), a("r")).k_geom; }},
    {{"silo.beverloo_2d",
      "2D Beverloo mass flow rate per unit thickness W = C rho_b sqrt(g) (D - k d)^(3/2) (refs §6.2)",
      {{"C", "1", "discharge coefficient"}, {"rho_b", "kg/m^3", "bulk density"}, {"g", "m/s^2", "gravity"},
       {"D", "m", "slot width"}, {"k", "1", "empty-annulus factor"}, {"d", "m", "grain diameter"}},
      "kg/(m s)"},
     [](const Args& a) { return beverloo_2d(a("C"), a("rho_b"), a("g"), a("D"), a("k"), a("d")); }},
  };
}

/// The ordered fill of the arguments s, B, r and count (ref/silo_fill.hpp).
OrderedFill fill_of(const Args& a) { return ordered_fill(a.count("s"), a("B"), a("r"), a.count("count")); }

/// Kiyama's ordered fills as built and Janssen per wall contact (refs §6.1, ref/silo_fill.hpp).
std::vector<Entry> silo_fill_entries() {
  const SolverArgument s{"s", "1", "disks in a full row"}, width{"B", "m", "silo width"}, radius{"r", "m", "disk radius"},
      count{"count", "1", "target disk count (the row count whose count is nearest)"},
      rho{"rho", "kg/m^3", "solid density of the disks"}, g{"g", "m/s^2", "gravity"}, mu_w{"mu_w", "1", "wall friction coefficient"};
  return {
    {{"silo.fill_height", "2r + (rows - 1) d_y of the (s-1)/s fill nearest `count` disks, no gaps (refs §6.1)",
      {s, width, radius, count}, "m"},
     [](const Args& a) { return ordered_fill(a.count("s"), a("B"), a("r"), a.count("count")).height; }},
    {{"silo.area_fraction", "phi_A = (2s - 1) pi r^2 / (2 B d_y) of the (s-1)/s packing (refs §6.1)", {s, width, radius}, "1"},
     [](const Args& a) { return ordered_packing(a.count("s"), a("B"), a("r")).area_fraction; }},
    {{"silo.fill_weight", "weight per unit thickness n rho pi r^2 g of the (s-1)/s fill nearest `count` disks",
      {s, width, radius, count, rho, g}, "N/m"},
     [](const Args& a) {
       const OrderedFill f = fill_of(a);
       return static_cast<double>(f.count) * a("rho") * std::numbers::pi * a("r") * a("r") * a("g");
     }},
    {{"silo.janssen_contact_force",
      "Janssen sigma_h(z) x 2 d_y x 1 m: the force on one wall contact at depth z below the top of the (s-1)/s fill, "
      "K = K_geom, rho_b = rho phi_A, full wall friction (refs §6.1)",
      {{"z", "m", "depth below the fill top"}, s, width, radius, count, rho, g, mu_w}, "N/m"},
     [](const Args& a) { return janssen_contact_force(a("z"), fill_of(a), a("rho"), a("g"), a("mu_w")); }},
    {{"silo.janssen_wall_contact",
      "Janssen's wall force on the band carried by the k-th wall contact from the bottom (y_k +- d_y, cut at "
      "floor and top) of the (s-1)/s fill, K = K_geom, rho_b = rho phi_A (refs §6.1)",
      {{"k", "1", "wall contact from the bottom, 0 = the bottom row"}, s, width, radius, count, rho, g, mu_w}, "N/m"},
     [](const Args& a) {
       const double k = a("k");
       if (!(k >= 0.0 && k == std::floor(k) && k < 1e6)) detail::fail("ref::evaluate", "k must be a whole number >= 0", k);
       return janssen_wall_contact(static_cast<int>(k), fill_of(a), a("rho"), a("g"), a("mu_w"));
     }},
  };
}

/// The solvers of the PRE-face base-friction model and the exact linear lattice beam (refs §3, §4).
std::vector<Entry> exact_entries() {
  return {
    {{"base_friction.pre_face_rate",
      "quasi-static dtheta/ddelta_B of a rigid n_w x n_h PRE block whose pivot element touches the "
      "slope by face-end springs fixed in the wall frame (M2, M12, M13.2, M15.2, M19, M21; "
      "ref/base_friction_pre_face.hpp)",
      {argument::rotation, argument::slope, argument::block_width, argument::block_height,
       argument::elements_w, argument::elements_h},
      "rad/m"},
     [](const Args& a) {
       return pre_face_rate(a("theta"), a("alpha"), a("W"), a("H"), a.count("n_w"), a.count("n_h"));
     }},
    {{"base_friction.theta_pre_face",
      "rotation at plate travel delta_B under the PRE model's own quasi-static rate "
      "(pre_face_rate; Odeint dopri5)",
      {argument::slope, argument::plate_travel, argument::block_width, argument::block_height,
       argument::elements_w, argument::elements_h},
      "rad"},
     [](const Args& a) {
       return theta_at_travel_pre_face(a("delta_B"), a("alpha"), a("W"), a("H"), a.count("n_w"),
                                       a.count("n_h"));
     }},
    {{"base_friction.theta_pre_face_exact",
      "rotation at plate travel delta_B of the rigid PRE block whose pivot spring uses the exact "
      "tangential increment (M3.2: the real corner does not drift), levers in the wall frame (M12, M19)",
      {argument::slope, argument::plate_travel, argument::block_width, argument::block_height,
       argument::elements_w, argument::elements_h},
      "rad"},
     [](const Args& a) {
       return theta_at_travel_pre_face(a("delta_B"), a("alpha"), a("W"), a("H"), a.count("n_w"),
                                       a.count("n_h"), WallTangentialLaw::exact);
     }},
    {{"base_friction.onset_theta_m21",
      "rotation at which the pivot of a rigid n_w x n_h block turning about its real corner under M21 "
      "needs the slope's friction tan phi_w (refs §3.6, §3.8; ref/base_friction_onset.hpp)",
      onset_arguments(), "rad"},
     [](const Args& a) { return onset_rotation(a("alpha"), a("phi_w"), a("W"), a("H"), a.count("n_w"), a.count("n_h"), rigid_m21_pivot); }},
    {{"base_friction.onset_travel_m21",
      "plate travel at base_friction.onset_theta_m21 under the M21 rate (refs §3.8)",
      onset_arguments(), "m"},
     [](const Args& a) { return onset_travel(a("alpha"), a("phi_w"), a("W"), a("H"), a.count("n_w"), a.count("n_h"), rigid_m21_pivot); }},
    {{"base_friction.onset_theta_pre_face",
      "the same onset for the PRE model's own rigid block (pivot spring in the wall frame, M15.2 rolling; "
      "pre_face_rate)",
      onset_arguments(), "rad"},
     [](const Args& a) { return onset_rotation(a("alpha"), a("phi_w"), a("W"), a("H"), a.count("n_w"), a.count("n_h"), pre_face_pivot); }},
    {{"base_friction.onset_travel_pre_face",
      "plate travel at base_friction.onset_theta_pre_face under the PRE model's rate",
      onset_arguments(), "m"},
     [](const Args& a) { return onset_travel(a("alpha"), a("phi_w"), a("W"), a("H"), a.count("n_w"), a.count("n_h"), pre_face_pivot); }},
    {{"beam.lattice_exact_stiffness",
      "P/delta at mid-span (bottom point left of x = 0) of the bonded square PRE lattice on disk supports "
      "under a load disk: the assembled linear stiffness matrix of the rigid elements, face springs "
      "M6/M13/M15, disk contacts k_c, k_t (ref/lattice_beam.hpp)",
      lattice_beam_arguments(false), "N/m"},
     [](const Args& a) { return solve_lattice_beam(lattice_beam_model(a)).stiffness; }},
    {{"beam.lattice_exact_first_crack_load",
      "load at which the most stretched face spring of the linear lattice beam reaches sigma_t A/N (M8), "
      "same model as beam.lattice_exact_stiffness",
      lattice_beam_arguments(true), "N"},
     [](const Args& a) { return solve_lattice_beam(lattice_beam_model(a), a("sigma_t")).first_crack_load; }},
  };
}

/// The arguments of the disk-on-slope solvers (ref/disk_on_slope.hpp).
std::vector<SolverArgument> slope_arguments() {
  return {argument::mass, {"kn", "N/m", "normal stiffness K_n of the wall contact"}, {"s", "1", "K_s/K_n"}, argument::zeta,
          argument::slope, {"phi", "rad", "friction angle, mu = tan phi"}, argument::gravity, argument::time};
}

DiskOnSlope disk_of(const Args& a) {
  return {.m = a("m"), .kn = a("kn"), .s = a("s"), .zeta = a("zeta"), .alpha = a("alpha"), .phi = a("phi"), .g = a("g")};
}

/// A disk released on a slope (ref/disk_on_slope.hpp) and its resting overlap on Kiyama's K_n (K22, K23).
std::vector<Entry> disk_slope_entries() {
  const SolverArgument E{"E", "Pa", "Young's modulus"}, nu{"nu", "1", "Poisson's ratio"}, r{"r", "m", "radius in K22.b, K23"},
      q{"q", "N/m", "line load"}, c{"c", "1", "approach constant of K23"},
      factor{"factor", "1", "K_n of the contact over K23's (2 for Kiyama's walls)"},
      g_n{"g", "m/s^2", "gravity across the wall"};
  return {
    {{"disk_slope.position", "x(t) of a disk released on slope alpha: sticking on (K_s, eta_s), then Coulomb sliding (ref/disk_on_slope.hpp)",
      slope_arguments(), "m"},
     [](const Args& a) { return disk_on_slope(disk_of(a), a("t")).x; }},
    {{"disk_slope.velocity", "v(t) of the same disk", slope_arguments(), "m/s"},
     [](const Args& a) { return disk_on_slope(disk_of(a), a("t")).v; }},
    {{"disk_slope.spin_speed", "r omega(t) of the same disk", slope_arguments(), "m/s"},
     [](const Args& a) { return disk_on_slope(disk_of(a), a("t")).spin_speed; }},
    {{"kiyama.rest_overlap", "m g / (factor K_n) with K_n = q/delta of two equal cylinders (K22, K23), per unit thickness",
      {argument::mass, g_n, E, nu, r, q, c, factor}, "m"},
     [](const Args& a) {
       detail::require_positive("kiyama.rest_overlap", "factor", a("factor"));
       const double k = contact_stiffness({.youngs_modulus = a("E"), .poisson_ratio = a("nu"), .radius1 = a("r"),
                                           .radius2 = a("r"), .line_load = a("q"), .approach_constant = a("c")});
       return resting_overlap(a("m"), a("g"), a("factor") * k);
     }},
  };
}

/// The arguments of the rolling-disk solver (ref/rolling_disk.hpp).
std::vector<SolverArgument> rolling_arguments() {
  return {argument::mass, {"r", "m", "disk radius"}, argument::gravity, {"alpha", "rad", "slope angle, 0 for a flat wall"},
          {"ks", "N/m", "shear spring K_s"}, {"eta_s", "N s/m", "shear dashpot eta_s"}, {"mu", "1", "Coulomb friction mu"},
          {"kr", "N m/rad", "rolling spring k_r"}, {"cr", "N m s/rad", "rolling dashpot C_r"},
          {"mu_r", "1", "rolling friction mu_r"}, {"v0", "m/s", "initial velocity down the slope, rolling without slip"},
          argument::time};
}

RollingDisk rolling_disk_of(const Args& a) {
  return {.m = a("m"), .r = a("r"), .g = a("g"), .alpha = a("alpha"), .ks = a("ks"), .eta_s = a("eta_s"), .mu = a("mu"),
          .kr = a("kr"), .cr = a("cr"), .mu_r = a("mu_r"), .v0 = a("v0")};
}

/// A disk with rolling resistance on a wall: the elastic–plastic model in continuous time and the rigid
/// limit's closed forms (ref/rolling_disk.hpp).
std::vector<Entry> rolling_entries() {
  const SolverArgument v0{"v0", "m/s", "initial rolling velocity"}, mu_r{"mu_r", "1", "rolling friction mu_r"};
  return {
    {{"rolling.position", "x(t) of a disk on a wall with an elastic-plastic rolling spring and dashpot (type C) and a "
                          "Coulomb shear spring, continuous time by Boost.Odeint (ref/rolling_disk.hpp)",
      rolling_arguments(), "m"},
     [](const Args& a) { return rolling_disk(rolling_disk_of(a), a("t")).x; }},
    {{"rolling.velocity", "v(t) of the same disk", rolling_arguments(), "m/s"},
     [](const Args& a) { return rolling_disk(rolling_disk_of(a), a("t")).v; }},
    {{"rolling.omega", "omega(t) of the same disk (counter-clockwise positive)", rolling_arguments(), "rad/s"},
     [](const Args& a) { return rolling_disk(rolling_disk_of(a), a("t")).omega; }},
    {{"rolling.moment", "the rolling moment M(t) on the same disk", rolling_arguments(), "N*m"},
     [](const Args& a) { return rolling_disk(rolling_disk_of(a), a("t")).moment; }},
    {{"rolling.spring_moment", "min(k_r theta, mu_r r e_n): a disk's rolling spring turned by theta about its contact point "
                               "on a wall, e_n = k_n (delta + (r - delta)(1 - cos theta))",
      {{"kr", "N m/rad", "rolling spring k_r"}, {"kn", "N/m", "normal spring K_n"}, mu_r, {"r", "m", "disk radius"},
       {"delta", "m", "approach before the turn"}, {"theta", "rad", "rotation about the contact point, >= 0"}},
      "N m"},
     [](const Args& a) { return rolling_spring_moment(a("kr"), a("kn"), a("mu_r"), a("r"), a("delta"), a("theta")); }},
    {{"rolling.pair_spring_moment", "min(k_r theta, mu_r R_r e_n): disk j of a pair turned by theta about the middle of "
                                    "the overlap, R_r = r_i r_j/(r_i + r_j), e_n = k_n times the overlap of the turned pair",
      {{"kr", "N m/rad", "rolling spring k_r"}, {"kn", "N/m", "normal spring K_n"}, mu_r, {"r_i", "m", "radius of disk i"},
       {"r_j", "m", "radius of the turned disk j"}, {"delta", "m", "approach before the turn"},
       {"theta", "rad", "rotation of j, >= 0"}},
      "N m"},
     [](const Args& a) {
       return rolling_pair_spring_moment(a("kr"), a("kn"), a("mu_r"), a("r_i"), a("r_j"), a("delta"), a("theta"));
     }},
    {{"rolling.rigid_stop_distance", "3 v0^2/(4 mu_r g): a rigid disk rolling to rest on a flat wall", {v0, mu_r, argument::gravity}, "m"},
     [](const Args& a) { return rolling_stop_distance(a("v0"), a("mu_r"), a("g")); }},
    {{"rolling.rigid_stop_time", "3 v0/(2 mu_r g): the time a rigid disk takes to roll to rest on a flat wall",
      {v0, mu_r, argument::gravity}, "s"},
     [](const Args& a) { return rolling_stop_time(a("v0"), a("mu_r"), a("g")); }},
    {{"rolling.rigid_velocity", "max(0, v0 + (2/3) g (sin alpha - mu_r cos alpha) t): a rigid disk rolling down a slope alpha >= 0 from v0 >= 0",
      {v0, {"alpha", "rad", "slope angle"}, mu_r, argument::gravity, argument::time}, "m/s"},
     [](const Args& a) { return rolling_rigid_velocity(a("v0"), a("alpha"), a("mu_r"), a("g"), a("t")); }},
    {{"rolling.mode", "the rigid limit's initial motion from rest on slope alpha: 0 stays, 1 slides, 2 rolls, 3 rolls and slides "
                      "(the block codes of incline.mode; a uniform disk; refs §7.4)",
      {argument::slope, argument::friction, mu_r}, "1"},
     [](const Args& a) { return static_cast<double>(rolling_disk_mode(a("alpha"), std::tan(a("phi")), a("mu_r"))); }},
    {{"rolling.rigid_slope_acceleration", "(2/3) g (sin alpha - mu_r cos alpha), 0 if tan alpha <= mu_r: a rigid disk on a slope",
      {{"alpha", "rad", "slope angle"}, mu_r, argument::gravity}, "m/s^2"},
     [](const Args& a) { return rolling_slope_acceleration(a("alpha"), a("mu_r"), a("g")); }},
  };
}

ObliqueRebound impact_of(const Args& a) {
  return oblique_impact({.m = a("m"), .r = a("r"), .kn = a("kn"), .eta_n = a("eta_n"), .ks = a("ks"), .eta_s = a("eta_s"),
                         .mu = a("mu"), .v = a("v"), .theta = a("theta"), .omega0 = a("omega0")});
}

/// Oblique impact of a disk on a wall (Chung & Ooi's tests 4–6 in 2D; ref/oblique_impact.hpp).
std::vector<Entry> oblique_entries() {
  const std::vector<SolverArgument> args = {
      argument::mass, {"r", "m", "disk radius"}, {"kn", "N/m", "normal spring K_n"}, {"eta_n", "N s/m", "normal dashpot eta_n"},
      {"ks", "N/m", "shear spring K_s"}, {"eta_s", "N s/m", "shear dashpot eta_s"}, {"mu", "1", "Coulomb friction mu"},
      {"v", "m/s", "impact speed"}, {"theta", "rad", "incidence from the wall's normal, in [0, pi/2)"},
      {"omega0", "rad/s", "initial spin, counter-clockwise positive"}};
  return {
    {{"oblique.vt_after", "velocity along the wall after an oblique impact of a uniform disk (linear contact with a capped "
                          "shear spring, continuous time, RK4; refs §1.8)", args, "m/s"},
     [](const Args& a) { return impact_of(a).vt; }},
    {{"oblique.omega_after", "spin after the same impact (counter-clockwise positive)", args, "rad/s"},
     [](const Args& a) { return impact_of(a).omega; }},
    {{"oblique.vn_after", "normal velocity away from the wall after the same impact", args, "m/s"},
     [](const Args& a) { return impact_of(a).vn; }},
  };
}

/// A gap spring stretched at constant speed (ref/gap_spring.hpp).
std::vector<Entry> gap_entries() {
  const SolverArgument k{"k", "N/m", "the bond's spring (normal or shear)"}, eta{"eta", "N s/m", "its dashpot"},
      v{"v", "m/s", "the constant stretch rate"}, strength{"strength", "N", "the elastic force at which it breaks"};
  return {
    {{"gap.pull_force", "k v t + eta v while k v t <= strength, else 0: a bond stretched at constant speed (refs §8)",
      {k, eta, v, argument::time, strength}, "N"},
     [](const Args& a) { return gap_pull_force(a("k"), a("eta"), a("v"), a("t"), a("strength")); }},
    {{"gap.break_time", "strength/(k v): when that bond breaks", {k, v, strength}, "s"},
     [](const Args& a) { return gap_break_time(a("k"), a("v"), a("strength")); }},
  };
}

/// Every solver, in a fixed order (the groups above, one after the other).
const std::vector<Entry>& table() {
  static const std::vector<Entry> entries = [] {
    std::vector<Entry> all;
    for (auto make : {contact_entries, block_entries, silo_and_beam_entries, silo_fill_entries, exact_entries, disk_slope_entries,
                      rolling_entries, oblique_entries, gap_entries}) {
      std::vector<Entry> group = make();
      all.insert(all.end(), std::make_move_iterator(group.begin()), std::make_move_iterator(group.end()));
    }
    return all;
  }();
  return entries;
}

std::string argument_list(const SolverInfo& info) {
  std::string list;
  for (const auto& argument : info.arguments) {
    if (!list.empty()) list += ", ";
    list += argument.name + " [" + argument.unit + "]";
  }
  return "(" + list + ")";
}

}  // namespace

double evaluate(std::string_view name, const std::map<std::string, double>& args) {
  const auto& entries = table();
  const Entry* entry = nullptr;
  for (const auto& candidate : entries)
    if (candidate.info.name == name) entry = &candidate;
  if (entry == nullptr) {
    std::string known;
    for (const auto& candidate : entries)
      known += (known.empty() ? "" : ", ") + candidate.info.name;
    throw std::invalid_argument("ref::evaluate: unknown solver '" + std::string(name) +
                                "'; known solvers: " + known);
  }
  const std::string prefix = "ref::evaluate(\"" + std::string(name) + "\"): ";
  const std::string expected = "; expected " + argument_list(entry->info);
  for (const auto& argument : entry->info.arguments)
    if (!args.contains(argument.name))
      throw std::invalid_argument(prefix + "missing argument '" + argument.name + "' [" +
                                  argument.unit + "]" + expected);
  for (const auto& [key, value] : args) {
    bool known = false;
    for (const auto& argument : entry->info.arguments) known = known || argument.name == key;
    if (!known) throw std::invalid_argument(prefix + "unknown argument '" + key + "'" + expected);
  }
  try {
    return entry->function(Args{args});
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(prefix + error.what());
  }
}

std::vector<SolverInfo> solvers() {
  std::vector<SolverInfo> infos;
  for (const auto& entry : table()) infos.push_back(entry.info);
  return infos;
}

}  // namespace ref
