// Exact linear-elastic lattice of rigid PREs (see ref/lattice_beam.hpp).
#include "ref/lattice_beam.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include "ref/no_tension.hpp"
#include "ref/require.hpp"

namespace ref {

int RigidSpringNetwork::add_body(double x, double y) {
  detail::require_finite("RigidSpringNetwork::add_body", "x", x);
  detail::require_finite("RigidSpringNetwork::add_body", "y", y);
  centres_.push_back(x);
  centres_.push_back(y);
  loads_.resize(loads_.size() + 3, 0.0);
  return body_count() - 1;
}

int RigidSpringNetwork::add_spring(int a, int b, double px, double py, double dx, double dy, double k) {
  constexpr const char* where = "RigidSpringNetwork::add_spring";
  const int n = body_count();
  if (a < ground || a >= n) detail::fail(where, "body a must be ground (-1) or an existing body", a);
  if (b < ground || b >= n) detail::fail(where, "body b must be ground (-1) or an existing body", b);
  if (a == b) detail::fail(where, "a spring needs two different bodies", a);
  detail::require_non_negative(where, "k", k);
  if (std::abs(std::hypot(dx, dy) - 1.0) > 1e-12) detail::fail(where, "the direction must be a unit vector", std::hypot(dx, dy));
  springs_.push_back({a, b, px, py, dx, dy, k, true});
  return static_cast<int>(springs_.size()) - 1;
}

void RigidSpringNetwork::add_load(int body, double fx, double fy, double torque) {
  if (body < 0 || body >= body_count()) detail::fail("RigidSpringNetwork::add_load", "no such body", body);
  loads_[3 * body] += fx;
  loads_[3 * body + 1] += fy;
  loads_[3 * body + 2] += torque;
}

void RigidSpringNetwork::prescribe(int body, int component, double value) {
  if (body < 0 || body >= body_count()) detail::fail("RigidSpringNetwork::prescribe", "no such body", body);
  if (component < 0 || component > 2) detail::fail("RigidSpringNetwork::prescribe", "component must be 0, 1 or 2", component);
  prescribed_dof_.push_back(3 * body + component);
  prescribed_value_.push_back(value);
}

// Extension e = d·(u_b + θ_b k×(p − c_b)) − d·(u_a + θ_a k×(p − c_a)); k×(x, y) = (−y, x), so the
// θ coefficient of d·(θ k×q) is −d_x q_y + d_y q_x.
void RigidSpringNetwork::row(const Spring& s, int& ia, int& ib, double ra[3], double rb[3]) const {
  auto fill = [&](int body, double sign, double r[3]) {
    const double qx = s.px - centres_[2 * body], qy = s.py - centres_[2 * body + 1];
    r[0] = sign * s.dx;
    r[1] = sign * s.dy;
    r[2] = sign * (-s.dx * qy + s.dy * qx);
  };
  ia = s.a;
  ib = s.b;
  if (ia != ground) fill(ia, -1.0, ra);
  if (ib != ground) fill(ib, 1.0, rb);
}

double RigidSpringNetwork::extension(const std::vector<double>& u, int spring) const {
  const Spring& s = springs_.at(static_cast<std::size_t>(spring));
  int ia, ib;
  double ra[3], rb[3];
  row(s, ia, ib, ra, rb);
  double e = 0.0;
  for (int j = 0; j < 3; ++j) {
    if (ia != ground) e += ra[j] * u[3 * ia + j];
    if (ib != ground) e += rb[j] * u[3 * ib + j];
  }
  return e;
}

double RigidSpringNetwork::spring_force(const std::vector<double>& u, int spring) const {
  const Spring& s = springs_.at(static_cast<std::size_t>(spring));
  return s.active ? s.k * extension(u, spring) : 0.0;
}

double RigidSpringNetwork::energy(const std::vector<double>& u) const {
  double w = 0.0;
  for (std::size_t i = 0; i < springs_.size(); ++i) {
    if (!springs_[i].active) continue;
    const double e = extension(u, static_cast<int>(i));
    w += 0.5 * springs_[i].k * e * e;
  }
  return w;
}

double RigidSpringNetwork::point_displacement(const std::vector<double>& u, int body, double px, double py,
                                              int component) const {
  const double qx = px - centres_[2 * body], qy = py - centres_[2 * body + 1];
  const double theta = u[3 * body + 2];
  return component == 0 ? u[3 * body] - theta * qy : u[3 * body + 1] + theta * qx;
}

std::vector<double> RigidSpringNetwork::solve() const {
  const int dofs = 3 * body_count();
  if (dofs == 0) detail::fail("RigidSpringNetwork::solve", "the network has no bodies", 0);
  std::vector<int> index(static_cast<std::size_t>(dofs), 0);  // free DOF number, or −1 if prescribed
  std::vector<double> u(static_cast<std::size_t>(dofs), 0.0);
  for (std::size_t i = 0; i < prescribed_dof_.size(); ++i) {
    index[static_cast<std::size_t>(prescribed_dof_[i])] = -1;
    u[static_cast<std::size_t>(prescribed_dof_[i])] = prescribed_value_[i];
  }
  int free = 0;
  for (int& i : index)
    if (i == 0) i = free++;
    else i = -1;
  // (index was 0 for free DOF before numbering; −1 stays −1.)
  if (free == 0) return u;

  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs(free);
  for (int d = 0; d < dofs; ++d)
    if (index[d] >= 0) rhs[index[d]] = loads_[d];
  for (const Spring& s : springs_) {
    if (!s.active) continue;
    int ia, ib;
    double ra[3], rb[3];
    row(s, ia, ib, ra, rb);
    int dof[6];
    double coef[6];
    int n = 0;
    for (int j = 0; j < 3; ++j) {
      if (ia != ground) dof[n] = 3 * ia + j, coef[n++] = ra[j];
      if (ib != ground) dof[n] = 3 * ib + j, coef[n++] = rb[j];
    }
    for (int p = 0; p < n; ++p) {
      const int fp = index[dof[p]];
      if (fp < 0) continue;
      for (int q = 0; q < n; ++q) {
        const double kpq = s.k * coef[p] * coef[q];
        const int fq = index[dof[q]];
        if (fq >= 0) triplets.emplace_back(fp, fq, kpq);
        else rhs[fp] -= kpq * u[dof[q]];  // K_fp u_p moves to the right-hand side
      }
    }
  }
  Eigen::SparseMatrix<double> K(free, free);
  K.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(K);
  if (ldlt.info() != Eigen::Success) detail::fail("RigidSpringNetwork::solve", "factorisation failed", free);
  const double dmax = ldlt.vectorD().cwiseAbs().maxCoeff();
  const double dmin = ldlt.vectorD().minCoeff();
  if (!(dmin > 1e-12 * dmax))
    detail::fail("RigidSpringNetwork::solve", "the stiffness matrix is singular or indefinite (a free rigid mode?); D_min/D_max",
                 dmin / dmax);
  const Eigen::VectorXd x = ldlt.solve(rhs);
  for (int d = 0; d < dofs; ++d)
    if (index[d] >= 0) u[d] = x[index[d]];
  return u;
}

double RigidSpringNetwork::relative_residual(const std::vector<double>& u) const {
  const int dofs = 3 * body_count();
  std::vector<double> r(static_cast<std::size_t>(dofs), 0.0);  // internal forces K u
  for (std::size_t i = 0; i < springs_.size(); ++i) {
    int ia, ib;
    double ra[3], rb[3];
    row(springs_[i], ia, ib, ra, rb);
    const double f = spring_force(u, static_cast<int>(i));
    for (int j = 0; j < 3; ++j) {
      if (ia != ground) r[3 * ia + j] += ra[j] * f;
      if (ib != ground) r[3 * ib + j] += rb[j] * f;
    }
  }
  std::vector<bool> fixed(static_cast<std::size_t>(dofs), false);
  for (int d : prescribed_dof_) fixed[static_cast<std::size_t>(d)] = true;
  double worst = 0.0, scale = 0.0;
  for (int d = 0; d < dofs; ++d) {
    scale = std::max(scale, std::abs(loads_[d]));
    if (!fixed[d]) worst = std::max(worst, std::abs(r[d] - loads_[d]));
  }
  return scale > 0.0 ? worst / scale : worst;
}

int add_bonded_face(RigidSpringNetwork& net, int a, int b, double radius, double thickness, double kn, double ks,
                    int segments, SegmentPositions where) {
  constexpr const char* fn = "add_bonded_face";
  detail::require_positive(fn, "radius", radius);
  detail::require_positive(fn, "thickness", thickness);
  detail::require_positive(fn, "kn", kn);
  detail::require_non_negative(fn, "ks", ks);
  if (segments < 1) detail::fail(fn, "segments must be >= 1", segments);
  if (where == SegmentPositions::face_ends && segments != 2) detail::fail(fn, "face ends (M13.2) need N = 2", segments);
  const auto [xa, ya] = net.centre(a);
  const auto [xb, yb] = net.centre(b);
  const double nx = (xb - xa) / (2.0 * radius), ny = (yb - ya) / (2.0 * radius);
  if (std::abs(std::hypot(nx, ny) - 1.0) > 1e-9) detail::fail(fn, "the centres must be 2r apart", std::hypot(nx, ny));
  const double tx = -ny, ty = nx;                                 // along the face
  const double fx = 0.5 * (xa + xb), fy = 0.5 * (ya + yb);       // face centre, on the face line
  const double Kn = kn * thickness / segments;  // (M6.3): k_n (2rℓ)/((r + r) N)
  const double Ks = ks * thickness / segments;  // (M6.4)
  int first = -1;
  for (int i = 1; i <= segments; ++i) {
    const double xi = where == SegmentPositions::centres ? double(2 * i - 1 - segments) / segments  // (M13.1)
                                                         : double(2 * i - 3);                        // (M13.2)
    const double px = fx + radius * xi * tx, py = fy + radius * xi * ty;
    const int n = net.add_spring(a, b, px, py, nx, ny, Kn);  // (M15.1): ū + rξ(θ₁ − θ₂) on the face line
    net.add_spring(a, b, px, py, tx, ty, Ks);                // (M15.2): v₁ − v₂ + rθ₁ + rθ₂
    if (first < 0) first = n;
  }
  return first;
}

LatticeBeamResponse solve_lattice_beam(const LatticeBeamModel& m, double tensile_strength) {
  constexpr const char* fn = "solve_lattice_beam";
  if (m.rows < 1) detail::fail(fn, "rows must be >= 1", m.rows);
  if (m.columns < 2 || m.columns % 2 != 0) detail::fail(fn, "columns must be even and >= 2", m.columns);
  detail::require_positive(fn, "radius", m.radius);
  detail::require_positive(fn, "span", m.span);
  detail::require_positive(fn, "support_radius", m.support_radius);
  detail::require_positive(fn, "load_radius", m.load_radius);
  detail::require_positive(fn, "contact_kn", m.contact_kn);
  detail::require_non_negative(fn, "contact_kt", m.contact_kt);
  detail::require_non_negative(fn, "platen_kt", m.platen_kt);
  detail::require_non_negative(fn, "tensile_strength", tensile_strength);
  const double r = m.radius, l = m.thickness;
  if (m.span / 2.0 >= (m.columns - 1) * r) detail::fail(fn, "the supports must lie under the lattice", m.span);

  RigidSpringNetwork net;
  const double x0 = -(m.columns - 1) * r;  // centre of column 0; the bottom at y = 0
  for (int row = 0; row < m.rows; ++row)
    for (int c = 0; c < m.columns; ++c) net.add_body(x0 + 2 * r * c, (2 * row + 1) * r);
  auto element = [&](int row, int c) { return row * m.columns + c; };
  std::vector<int> face_normals;  // first normal spring of each face; N normal springs, stride 2
  for (int row = 0; row < m.rows; ++row)
    for (int c = 0; c < m.columns; ++c) {
      if (c + 1 < m.columns)
        face_normals.push_back(add_bonded_face(net, element(row, c), element(row, c + 1), r, l, m.kn, m.ks,
                                               m.segments, m.where));
      if (row + 1 < m.rows)
        face_normals.push_back(add_bonded_face(net, element(row, c), element(row + 1, c), r, l, m.kn, m.ks,
                                               m.segments, m.where));
    }

  // Disk contacts: a disk of radius R at x_d touching the nearest core(s) of one row, from below
  // (side −1) or above (+1); disk is its body, or ground for a fixed support.
  struct Contact {
    int normal, tangential;
  };
  std::vector<Contact> contacts;
  int supported_core = -1;
  auto place = [&](int row, double x_d, int side, double R, int disk) {
    double dx_min = 1e300;
    for (int c = 0; c < m.columns; ++c) dx_min = std::min(dx_min, std::abs(x0 + 2 * r * c - x_d));
    if (!(dx_min < r + R)) detail::fail(fn, "a disk cannot reach the lattice", x_d);
    const double y_row = (2 * row + 1) * r;
    const double y_d = y_row + side * std::sqrt((r + R) * (r + R) - dx_min * dx_min);
    for (int c = 0; c < m.columns; ++c) {
      const double xc = x0 + 2 * r * c;
      if (std::abs(std::abs(xc - x_d) - dx_min) > 1e-9 * r) continue;
      const double nx = (x_d - xc) / (r + R), ny = (y_d - y_row) / (r + R);  // core → disk
      const double px = xc + r * nx, py = y_row + r * ny;                     // the touching point
      Contact k{net.add_spring(element(row, c), disk, px, py, nx, ny, m.contact_kn), -1};
      if (m.contact_kt > 0.0) k.tangential = net.add_spring(element(row, c), disk, px, py, -ny, nx, m.contact_kt);
      contacts.push_back(k);
      if (side < 0 && supported_core < 0) supported_core = element(row, c);
    }
    return y_d;
  };
  auto disk_height = [&](int row, double x_d, int side, double R) {
    double dx_min = 1e300;
    for (int c = 0; c < m.columns; ++c) dx_min = std::min(dx_min, std::abs(x0 + 2 * r * c - x_d));
    return (2 * row + 1) * r + side * std::sqrt((r + R) * (r + R) - dx_min * dx_min);
  };
  place(0, -m.span / 2.0, -1, m.support_radius, RigidSpringNetwork::ground);  // supports: fixed, ground
  place(0, m.span / 2.0, -1, m.support_radius, RigidSpringNetwork::ground);
  const double y_load = disk_height(m.rows - 1, 0.0, +1, m.load_radius);
  const int disk = net.add_body(0.0, y_load);
  place(m.rows - 1, 0.0, +1, m.load_radius, disk);
  if (m.platen_kt > 0.0) net.add_spring(RigidSpringNetwork::ground, disk, 0.0, y_load + m.load_radius, 1.0, 0.0, m.platen_kt);
  net.add_load(disk, 0.0, -1.0, 0.0);  // P = 1 N downwards
  // Rigid modes without friction: the disk's spin carries no torque, and with vertical support contacts
  // the beam's horizontal translation carries no force; holding them changes no force (equilibrium).
  if (m.contact_kt == 0.0 && m.platen_kt == 0.0) net.prescribe(disk, 2, 0.0);
  const bool supports_vertical = std::abs(disk_height(0, -m.span / 2.0, -1, m.support_radius) + m.support_radius) < 1e-12 * r;
  if (m.contact_kt == 0.0 && supports_vertical) net.prescribe(element(0, 0), 0, 0.0);

  std::vector<UnilateralContact> unilateral;  // the disk contacts push only (K8): active-set solve
  if (m.no_tension)
    for (const Contact& k : contacts) unilateral.push_back({k.normal, k.tangential});
  const NoTensionSolution solution = solve_no_tension(net, unilateral);
  const std::vector<double>& u = solution.u;
  LatticeBeamResponse out;
  out.open_contacts = static_cast<int>(std::count(solution.open.begin(), solution.open.end(), true));
  out.residual = net.relative_residual(u);
  out.deflection_body = element(0, m.columns / 2 - 1);
  const auto [xm, ym] = net.centre(out.deflection_body);
  const double delta = -net.point_displacement(u, out.deflection_body, xm + r, ym - r, 1);
  if (!(delta > 0.0)) detail::fail(fn, "the beam does not deflect downwards", delta);
  out.stiffness = 1.0 / delta;
  if (supported_core >= 0) {
    const auto [xs, ys] = net.centre(supported_core);
    out.support_settlement = -net.point_displacement(u, supported_core, xs, ys - r, 1);
  }
  const int n_springs = m.segments;
  for (int first : face_normals)
    for (int i = 0; i < n_springs; ++i) {
      const double f = net.spring_force(u, first + 2 * i);
      if (f > out.max_segment_tension) {
        out.max_segment_tension = f;
        std::tie(out.max_tension_x, out.max_tension_y) = net.spring_point(first + 2 * i);
      }
    }
  out.max_contact_tension = -1e300;
  for (const Contact& k : contacts) {
    out.contact_forces.push_back(net.spring_force(u, k.normal));
    if (!net.active(k.normal)) continue;               // open: carries nothing
    const double fn_ = net.spring_force(u, k.normal);  // tension > 0
    out.max_contact_tension = std::max(out.max_contact_tension, fn_);
    if (k.tangential >= 0 && fn_ < 0.0)
      out.max_contact_friction = std::max(out.max_contact_friction, std::abs(net.spring_force(u, k.tangential)) / -fn_);
  }
  if (tensile_strength > 0.0 && out.max_segment_tension > 0.0)
    out.first_crack_load = tensile_strength * (2.0 * r * l / m.segments) / out.max_segment_tension;  // (M8)
  return out;
}

}  // namespace ref
