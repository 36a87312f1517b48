#pragma once
// Cundall's linear spring–dashpot contact with no tension and a Coulomb slider, as used by
// Kiyama & Fujimura (docs/model.md §1, K6–K14). A value type holding the parameters and one pure function
// that advances a contact's history by one step.
#include <cmath>
#include <cstdint>

namespace dem {

/// When a no-tension contact stops carrying force (docs/references.md §1.2).
enum class EndRule : std::uint8_t {
  elastic,  // convention A, Kiyama's K8: the contact opens when the elastic force e_n < 0
  total     // convention B: no attractive total force, f_n = max(e_n + d_n, 0)
};

/// How a contact that forms during a run starts its elastic force.
enum class Onset : std::uint8_t {
  increment,  // Cundall: the whole first increment (including the approach inside the gap) goes into e_n
  overlap     // e_n starts from K_n times the geometric overlap at the first step of contact
};

struct LinearContactHistory {
  double en = 0.0;  // accumulated elastic normal force e_n [N], compression positive (K7.a)
  double es = 0.0;  // accumulated elastic shear force e_s [N] (K11.a)
};

struct LinearSpringDashpot {
  double kn = 0.0;   // normal spring [N/m]
  double ks = 0.0;   // shear spring [N/m]
  double mu = 0.0;   // Coulomb friction coefficient tan(phi)
  EndRule end_rule = EndRule::elastic;
};

struct ContactForce {
  double fn = 0.0;      // normal force, compression positive [N]
  double fs = 0.0;      // shear force [N]
  bool opened = false;  // K8: the contact opened (ended) in this step
};

/// One step of the contact law. du_n, du_s: relative displacement increments of the step (K5),
/// approach positive; eta_n, eta_s: dashpots [N·s/m]; inv_dt = 1/Δt.
inline ContactForce linear_contact_force(const LinearSpringDashpot& law, double eta_n, double eta_s,
                                         double du_n, double du_s, double inv_dt,
                                         LinearContactHistory& h) {
  h.en += law.kn * du_n;               // (K6.a, K7.a)
  h.es += law.ks * du_s;               // (K10.a, K11.a)
  const double dn = eta_n * du_n * inv_dt;  // (K6.b, K7.b)
  double ds = eta_s * du_s * inv_dt;        // (K10.b, K11.b)
  if (h.en < 0.0) {                    // (K8, K12): no tension, the contact opens
    h.en = 0.0;
    h.es = 0.0;
    return {0.0, 0.0, true};
  }
  const double limit = law.mu * h.en;  // (K13): Coulomb slider
  if (std::abs(h.es) > limit) {
    h.es = std::copysign(limit, h.es);  // (K13.a)
    ds = 0.0;                           // (K13.b)
  }
  ContactForce f{h.en + dn, h.es + ds, false};  // (K9, K14)
  if (law.end_rule == EndRule::total && f.fn < 0.0) return {};
  return f;
}

}  // namespace dem
