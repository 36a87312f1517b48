// A preload (Model::preloads, `preload = { rotation, about }`): a static zeroth step that forms and loads
// the contacts with the preloaded turn alone. The other elements' step-0 increments (their initial
// velocity and spin) do not enter it: they are restored afterwards, for the first real step.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "../test_support.hpp"

TEST_CASE("A preload turns one element statically - another element's initial spin does not load its springs", "[preload]") {
  // cases/pre/small_rotation.toml (a PRE bonded to the wall y = 0, preloaded by a 0.1° turn) and a disk
  // resting on the same wall 5 cm away, spinning at 5 rad/s. After the preload the disk's shear spring
  // holds nothing (its spin is a step-0 increment, not part of the static step); the PRE's springs hold
  // the turn whether the disk spins or not.
  std::ifstream in(test::source("cases/pre/small_rotation.toml"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string disk = "\n[[material]]\nname = \"ball\"\ndensity = \"2650 kg/m^3\"\n"
                           "[[contact]]\nbetween = [\"ball\", \"wall\"]\nkn = \"1e5 N/m\"\nks_ratio = 0.5\nfriction = 0.5\n"
                           "[[contact]]\nbetween = [\"ball\", \"block\"]\nkn = \"1e5 N/m\"\n"
                           "[[element]]\nmaterial = \"ball\"\nradius = \"5 mm\"\nposition = [\"0.05 m\", \"4.99 mm\"]\n";
  const auto path = test::write_temp("preload_spin.toml", text.str() + disk);
  const dem::Case still = dem::read_case(path), spinning = dem::read_case(path, {"element.1.angular_velocity=5 rad/s"});
  const dem::Simulation a(still.model), b(spinning.model);
  const dem::ContactView disk_a = a.contact(a.index_of(1), 0, true), disk_b = b.contact(b.index_of(1), 0, true);
  REQUIRE(disk_a.fn > 0.0);  // the disk presses on the wall
  CHECK(disk_b.fn == disk_a.fn);
  CHECK(disk_a.fs == 0.0);
  CHECK(disk_b.fs == 0.0);
  const dem::ContactView pre_a = a.contact(a.index_of(0), 0, true), pre_b = b.contact(b.index_of(0), 0, true);
  REQUIRE(pre_a.links > 0);
  CHECK(pre_b.fn == pre_a.fn);
  CHECK(pre_b.fs == pre_a.fs);
}
