// The LAMMPS dump frame (lib/dem/run/lammps_dump.hpp) read back: every column of every line is the
// state of the element that line names (its id), bit for bit (%.17g reads back exactly), and the box is
// the elements' extent. Planted bug that turns it red: the force column of the previous element.
#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/lammps_dump.hpp"

#include "../test_support.hpp"

TEST_CASE("lammps dump: each line is the state of the element its id names", "[outputs]") {
  // five disks in a box pushed by a driven disk: contacts, so the forces differ from element to element
  const dem::Case c = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"));
  dem::Simulation sim(c.model);
  for (int k = 0; k < 3000; ++k) sim.step();
  const dem::Elements& e = sim.model().elements;
  std::istringstream in(dem::lammps_dump_frame(sim));
  std::string line;
  auto next = [&] {
    REQUIRE(std::getline(in, line));
    return line;
  };
  CHECK(next() == "ITEM: TIMESTEP");
  CHECK(next() == std::to_string(sim.steps()));
  CHECK(next() == "ITEM: NUMBER OF ATOMS");
  CHECK(next() == std::to_string(e.size()));
  CHECK(next() == "ITEM: BOX BOUNDS ff ff pp");
  double xlo, xhi, ylo, yhi, zlo, zhi;
  std::istringstream(next()) >> xlo >> xhi;
  std::istringstream(next()) >> ylo >> yhi;
  std::istringstream(next()) >> zlo >> zhi;
  CHECK(next() == "ITEM: ATOMS id type x y vx vy omegaz radius fx fy");
  double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
  for (std::size_t i = 0; i < e.size(); ++i) {
    x_min = std::min(x_min, e.x[i] - e.radius[i]), x_max = std::max(x_max, e.x[i] + e.radius[i]);
    y_min = std::min(y_min, e.y[i] - e.radius[i]), y_max = std::max(y_max, e.y[i] + e.radius[i]);
  }
  CHECK(xlo == x_min);
  CHECK(xhi == x_max);
  CHECK(ylo == y_min);
  CHECK(yhi == y_max);
  CHECK(zlo == -0.5 * c.model.thickness);
  CHECK(zhi == 0.5 * c.model.thickness);
  // the storage index of each id (the order may differ from the ids after a reordering)
  std::vector<std::size_t> index_of(e.size());
  for (std::size_t i = 0; i < e.size(); ++i) index_of[sim.id_of(i)] = i;
  std::vector<long> ids;
  int distinct_fx = 0;
  double last_fx = 0.0;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    long id, type;
    double x, y, vx, vy, omega, radius, fx, fy;
    REQUIRE(row >> id >> type >> x >> y >> vx >> vy >> omega >> radius >> fx >> fy);
    REQUIRE(id >= 1);
    REQUIRE(static_cast<std::size_t>(id) <= e.size());
    const std::size_t i = index_of[static_cast<std::size_t>(id - 1)];
    INFO("id " << id);
    CHECK(type == e.material[i] + 1);
    CHECK(x == e.x[i]);
    CHECK(y == e.y[i]);
    CHECK(vx == e.vx[i]);
    CHECK(vy == e.vy[i]);
    CHECK(omega == e.omega[i]);
    CHECK(radius == e.radius[i]);
    CHECK(fx == e.fx[i]);
    CHECK(fy == e.fy[i]);
    if (ids.empty() || fx != last_fx) ++distinct_fx;
    last_fx = fx;
    ids.push_back(id);
  }
  CHECK(ids.size() == e.size());
  CHECK(std::is_sorted(ids.begin(), ids.end()));
  CHECK(distinct_fx > 2);  // the forces differ, so a line with its neighbour's force is seen
}
