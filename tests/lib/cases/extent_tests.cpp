// Every geometry a case gives or generates lies within the extent dem2d represents (lib/dem/cases/extent.hpp):
// a random arrangement's region of ±1e308 (every disk at (inf, inf), UBSan at the fill's cell index), two
// disks at x = ±1e308 (NaN → uint32 in the neighbour search), walls, rows, lattices and ordered
// arrangements beyond it are refused with file:line: key before anything runs; the same shapes inside it
// are read.
#include <catch2/catch.hpp>

#include <string>

#include "dem/cases/case_file.hpp"
#include "../test_support.hpp"

using Catch::Matchers::Contains;

namespace {

const std::string kHead = R"([case]
title = "extent"
[[material]]
name = "d"
density = 2650.0
[[contact]]
between = ["d", "d"]
kn = 1e5
[numerics]
dt = 1e-5
duration = 1e-4
)";

const std::string kDisk = "[[element]]\nmaterial = \"d\"\nradius = 0.01\nposition = [0.0, 1.0]\n";

std::string read_error(const std::string& name, const std::string& body) {
  return test::message_of<dem::CaseError>([&] { dem::read_case(test::write_temp(name, kHead + body)); });
}

}  // namespace

TEST_CASE("check: geometry outside the represented extent is refused with file:line: key", "[trust][case]") {
  struct Bad {
    const char* name;
    std::string body;
    const char* key_at;  // "file:line: key"
  };
  const Bad bad[] = {
      {"random_region", "[[arrangement]]\nkind = \"random\"\nmaterial = \"d\"\nradius = 0.01\nregion = [[-1e308, -1e308], [1e308, 1e308]]\ncount = 3\nseed = 1\n",
       "extent_random_region.toml:16: arrangement.0.region"},
      {"random_cells", "[[arrangement]]\nkind = \"random\"\nmaterial = \"d\"\nradius = 1e-300\nregion = [[0.0, 0.0], [1.0, 1.0]]\ncount = 3\nseed = 1\n",
       "extent_random_cells.toml:16: arrangement.0.region"},
      {"disks", "[[element]]\nmaterial = \"d\"\nradius = 0.01\nposition = [-1e308, 0.0]\n"
                "[[element]]\nmaterial = \"d\"\nradius = 0.01\nposition = [1e308, 0.0]\n",
       "extent_disks.toml:15: element.0.position"},
      {"wall", "[[wall]]\nfrom = [0.0, 0.0]\nto = [2e6, 0.0]\nmaterial = \"d\"\n" + kDisk, "extent_wall.toml:14: wall.0.to"},
      {"point_wall", "[[wall]]\ntype = \"point\"\nat = [0.0, -3e6]\nmaterial = \"d\"\n" + kDisk, "extent_point_wall.toml:14: wall.0.at"},
      {"row", "[[row]]\nmaterial = \"d\"\nradius = 0.01\nstart = [0.0, 0.0]\nstep = [1e5, 0.0]\ncount = 20\n",
       "extent_row.toml:16: row.0.step"},
      {"lattice", "[[lattice]]\nmaterial = \"d\"\nradius = 0.01\norigin = [999999.995, 0.0]\ncolumns = 1\nrows = 1\n",
       "extent_lattice.toml:15: lattice.0.origin"},
      {"ordered", "[[arrangement]]\nkind = \"ordered\"\nmaterial = \"d\"\nradius = 0.01\ns = 4\nleft = 0.0\nright = 0.2\nfloor = 1e7\nrows = 2\n",
       "extent_ordered.toml:19: arrangement.0.floor"},
      {"ordered_left", "[[arrangement]]\nkind = \"ordered\"\nmaterial = \"d\"\nradius = 0.01\ns = 4\nleft = -1e7\nright = 0.2\nfloor = 0.0\nrows = 2\n",
       "extent_ordered_left.toml:17: arrangement.0.left"},
  };
  for (const Bad& b : bad) {
    INFO(b.name);
    CHECK_THAT(read_error(std::string("extent_") + b.name + ".toml", b.body), Contains(b.key_at) && Contains("extent"));
  }
}

TEST_CASE("check: geometry inside the represented extent is read", "[trust][case]") {
  const std::string body =
      "[[element]]\nmaterial = \"d\"\nradius = 0.01\nposition = [999999.99, -999999.99]\n"
      "[[wall]]\nfrom = [-1e6, 0.0]\nto = [1e6, 0.0]\nmaterial = \"d\"\n"
      "[[arrangement]]\nkind = \"random\"\nmaterial = \"d\"\nradius = 0.01\nregion = [[0.0, 1.0], [1.0, 2.0]]\ncount = 3\nseed = 1\n";
  const dem::Case c = dem::read_case(test::write_temp("extent_inside.toml", kHead + body));
  CHECK(c.model.elements.size() == 4);
  CHECK(c.model.walls.size() == 1);
}
