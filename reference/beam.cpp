// Elastic beam theory for three-point bending and the square PRE lattice's effective beam (see
// ref/beam.hpp for the derivations).
#include "ref/beam.hpp"

#include <cmath>
#include <stdexcept>

#include "ref/require.hpp"

namespace ref {

namespace {

void require_section(const char* where, const BeamSection& s) {
  detail::require_positive(where, "width", s.width);
  detail::require_positive(where, "depth", s.depth);
  detail::require_positive(where, "span", s.span);
}

void require_lattice(const char* where, int rows, int segments, SegmentPositions positions) {
  if (rows < 1) detail::fail(where, "rows must be >= 1", rows);
  if (segments < 1) detail::fail(where, "segments must be >= 1", segments);
  if (positions == SegmentPositions::face_ends && segments != 2)
    detail::fail(where, "face-end positions (M13.2) have exactly 2 segments", segments);
}

}  // namespace

double second_moment(const BeamSection& s) {
  require_section("ref::second_moment", s);
  return s.width * s.depth * s.depth * s.depth / 12.0;
}

double euler_bernoulli_stiffness(const BeamSection& s, double young) {
  detail::require_positive("ref::euler_bernoulli_stiffness", "young", young);
  return 48.0 * young * second_moment(s) / (s.span * s.span * s.span);
}

double shear_coefficient_parabolic() { return 5.0 / 6.0; }

double shear_coefficient_cowper(double poisson) {
  if (!(poisson > -1.0 && poisson < 0.5)) detail::fail("ref::shear_coefficient_cowper", "poisson must be in (-1, 0.5)", poisson);
  return 10.0 * (1.0 + poisson) / (12.0 + 11.0 * poisson);
}

double timoshenko_stiffness(const BeamSection& s, double young, double shear_modulus, double kappa,
                            double bending_moment_factor) {
  constexpr const char* where = "ref::timoshenko_stiffness";
  detail::require_positive(where, "young", young);
  detail::require_positive(where, "shear_modulus", shear_modulus);
  detail::require_positive(where, "kappa", kappa);
  detail::require_positive(where, "bending_moment_factor", bending_moment_factor);
  const double inertia = second_moment(s) * bending_moment_factor;
  const double area = s.width * s.depth;
  const double bending = s.span * s.span * s.span / (48.0 * young * inertia);  // δ_b / P
  const double shear = s.span / (4.0 * kappa * shear_modulus * area);          // δ_s / P
  return 1.0 / (bending + shear);
}

double flexural_peak_load(const BeamSection& s, double tensile_strength) {
  require_section("ref::flexural_peak_load", s);
  detail::require_positive("ref::flexural_peak_load", "tensile_strength", tensile_strength);
  return 2.0 * tensile_strength * s.width * s.depth * s.depth / (3.0 * s.span);
}

LatticeModuli square_lattice_moduli(double kn, double ks) {
  detail::require_positive("ref::square_lattice_moduli", "kn", kn);
  detail::require_positive("ref::square_lattice_moduli", "ks", ks);
  return {kn, ks / 2.0, 0.0};
}

double lattice_bending_factor(int rows, int segments, SegmentPositions where) {
  require_lattice("ref::lattice_bending_factor", rows, segments, where);
  const double n = rows;
  if (where == SegmentPositions::face_ends) return 1.0 + 2.0 / (n * n);
  const double nN = n * segments;
  return 1.0 - 1.0 / (nN * nN);
}

double lattice_first_crack_ratio(int rows, int segments, SegmentPositions where) {
  require_lattice("ref::lattice_first_crack_ratio", rows, segments, where);
  const double n = rows;
  if (where == SegmentPositions::face_ends) return 1.0 + 2.0 / (n * n);
  return 1.0 + 1.0 / (n * segments);
}

double stiffness_on_support_springs(double beam_stiffness, double support_stiffness) {
  detail::require_positive("ref::stiffness_on_support_springs", "beam_stiffness", beam_stiffness);
  detail::require_positive("ref::stiffness_on_support_springs", "support_stiffness",
                           support_stiffness);
  return 1.0 / (1.0 / beam_stiffness + 0.5 / support_stiffness);
}

double lattice_beam_stiffness(const BeamSection& s, double kn, double ks, int rows, int segments,
                              SegmentPositions where) {
  const LatticeModuli m = square_lattice_moduli(kn, ks);
  return timoshenko_stiffness(s, m.young, m.shear_modulus, shear_coefficient_parabolic(),
                              lattice_bending_factor(rows, segments, where));
}

double groove_first_crack_load(const BeamSection& s, double tensile_strength, int rows, int segments,
                               SegmentPositions where, double load_disk_radius) {
  constexpr const char* name = "ref::groove_first_crack_load";
  require_section(name, s);
  require_lattice(name, rows, segments, where);
  detail::require_positive(name, "tensile_strength", tensile_strength);
  detail::require_positive(name, "load_disk_radius", load_disk_radius);
  const double r = s.depth / (2.0 * rows);  // core radius
  const double sin_theta = r / (r + load_disk_radius);
  const double cos_theta = std::sqrt(1.0 - sin_theta * sin_theta);
  const double t = 0.5 * sin_theta / cos_theta;                       // H / P
  const double e = s.depth - r + r * cos_theta - 0.5 * s.depth;       // y_p − h/2
  const double inertia = second_moment(s) * lattice_bending_factor(rows, segments, where);
  const double y_max = where == SegmentPositions::face_ends
                           ? 0.5 * s.depth
                           : 0.5 * s.depth * (1.0 - 1.0 / (static_cast<double>(rows) * segments));
  const double area = s.width * s.depth;
  return tensile_strength / ((0.25 * s.span - t * e) * y_max / inertia + t / area);
}

}  // namespace ref
