#pragma once
// Exact linear-elastic response of a bonded square PRE lattice (refs §4.3) and of the M-D beam built
// from it (three-point bending on disk supports under a load disk, case M-D), by assembling and solving
// the stiffness matrix of the discrete lattice. Independent of lib/: derived here from the equations
// of docs/model.md.
//
// Model (small displacements, every contact in its initial state, no breaking, no slip):
//  - each element is a rigid body with 3 DOF (u_x, u_y, θ) about its centre; the displacement of a
//    body point p is u + θ k×(p − c);
//  - a bonded face between two equal squares of half-side r (M1: area A = 2rℓ) carries N discrete
//    normal springs K_n = k_n A/((r₁+r₂)N) = k_n ℓ/N (M6.3) at s = rξ_i on the face line, ξ_i at the
//    segment centres (M13.1) or the face ends (M13.2, N = 2), and as many tangential springs
//    K_s = k_s ℓ/N (M6.4). The relative displacement of the two bodies' points on the face line is,
//    along the normal, ū + rξ(θ₁ − θ₂) (M15.1, up to the sign convention of ξ) and along the face
//    v̄ = v₁ − v₂ + rθ₁ + rθ₂ (M15.2, M3.4): the linearised increments ARE the rigid-body
//    kinematics of a point on the face line, so the springs are placed there;
//  - a disk contact (Cundall's linear law, the load and support disks) is a normal spring k_c along
//    the line of centres and a tangential spring k_t (0: frictionless) at the touching point;
//  - dashpots carry no force in a static state and are left out.
// The stiffness matrix is K = Σ k bᵀb over the springs, b the row that maps the 6 DOF of the two
// bodies to the spring's extension; it is solved with Eigen's sparse LDLᵀ (SimplicialLDLT). Bodies
// held fixed (the supports) are ground and carry no DOF.
// With N = 1 (segment centres) a face has no moment lever and its shear spring sees r(θ₁ + θ₂), so
// elements turning by ±θ in a checkerboard strain nothing: the static problem is singular (throws).
// Accuracy: a direct solve; relative error ~ condition number × 1e-16 (≤ 1e-9 for the lattices here,
// checked by the residual in the tests).

#include <utility>
#include <vector>

#include "ref/beam.hpp"

namespace ref {

// A linear network of springs between rigid bodies in the plane.
class RigidSpringNetwork {
 public:
  static constexpr int ground = -1;

  int add_body(double x, double y);  // returns the body's index; its DOF are 3·index + {0, 1, 2}
  int body_count() const { return static_cast<int>(centres_.size()) / 2; }
  std::pair<double, double> centre(int body) const { return {centres_.at(2 * body), centres_.at(2 * body + 1)}; }

  // A spring of stiffness k [N/m] acting along the unit vector (dx, dy) at the point (px, py);
  // its extension is the displacement of body b's point minus that of body a's, along (dx, dy).
  // Returns its index.
  int add_spring(int a, int b, double px, double py, double dx, double dy, double k);

  void add_load(int body, double fx, double fy, double torque);
  void prescribe(int body, int component, double value);  // component 0: u_x, 1: u_y, 2: θ

  // Solves K u = f for the free DOF, prescribed ones held; throws if K is singular on the free DOF.
  // Inactive springs (set_active) carry nothing and are left out of K.
  std::vector<double> solve() const;

  // A spring taken out (false) or put back (true): an open unilateral contact (ref/no_tension.hpp).
  void set_active(int spring, bool active) { springs_.at(static_cast<std::size_t>(spring)).active = active; }
  bool active(int spring) const { return springs_.at(static_cast<std::size_t>(spring)).active; }

  double extension(const std::vector<double>& u, int spring) const;
  std::pair<double, double> spring_point(int spring) const {
    const Spring& s = springs_.at(static_cast<std::size_t>(spring));
    return {s.px, s.py};
  }
  double spring_force(const std::vector<double>& u, int spring) const;  // k × extension, tension > 0; 0 if inactive
  double energy(const std::vector<double>& u) const;                    // Σ ½ k e²
  // The y (or x) displacement of the body point at (px, py) in the undeformed configuration.
  double point_displacement(const std::vector<double>& u, int body, double px, double py, int component) const;
  // Largest |K u − f| on the free DOF over the largest |f| (a solve check).
  double relative_residual(const std::vector<double>& u) const;

 private:
  struct Spring {
    int a, b;
    double px, py, dx, dy, k;
    bool active = true;
  };
  void row(const Spring& s, int& ia, int& ib, double ra[3], double rb[3]) const;
  std::vector<double> centres_;  // x0, y0, x1, y1, ...
  std::vector<Spring> springs_;
  std::vector<double> loads_;
  std::vector<int> prescribed_dof_;
  std::vector<double> prescribed_value_;
};

// A bonded face between bodies a (centre c_a) and b = a's neighbour at c_a + 2r·n, n = (nx, ny) a unit
// axis vector; N normal and N tangential springs at the segment positions. Returns the index of the
// first normal spring; the springs of one face are [normal_0, tangential_0, normal_1, ...].
int add_bonded_face(RigidSpringNetwork& net, int a, int b, double radius, double thickness, double kn,
                    double ks, int segments, SegmentPositions where);

// The M-D beam: rows × columns bonded PREs of radius r (bottom at y = 0, centred on x = 0), two fixed
// support disks at x = ±span/2 under the bottom row, a load disk at x = 0 on the top row, each disk
// placed touching its nearest core(s) (one core straight above or below, or two in a groove).
struct LatticeBeamModel {
  int rows = 0, columns = 0;
  double radius = 0.0;      // r [m]
  double thickness = 0.0;   // ℓ = b [m]
  double kn = 0.0, ks = 0.0;  // face moduli, stress per unit strain [Pa]
  int segments = 1;
  SegmentPositions where = SegmentPositions::centres;
  double span = 0.0;                 // L [m]
  double support_radius = 0.0;       // [m]
  double load_radius = 0.0;          // [m]
  double contact_kn = 0.0;           // every disk–PRE contact, normal [N/m]
  double contact_kt = 0.0;           // tangential [N/m]; 0: frictionless (slipping freely)
  double platen_kt = 0.0;            // platen–load-disk tangential [N/m]; 0: frictionless
  bool no_tension = true;            // disk contacts push only (K9); false: they may pull (linear)
};

struct LatticeBeamResponse {
  double stiffness = 0.0;             // P/δ, δ the downward displacement of the deflection point [N/m]
  double support_settlement = 0.0;    // downward displacement of the support cores' bottom, per unit P [m/N]
  double max_segment_tension = 0.0;   // largest face normal spring tension per unit P [1]
  double max_tension_x = 0.0, max_tension_y = 0.0;  // where that spring sits [m]
  double first_crack_load = 0.0;      // P at which that spring reaches σ_t A/N (set by first_crack) [N]
  double max_contact_tension = 0.0;   // largest disk-contact normal tension per unit P (≤ 0: no-tension solve) [1]
  int open_contacts = 0;              // disk contacts that the no-tension solve left open (would pull)
  std::vector<double> contact_forces; // normal force per unit P of each disk contact (left support's,
                                      // right support's, the load disk's; tension > 0, 0 when open)
  double max_contact_friction = 0.0;  // largest |tangential|/normal force over the disk contacts [1]
  int deflection_body = -1;           // the lattice element whose point is measured
  double residual = 0.0;              // relative residual of the solve
};

// Solves the beam for a unit load on the load disk, the disk contacts unilateral (no tension: the
// active-set solve of ref/no_tension.hpp; a support in a groove may lift off one of its two cores); the deflection point is the bottom corner at
// x = 0 of the bottom element left of mid-span (columns even), i.e. body point c + r(1, −1).
// With tensile_strength > 0 also the first-crack load σ_t (2rℓ/N)/max_segment_tension.
LatticeBeamResponse solve_lattice_beam(const LatticeBeamModel& model, double tensile_strength = 0.0);

}  // namespace ref
