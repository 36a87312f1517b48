// Probe quantity names (lib/dem/run/quantities.hpp) are read strictly: a contact quantity is exactly
// e<i>.<field>.<other> with a field it knows; anything else is refused with the name, never read as
// another field. Planted bug that turns it red: any three-part name taken as a contact quantity (an
// unknown field then read as f_s), and a fourth part ignored.
#include <catch2/catch.hpp>

#include "dem/cases/case_file.hpp"
#include "dem/run/quantities.hpp"

#include "../test_support.hpp"

using Catch::Matchers::Contains;

TEST_CASE("quantities: a contact quantity has exactly three parts and a field it knows", "[outputs]") {
  const dem::Case c = dem::read_case(test::source("tests/lib/fixtures/restart_disks.toml"));
  const dem::Model& m = c.model;
  const std::string expected = "expected e<i>.<field> or e<i>.gap|fn|fs|mr|links|mobilised.<other>";
  for (const char* name : {"e0.fnn.e1", "e0.fx.e1", "e0.x.floor", "e0.fn.e1.e2", "e0.gap.e1.x", "e0.fs.floor.x"}) {
    CAPTURE(name);
    CHECK_THROWS_WITH(dem::compile_quantity(name, m), Contains(name) && Contains(expected));
  }
  for (const char* name : {"e0.fn.e1", "e0.fs.e1", "e0.gap.e1", "e0.links.e1", "e0.mobilised.e1", "e0.fn.floor"}) {
    CAPTURE(name);
    CHECK_NOTHROW(dem::compile_quantity(name, m));
  }
}
