// The reference step as the oracle (lib/dem/core/reference_step.cpp): Kiyama's cycle stated on one thread,
// contact by contact, without the optimised step's machinery. The optimised step() on 1, 2 and 3 threads
// must give the reference's whole state (positions, increments, velocities, rotations, forces, walls, every
// contact slot's history and forces) bit for bit after every compared step.
// The reference calls the readable face law (face_contact_force_scalar), the sweeps its lanes form
// (face_contact_force): the oracle checks that the two agree too.
//
// What the oracle covers: disks and PREs, linear and face laws, element and wall contacts, bonded faces,
// preloads (the constructor's static step, shared by both), a driven element and a driven wall, the base plate
// (M21), both integrators and the staggered start, spatial reordering, rolling resistance (R1–R6), polygon elements
// (P5–P8: both call the one polygon sweep, after the other contacts). What it does not: a silo's
// discharge (the outlet and the keystone are run.cpp's, between steps; a filled silo is covered), and the
// blow-up test (the reference makes none).
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/checkpoint.hpp"
#include "../test_support.hpp"

namespace {

struct OracleCase {
  const char* what;
  const char* path;
  std::vector<std::string> sets;
  int steps;
};

// Small and short: the whole test takes seconds.
const std::vector<OracleCase> kCases = {
    {"a settling bed of disks with walls (contacts from about step 500)", "cases/bench/settle_10k.toml",
     {"numerics.duration=3.2e-3"}, 700},
    {"a PRE block on a slope (face wall)", "cases/pre/block_on_slope.toml", {}, 1500},
    {"a bonded PRE lattice with disks and a driven platen", "cases/beam/mortar_2x8.toml", {}, 2500},
    {"PREs on a base plate (M21)", "cases/base_friction/mc_topple_75pre.toml", {}, 400},
    {"a preloaded PRE", "cases/pre/small_rotation.toml", {}, 400},
    {"a silo filling (disks, walls, spatial reordering at every rebuild)", "cases/silo/fill_discharge_11_12.toml",
     {"numerics.reorder_every=1"}, 600},
    {"disks in a box pushed by a driven disk (K19, rebuilds)", "tests/lib/fixtures/restart_disks.toml", {}, 3000},
    {"a disk on a slope, staggered start", "cases/bench/disk_on_slope.toml", {"numerics.velocity_start=staggered"}, 500},
    {"a disk rolling off a wall's end: the contact opens while it overlaps (K8) and starts again",
     "tests/lib/fixtures/disk_off_wall_end.toml", {}, 900},
    {"a settling bed of disks with rolling resistance (R1–R6) between disks and at the walls",
     "cases/bench/settle_10k.toml",
     {"numerics.duration=3.2e-3", "contact.0.rolling={ friction = 0.1, stiffness_factor = 2.25, damping_ratio = 0.3 }",
      "contact.1.rolling={ friction = 0.2, stiffness = \"1e-3 N*m/rad\" }"},
     700},
    {"a row of spinning disks with rolling resistance on a floor (shared elements with rolling floor contacts)",
     "tests/lib/fixtures/rolling_row.toml", {}, 600},
    {"disks in a box pushed by a driven disk with rolling resistance (K19, rebuilds)", "tests/lib/fixtures/restart_disks.toml",
     {"contact.0.rolling={ friction = 0.3, stiffness_factor = 2.25, damping_ratio = 0.5 }",
      "contact.1.rolling={ friction = 0.2, stiffness_factor = 1.0, damping_ratio = 0.4 }"},
     3000},
    {"a polygon block rocking onto its other corner (polygon–wall contact points, P6)", "cases/polygon/rocking_block.toml",
     {"numerics.dt=2e-4", "contact.0.kn=1e6"}, 900},
    {"two polygon blocks colliding corner first, with friction and dashpots (P5)", "cases/polygon/collision.toml",
     {"element.1.rotation=30 deg", "element.1.position=[\"60 mm\", \"5 mm\"]", "contact.0.friction=0.4",
      "contact.0.damping_ratio=0.1", "numerics.dt=1e-6"},
     1500},
    {"a block of six polygon rectangles settling on a floor, corners on corners, a pentagon above (P5, P6)",
     "tests/lib/fixtures/schema/polygons.toml", {}, 3000},
};

}  // namespace

TEST_CASE("The optimised step on 1, 2 and 3 threads gives the reference step's state bit for bit", "[reference]") {
  for (const OracleCase& oc : kCases) {
    CAPTURE(oc.what, oc.path);
    const dem::Case c = dem::read_case(test::source(oc.path), oc.sets);
    dem::Simulation reference(c.model);
    std::vector<dem::Simulation> sims;
    for (int t = 1; t <= 3; ++t) {
      sims.emplace_back(c.model);
      sims.back().set_threads(t, 1);  // threads even for a few elements
    }
    std::size_t most_contacts = 0;
    bool same = true;
    for (int k = 1; k <= oc.steps && same; ++k) {
      reference.reference_step();
      for (auto& s : sims) s.step();
      most_contacts = std::max(most_contacts, reference.contact_count());
      if (k % 50 == 0 || k == oc.steps) {
        const std::string want = dem::simulation_state(reference);
        CAPTURE(k);
        for (const auto& s : sims) {
          CAPTURE(s.threads());
          same = same && dem::simulation_state(s) == want;
          CHECK(dem::simulation_state(s) == want);
        }
      }
    }
    CHECK(most_contacts > 0);  // the comparison covered contact forces and histories
  }
}
