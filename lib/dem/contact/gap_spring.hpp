#pragma once
// Gap springs: the bonds of Iwashita (1988) and Meguro & Hakuno (1989) between disks in contact or slightly
// apart at the start, in parallel with the contact law (docs/model.md §6, B1–B5). A value type holding the
// parameters, the per-bond history, and one pure function that advances a bond by one step.
#include <cmath>
#include <cstdint>
#include <limits>

namespace dem {

/// The gap-spring option of a linear contact law (`gap = { … }` in a case's [[contact]]).
struct GapSpringLaw {
  bool enabled = false;
  double distance = 0.0;  // pairs whose surface gap is at most this at the start are bonded (B1) [m]
  double kn = 0.0;        // normal spring, in tension and compression [N/m] (B2)
  double ks = 0.0;        // shear spring [N/m] (B2)
  double damping_ratio = 0.0;  // ζ of the dashpots η = 2ζ√(m_eff k), normal and shear (B3)
  double tensile_strength = std::numeric_limits<double>::infinity();  // T: breaks when the tension exceeds it [N] (B4.a)
  double shear_strength = std::numeric_limits<double>::infinity();    // S: breaks when |shear| exceeds it [N] (B4.b)
  double break_gap = std::numeric_limits<double>::infinity();  // breaks when the surface gap exceeds it [m] (B4.c)
};

/// One bond between elements i < j, formed at the start; `intact` false once it broke (it never forms again).
struct GapSpring {
  std::uint32_t i = 0, j = 0;
  std::int32_t law = -1;       // index into Model::laws
  double eta_n = 0.0, eta_s = 0.0;  // dashpots of this pair [N·s/m] (B3)
  double en = 0.0, es = 0.0;   // elastic normal (compression positive, tension negative) and shear force [N] (B2)
  double fn = 0.0, fs = 0.0;   // the forces of the last step (outputs) [N]
  bool intact = true;
};

struct GapSpringForce {
  double fn = 0.0, fs = 0.0;  // compression positive [N]
  bool broke = false;         // (B4): it broke in this step and carries nothing from now on
};

/// One step of a bond. du_n, du_s: the relative displacement increments of the step (K5, approach positive);
/// gap: the surface gap after the step (centre distance less the radii) [m]; inv_dt = 1/Δt.
inline GapSpringForce gap_spring_force(const GapSpringLaw& law, double du_n, double du_s, double gap, double inv_dt,
                                       GapSpring& b) {
  b.en += law.kn * du_n;  // (B2.a): tension (en < 0) as well as compression
  b.es += law.ks * du_s;  // (B2.b)
  if (-b.en > law.tensile_strength || std::abs(b.es) > law.shear_strength || gap > law.break_gap) {  // (B4)
    b.en = b.es = 0.0;
    b.intact = false;
    return {0.0, 0.0, true};
  }
  return {b.en + b.eta_n * du_n * inv_dt, b.es + b.eta_s * du_s * inv_dt, false};  // (B3, B5)
}

}  // namespace dem
