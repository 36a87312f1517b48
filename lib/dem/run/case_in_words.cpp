#include "dem/run/case_in_words.hpp"

#include <cmath>

#include <fmt/format.h>

namespace dem {

std::string law_in_words(const nlohmann::json& l) {
  std::string s = fmt::format("{}–{}: {} law", l["between"][0].get<std::string>(), l["between"][1].get<std::string>(),
                              l["law"].get<std::string>());
  if (l["law"] == "linear") {
    s += fmt::format(", kn = {:.6g} N/m, ks = {:.6g} N/m, friction = {:.6g}, end rule {} ({}), onset {} ({})",
                     l["kn"].get<double>(), l["ks"].get<double>(), l["friction"].get<double>(), l["end_rule"].get<std::string>(),
                     l["end_rule"] == "elastic" ? "opens when e_n < 0, K8" : "no attractive total force",
                     l["onset"].get<std::string>(),
                     l["onset"] == "increment" ? "the first increment goes into e_n, Cundall" : "e_n from the overlap");
    if (l.contains("rolling")) {
      const auto& r = l["rolling"];
      s += fmt::format(", rolling resistance (R1-R6): moment capped at mu_r R_r e_n with mu_r = {:.6g}, ", r["friction"].get<double>());
      if (r.contains("stiffness")) s += fmt::format("k_r = {:.6g} N*m/rad", r["stiffness"].get<double>());
      else s += fmt::format("k_r = {:.6g} k_n mu_r^2 R_r^2 (R2)", r["stiffness_factor"].get<double>());
      s += fmt::format(", rolling damping ratio {:.6g} (C_r = 2 zeta_r sqrt(I_r k_r), R5; none at the cap)", r["damping_ratio"].get<double>());
    }
    if (l.contains("gap")) {
      const auto& g = l["gap"];
      auto limit = [&](const char* key, const char* unit) {
        return g.contains(key) ? fmt::format("{:.6g} {}", g[key].get<double>(), unit) : std::string("none");
      };
      s += fmt::format(", gap springs (B1-B5) bonding the disks at most {:.6g} m apart at the start: kn = {:.6g} N/m, ks = {:.6g} N/m "
                       "in tension and compression, damping ratio {:.6g}, breaking at a tension of {}, a shear of {}, a gap of {}",
                       g["distance"].get<double>(), g["kn"].get<double>(), g["ks"].get<double>(), g["damping_ratio"].get<double>(),
                       limit("tensile_strength", "N"), limit("shear_strength", "N"), limit("break_distance", "m"));
    }
  } else {
    s += fmt::format(", {} segment(s) at the {} ({}), normal increment {}, tangential increment {}, onset {}",
                     l["segments"].get<int>(), l["positions"] == "centres" ? "segment centres" : "face ends",
                     l["positions"] == "centres" ? "M13.1" : "M13.2", l["normal_increment"].get<std::string>(),
                     l["tangential_increment"].get<std::string>(), l["onset"].get<std::string>());
    if (l.contains("kn")) s += fmt::format(", kn = {:.6g} N/m per segment, ks = {:.6g} N/m", l["kn"].get<double>(), l["ks"].get<double>());
    else s += fmt::format(", kn = {:.6g} Pa, ks = {:.6g} Pa (moduli)", l["kn_modulus"].get<double>(), l["ks_modulus"].get<double>());
    s += fmt::format(", tan phi = {:.6g}, tensile strength {:.6g} Pa, cohesion {:.6g} Pa{}{}", l["friction"].get<double>(),
                     l["tensile_strength"].get<double>(), l["cohesion"].get<double>(), l["bonded"].get<bool>() ? ", bonded at the start" : "",
                     l["healing"].get<bool>() ? ", healing" : "");
    if (l.value("lever", "wall_frame") == "rotated_corner") s += ", at a wall the forces act at the rotated corner (M19.r)";
  }
  if (l.contains("damping_ratio"))
    s += fmt::format(", damping ratio {:.6g} ({} mass)", l["damping_ratio"].get<double>(), l["mass_basis"].get<std::string>());
  else
    s += fmt::format(", dashpots eta_n = {:.6g}, eta_s = {:.6g} N*s/m", l["eta_n"].get<double>(), l["eta_s"].get<double>());
  return s;
}

std::string limit_in_words(const Model& m, const StabilityBound& b, double limit) {
  if (!std::isfinite(limit)) return "no contact can form: no limit from contacts";
  const auto i = static_cast<std::size_t>(b.element);
  const Elements& e = m.elements;
  std::string s = fmt::format(
      "the fastest mode of element {} (a {} of radius {:.4g} m, mass {:.4g} kg, material {}) pressed by {} element "
      "and {} wall contact(s) through {} at once, in the worst arrangement of their directions: "
      "stiffness rate lambda = {:.4g} 1/s^2 (omega = {:.4g} rad/s), damping rate c = {:.4g} 1/s; ",
      b.element, e.shape[i] == Shape::disk ? "disk" : e.shape[i] == Shape::pre ? "PRE" : "polygon (circumradius)", e.radius[i], e.mass[i],
      m.materials[static_cast<std::size_t>(e.material[i])].name, b.element_contacts, b.wall_contacts,
      b.law.empty() ? std::string("no contact") : b.law, b.stiffness_rate, std::sqrt(b.stiffness_rate), b.damping_rate);
  const double lam = b.stiffness_rate, c = b.damping_rate;
  if (m.numerics.integrator == Integrator::k18) {
    s += "K18 (symplectic Euler) loses stability when that mode flips sign every step: dt < 4/(sqrt(c^2 + 4 lambda) + c)";
  } else {
    const double flip = 12.0 / (std::sqrt(c * c + 12.0 * lam) + c);
    if (limit < flip * (1.0 - 1e-9))
      s += fmt::format("K19 (averaged increment) is limited by its Hopf branch, dt < eta/K = {:.6g} s: the averaging needs "
                       "damping (the flip branch alone would allow {:.6g} s)", limit, flip);
    else
      s += "K19 (averaged increment) loses stability on its flip branch: dt < 12/(sqrt(c^2 + 12 lambda) + c)";
  }
  return s + " (the shear springs of linear, Coulomb contacts are left out of this limit: a sliding contact bounds a "
             "shear mode)";
}

}  // namespace dem
