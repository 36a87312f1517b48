#pragma once
// Small helpers shared by the unit tests of the DEM core: models built in code, temporary case
// files, messages of expected exceptions.
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "dem/core/model.hpp"

namespace test {

/// A model with the given materials (name, density) and no laws yet; thickness 1 m.
inline dem::Model make_model(const std::vector<std::pair<std::string, double>>& materials, double dt) {
  dem::Model m;
  for (const auto& [name, rho] : materials) m.materials.push_back({name, rho});
  m.law_of_pair.assign(m.materials.size() * m.materials.size(), -1);
  m.numerics.dt = dt;
  return m;
}

/// Registers `law` for the material pair (a, b), both orders.
inline void set_law(dem::Model& m, std::int32_t a, std::int32_t b, const dem::PairLaw& law) {
  const auto idx = static_cast<std::int32_t>(m.laws.size());
  m.laws.push_back(law);
  const std::size_t n = m.materials.size();
  m.law_of_pair[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)] = idx;
  m.law_of_pair[static_cast<std::size_t>(b) * n + static_cast<std::size_t>(a)] = idx;
}

inline dem::Wall segment_wall(dem::Vec2 a, dem::Vec2 b, std::int32_t material, std::string name = "wall") {
  dem::Wall w;
  w.name = std::move(name);
  w.a = a;
  w.b = b;
  w.material = material;
  return w;
}

/// Linear spring–dashpot law with explicit dashpots.
inline dem::PairLaw linear_law(double kn, double ks, double mu, double eta_n, double eta_s) {
  dem::PairLaw law;
  law.kind = dem::LawKind::linear;
  law.linear.kn = kn;
  law.linear.ks = ks;
  law.linear.mu = mu;
  law.damping_from_ratio = false;
  law.eta_n = eta_n;
  law.eta_s = eta_s;
  return law;
}

/// A bonded face law: N segments at the centres, linearised, strengths never reached, bonded at the
/// start; discrete springs kn, ks per segment [N/m], damping ratio h_n.
inline dem::PairLaw bonded_face_law(int segments, double kn, double ks, double h_n) {
  dem::PairLaw law;
  law.kind = dem::LawKind::face;
  law.face.segments = segments;
  law.face.tensile_strength = 1e15;
  law.face.cohesion = 1e15;
  law.face_kn = kn;
  law.face_ks = ks;
  law.damping_ratio = h_n;
  law.bond_at_start = true;
  return law;
}

/// Materials "block" (0, 2000 kg/m³) and "disk" (1, 2650 kg/m³), K18: blocks bonded face to face by
/// `face_kn` (2 segments at the face ends, K_s = 0, no dashpots) and a linear law `disk_kn` (μ = 0.5, no
/// dashpots) between a block and a disk; no elements yet (the guard's block and room tests).
inline dem::Model blocks_and_disk_laws(double face_kn, double disk_kn) {
  dem::Model m = make_model({{"block", 2000.0}, {"disk", 2650.0}}, 1e-7);
  m.numerics.integrator = dem::Integrator::k18;
  dem::PairLaw law = bonded_face_law(2, face_kn, 0.0, 0.0);
  law.face.positions = dem::SegmentPositions::ends;
  set_law(m, 0, 0, law);
  set_law(m, 0, 1, linear_law(disk_kn, 0.0, 0.5, 0.0, 0.0));
  return m;
}

/// Writes `text` to a fresh file in a per-test temporary folder and returns its path.
inline std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "dem2d_unit_lib";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

/// What `f` throws as Exception (the test fails if it throws nothing or something else).
template <class Exception, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const Exception& e) {
    return e.what();
  }
  FAIL("the expected exception was not thrown");
  return {};
}

/// Source folder of the tests' case files.
inline std::filesystem::path case_dir() { return std::filesystem::path(DEM2D_SOURCE_DIR) / "tests/lib/fixtures"; }

/// The elements of `a` have the same state bit for bit in `b` (positions, rotations, velocities,
/// rotation increments); `b` may hold more elements after them.
inline void check_same_state(const dem::Elements& a, const dem::Elements& b) {
  REQUIRE(a.size() <= b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CAPTURE(i);
    CHECK(a.x[i] == b.x[i]);
    CHECK(a.y[i] == b.y[i]);
    CHECK(a.phi[i] == b.phi[i]);
    CHECK(a.vx[i] == b.vx[i]);
    CHECK(a.vy[i] == b.vy[i]);
    CHECK(a.omega[i] == b.omega[i]);
    CHECK(a.dphi[i] == b.dphi[i]);
  }
}

/// A path below the source root.
inline std::filesystem::path source(const std::string& rel) { return std::filesystem::path(DEM2D_SOURCE_DIR) / rel; }

/// An empty scratch folder <tmp>/<group>/<name> (removed first).
inline std::filesystem::path fresh_dir(const std::string& group, const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / group / name;
  std::filesystem::remove_all(d);
  return d;
}

/// A whole file as bytes.
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace test
