// Name-based table of the reference solvers (see ref/registry.hpp).
#include "ref/registry.hpp"

#include <stdexcept>

#include "ref/block_on_incline.hpp"
#include "ref/elastic_contact_2d.hpp"
#include "ref/free_fall.hpp"
#include "ref/impact.hpp"
#include "ref/oscillator.hpp"
#include "ref/require.hpp"
#include "ref/resting_overlap.hpp"
#include "ref/spring_layer.hpp"
#include "ref/stability.hpp"

namespace ref {

namespace {

// Read access to validated arguments.
struct Args {
  const std::map<std::string, double>& values;
  double operator()(const std::string& name) const { return values.at(name); }
  Oscillator oscillator() const { return Oscillator((*this)("m"), (*this)("K"), (*this)("eta")); }
};

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

}  // namespace argument

const std::vector<Entry>& table() {
  static const std::vector<Entry> entries{
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
      {{"kiyama.contact_stiffness",
        "K_n = q/delta of two equal cylinders (K22, K23, refs §5)",
        {{"E", "Pa", "Young's modulus"},
         {"nu", "1", "Poisson's ratio"},
         {"r", "m", "radius of both cylinders"},
         {"q", "N/m", "line load"},
         {"c", "1", "approach constant: 1.5 (K23) or 2/3 (K22a)"}},
        "Pa"},
       [](const Args& a) {
         return contact_stiffness({.youngs_modulus = a("E"),
                                   .poisson_ratio = a("nu"),
                                   .radius1 = a("r"),
                                   .radius2 = a("r"),
                                   .line_load = a("q"),
                                   .approach_constant = a("c")});
       }},
  };
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
