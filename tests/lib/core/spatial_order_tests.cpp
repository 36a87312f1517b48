// Spatial reordering of the elements (lib/dem/core/spatial_order.hpp, numerics.reorder_every): the order
// is a bijection that brings neighbours in space together in memory; contact slots follow their elements
// with their histories; every output is keyed by the element's id and agrees with a run without
// reordering (bit for bit where no sum changes order, within round-off growth otherwise); restart and
// threads stay bit-identical.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/core/spatial_order.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/run.hpp"
#include "../test_support.hpp"

namespace fs = std::filesystem;

namespace {

/// A permutation of 0..n−1 from a fixed seed (Fisher–Yates on mt19937's outputs: the same on every
/// platform, unlike std::shuffle).
std::vector<std::uint32_t> shuffled(std::size_t n, std::uint32_t seed) {
  std::vector<std::uint32_t> p(n);
  std::iota(p.begin(), p.end(), std::uint32_t{0});
  std::mt19937 rng(seed);
  for (std::size_t k = n; k > 1; --k) std::swap(p[k - 1], p[rng() % k]);
  return p;
}

/// A settle in a box: rows × cols disks (radii 0.9–1.0 mm), rows staggered, written as [[element]]
/// tables in a random order (the numbering has nothing to do with space); `extra` goes into [numerics].
std::string shuffled_settle(int rows, int cols, double duration, const std::string& extra = "",
                            const std::string& output = "vtk = false\nevery = 100\nseries = [\"t\", \"contacts\", \"energy.kinetic\", \"e7.y\", \"e7.fn.e8\"]\n") {
  const double sx = 2.04e-3, width = 2.2e-3 + cols * sx;
  std::vector<std::string> disks;
  for (int k = 0; k < rows; ++k) {
    const double r = 0.9e-3 + 0.1e-3 * std::fmod(k * 0.618034, 1.0);
    for (int c = 0; c < cols; ++c)
      disks.push_back(fmt::format("[[element]]\nmaterial = \"g\"\nradius = {:.17g}\nposition = [{:.17g}, {:.17g}]\n", r,
                                  1.1e-3 + (c + 0.5 * (k % 2) + 0.03 * std::sin(k)) * sx, 1.1e-3 + k * 2.05e-3));
  }
  std::string t = R"toml([case]
title = "Shuffled settle (spatial order tests)"
[physics]
gravity = [0.0, -9.81]
[[material]]
name = "g"
density = 2650.0
[[material]]
name = "w"
[[contact]]
between = ["g", "g"]
kn = 1e6
ks_ratio = 0.5
friction = 0.5
damping_ratio = 0.3
[[contact]]
between = ["g", "w"]
kn = 1e6
ks_ratio = 0.5
friction = 0.5
damping_ratio = 0.3
)toml";
  t += fmt::format("[[wall]]\nname = \"floor\"\nfrom = [0.0, 0.0]\nto = [{0:.17g}, 0.0]\nmaterial = \"w\"\n"
                   "[[wall]]\nname = \"right\"\nfrom = [{0:.17g}, 0.0]\nto = [{0:.17g}, 1.0]\nmaterial = \"w\"\n"
                   "[[wall]]\nname = \"left\"\nfrom = [0.0, 1.0]\nto = [0.0, 0.0]\nmaterial = \"w\"\n",
                   width);
  for (std::uint32_t k : shuffled(disks.size(), 7)) t += disks[k];
  t += fmt::format("[numerics]\ndt = 4e-6\nduration = {:.17g}\n{}\n[output]\n{}", duration, extra, output);
  return t;
}

/// Mean distance in memory between the two elements of a candidate pair.
double mean_index_gap(const dem::Elements& e, double skin) {
  dem::NeighbourSearch search;
  std::vector<dem::CandidatePair> pairs;
  search.build(e, skin, pairs);
  double sum = 0.0;
  for (const auto& p : pairs) sum += static_cast<double>(p.j - p.i);
  return pairs.empty() ? 0.0 : sum / static_cast<double>(pairs.size());
}

}  // namespace

TEST_CASE("A spatial order is a bijection in Morton order of the cells and brings neighbours together in memory",
          "[spatial_order]") {
  const dem::Case c = dem::read_case(test::write_temp("order_settle.toml", shuffled_settle(30, 30, 4e-6)));
  const dem::Elements& e = c.model.elements;
  std::vector<std::uint32_t> order, inverse;
  std::vector<std::uint64_t> keys;
  const double cell = 2.0 * 1e-3 + 0.225e-3;
  dem::spatial_order(e, cell, order, keys);
  REQUIRE(order.size() == e.size());
  REQUIRE_NOTHROW(dem::invert_permutation(order, inverse));  // a bijection
  for (std::size_t k = 0; k < order.size(); ++k) CHECK(order[inverse[k]] == k);
  for (std::size_t k = 1; k < order.size(); ++k) {  // keys ascending, ties by current index
    CAPTURE(k);
    REQUIRE(keys[order[k - 1]] <= keys[order[k]]);
    if (keys[order[k - 1]] == keys[order[k]]) REQUIRE(order[k - 1] < order[k]);
  }
  CHECK(dem::morton_key(0, 0) == 0);
  CHECK(dem::morton_key(1, 0) == 1);
  CHECK(dem::morton_key(0, 1) == 2);
  CHECK(dem::morton_key(3, 5) == 0b100111);  // x = 011, y = 101 → y2 x2 y1 x1 y0 x0 = 1 0 0 1 1 1
  // a repeated entry is no permutation
  std::vector<std::uint32_t> bad = order;
  bad[1] = bad[0];
  CHECK_THROWS_AS(dem::invert_permutation(bad, inverse), std::invalid_argument);
  // Locality: the partners of a candidate pair, about n/3 apart in a shuffled numbering, sit a few
  // cells' worth of elements apart once ordered.
  dem::Elements ordered = e;
  dem::PermuteScratch scratch;
  dem::permute_elements(ordered, order, scratch);
  const double before = mean_index_gap(e, 0.225e-3), after = mean_index_gap(ordered, 0.225e-3);
  CAPTURE(before, after);
  CHECK(before > 100.0);
  CHECK(after < 0.1 * before);
  // every array moved together, the id with it
  for (std::size_t k = 0; k < ordered.size(); ++k) {
    const std::uint32_t o = order[k];
    REQUIRE(ordered.id[k] == e.id[o]);
    REQUIRE(ordered.x[k] == e.x[o]);
    REQUIRE(ordered.radius[k] == e.radius[o]);
    REQUIRE(ordered.mass[k] == e.mass[o]);
    REQUIRE(ordered.inv_inertia[k] == e.inv_inertia[o]);
  }
}

TEST_CASE("Contacts follow their elements with their histories, turned round where the sides swap",
          "[spatial_order]") {
  // Settled for a while: contacts with shear history (friction, sliding, rotation); a second time with rolling
  // resistance (R1–R6), whose moments are those on i and must turn round with the pair.
  const bool rolling = GENERATE(false, true);
  CAPTURE(rolling);
  const std::vector<std::string> sets =
      rolling ? std::vector<std::string>{"contact.0.rolling={ friction = 0.2, stiffness_factor = 2.25, damping_ratio = 0.3 }",
                                         "contact.1.rolling={ friction = 0.1, stiffness_factor = 2.25, damping_ratio = 0.3 }"}
              : std::vector<std::string>{};
  const dem::Case c = dem::read_case(test::write_temp("order_contacts.toml", shuffled_settle(12, 12, 0.1)).string(), sets);
  dem::Simulation a(c.model);
  for (int k = 0; k < 10000; ++k) a.step();
  const auto before = a.contacts();
  REQUIRE(before.size() > 100);
  // b: the same state, then renumbered by a random permutation (every pair's sides swap with
  // probability ½), as a checkpoint's order would be restored.
  dem::Simulation b = a;
  const std::vector<std::uint32_t> ids = shuffled(a.model().elements.size(), 11);
  b.restore_order(ids);
  REQUIRE(b.reordered());
  for (std::size_t k = 0; k < ids.size(); ++k) REQUIRE(b.model().elements.id[k] == ids[k]);
  // Right after the renumbering: the same contacts, keyed by id, same forces and normals, bit for bit.
  const auto mapped = dem::contacts_in_id_order(b);
  REQUIRE(mapped.size() == before.size());
  int turned = 0, turned_rolling = 0;
  for (std::size_t k = 0; k < before.size(); ++k) {
    CAPTURE(k);
    const auto& x = before[k];
    const auto& y = mapped[k];
    REQUIRE(b.id_of(y.i) == x.i);
    REQUIRE((y.wall ? y.j : b.id_of(y.j)) == x.j);
    REQUIRE(y.wall == x.wall);
    CHECK(y.fn == x.fn);
    CHECK(y.fs == x.fs);
    CHECK(y.nx == x.nx);
    CHECK(y.ny == x.ny);
    CHECK(y.mr == x.mr);
    turned += !x.wall && y.i > y.j;  // b keeps this pair as (j, i)
    turned_rolling += !x.wall && y.i > y.j && x.mr != 0.0;
  }
  CHECK(turned > 20);  // the test covered pairs whose sides swapped
  if (rolling) CHECK(turned_rolling > 20);  // and rolling moments among them
  // Stepping on: both runs agree element by element (by id) within round-off growth. A history lost or
  // given to the wrong pair changes the shear force by up to μ f_n at once: far above this.
  for (int k = 0; k < 500; ++k) a.step(), b.step();
  double worst = 0.0, fworst = 0.0, fscale = 0.0;
  const dem::Elements& ea = a.model().elements;
  const dem::Elements& eb = b.model().elements;
  for (std::uint32_t id = 0; id < ea.size(); ++id) {
    const std::size_t j = b.index_of(id);
    worst = std::max({worst, std::abs(ea.x[id] - eb.x[j]), std::abs(ea.y[id] - eb.y[j])});
    fworst = std::max({fworst, std::abs(ea.fx[id] - eb.fx[j]), std::abs(ea.fy[id] - eb.fy[j])});
    fscale = std::max(fscale, std::hypot(ea.fx[id], ea.fy[id]) + ea.mass[id] * 9.81);
  }
  CAPTURE(worst, fworst, fscale);
  CHECK(worst < 1e-12 * 1e-3);    // positions: far below 10⁻¹² of a radius
  CHECK(fworst < 1e-9 * fscale);  // forces: round-off grown over 500 steps
}

TEST_CASE("With reorder_every the outputs keep the case's numbering bit for bit where no sum changes order",
          "[spatial_order][outputs]") {
  // Disks in free fall (no contact: every element's update is its own), numbered at random: every
  // output — the series with element probes, every VTK snapshot with its ids — is the same file with and
  // without reordering.
  std::string t = shuffled_settle(10, 10, 4e-3, "",
                                  "vtk = true\nvtk_every = 250\nevery = 50\nseries = [\"t\", \"e7.y\", \"e42.vy\", \"e99.x\", \"contacts\"]\n");
  // (not energy.*: a sum over all elements, taken in the arrays' order, differs at round-off)
  // lift every disk high above the floor: no contact for 4 ms
  const std::string path_off = test::write_temp("order_free_off.toml", t).string();
  std::vector<fs::path> outs;
  for (const char* every : {"0", "1"}) {
    const dem::Case c = dem::read_case(path_off, {std::string("numerics.reorder_every=") + every, "physics.gravity=[0.0, 9.81]"});
    dem::RunOptions o;
    o.out_dir = test::fresh_dir("dem2d_spatial_order", std::string("free_") + every);
    const dem::RunResult r = dem::run_case(c, o);
    REQUIRE(r.status == "completed");
    outs.push_back(o.out_dir);
  }
  auto body = [](const fs::path& f) {  // without the provenance line
    std::string s = test::slurp(f);
    return s.substr(s.find('\n') + 1);
  };
  CHECK(body(outs[0] / "series.csv") == body(outs[1] / "series.csv"));
  int files = 0;
  for (const auto& f : fs::directory_iterator(outs[0] / "vtk")) {
    ++files;
    CAPTURE(f.path().filename().string());
    CHECK(test::slurp(f.path()) == test::slurp(outs[1] / "vtk" / f.path().filename()));
  }
  CHECK(files >= 5);
}

TEST_CASE("A settle with reorder_every agrees with the run without it within round-off", "[spatial_order]") {
  // 400 disks numbered at random, 6000 steps (24 ms: the rows land, about 110 contacts). Reordering
  // changes the order of floating-point sums (which element is i, the order of each element's contacts),
  // so the runs part at round-off: measured 1e-15 relative on these statistics. Over such a short run
  // round-off has not yet been amplified by the packing's chaos, so 1e-10 (10⁵ times the measured
  // difference) is far below any physical change (a lost history changes them at once by 10⁻³ or more).
  // Longer runs part element by element; bench/journal.md ("Locality") gives the settle's statistics then.
  const auto path = test::write_temp("order_settle_on_off.toml", shuffled_settle(20, 20, 0.024));
  struct Stats {
    double contacts, kinetic, mean_y;
  };
  auto stats = [](const dem::Simulation& s) {
    const dem::Elements& e = s.model().elements;
    double y = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) y += e.y[i];
    return Stats{static_cast<double>(s.contact_count()), s.energies().kinetic, y / static_cast<double>(e.size())};
  };
  std::vector<Stats> st;
  std::vector<dem::Simulation> sims;
  for (const char* every : {"0", "1", "4"}) {
    const dem::Case c = dem::read_case(path, {std::string("numerics.reorder_every=") + every});
    dem::Simulation s(c.model);
    while (s.time() < 0.024 - 1e-9) s.step();
    st.push_back(stats(s));
    sims.push_back(std::move(s));
  }
  CHECK_FALSE(sims[0].reordered());
  CHECK(sims[1].reordered());
  CHECK(sims[1].rebuilds() == sims[0].rebuilds());  // the rebuild test does not depend on the order
  for (std::size_t k = 1; k < st.size(); ++k) {
    CAPTURE(k, st[0].contacts, st[k].contacts, st[0].kinetic, st[k].kinetic, st[0].mean_y, st[k].mean_y);
    CHECK(st[k].contacts == st[0].contacts);
    CHECK(st[k].mean_y == Approx(st[0].mean_y).epsilon(1e-10));
    CHECK(st[k].kinetic == Approx(st[0].kinetic).epsilon(1e-10));
  }
}

TEST_CASE("A restart of a reordered run continues bit for bit, on any number of threads", "[spatial_order][restart]") {
  const dem::Case c = dem::read_case(test::write_temp("order_restart.toml", shuffled_settle(12, 12, 0.012, "reorder_every = 2")));
  const auto a = test::fresh_dir("dem2d_spatial_order", "restart_a");
  dem::RunOptions oa;
  oa.out_dir = a;
  oa.checkpoint_at_end = true;
  REQUIRE(dem::run_case(c, oa).status == "completed");
  const auto b = test::fresh_dir("dem2d_spatial_order", "restart_b");
  dem::RunOptions ob;
  ob.out_dir = b;
  ob.interrupt_at_step = 1700;
  REQUIRE(dem::run_case(c, ob).status == "interrupted");
  {  // the checkpoint holds a reordered state (else this test would not test the order's restore)
    const dem::Checkpoint ck = dem::read_checkpoint(b / "checkpoint.bin");
    dem::Simulation s(dem::read_case(test::write_temp("order_restart.toml", shuffled_settle(12, 12, 0.012))).model);
    REQUIRE_NOTHROW(dem::restore_simulation(s, ck, true));
    CHECK(s.reordered());
  }
  for (int threads : {1, 3}) {
    const auto cdir = test::fresh_dir("dem2d_spatial_order", "restart_c" + std::to_string(threads));
    dem::RunOptions oc;
    oc.out_dir = cdir;
    oc.restart = b / "checkpoint.bin";
    oc.checkpoint_at_end = true;
    oc.threads = threads;
    oc.governed = false;
    oc.min_per_thread = 1;
    REQUIRE(dem::run_case(c, oc).status == "completed");
    const dem::Checkpoint fa = dem::read_checkpoint(a / "checkpoint.bin");
    const dem::Checkpoint fc = dem::read_checkpoint(cdir / "checkpoint.bin");
    CHECK(fa.state == fc.state);
    CHECK(fa.loop == fc.loop);
  }
}

TEST_CASE("The state of a reordered run is the same bit for bit on 1, 2 and 3 threads", "[spatial_order][threads]") {
  const dem::Case c = dem::read_case(test::write_temp("order_threads.toml", shuffled_settle(15, 15, 0.02, "reorder_every = 1")));
  std::vector<dem::Simulation> sims;
  for (int t = 1; t <= 3; ++t) {
    sims.emplace_back(c.model);
    sims.back().set_threads(t, 1);
  }
  for (int k = 1; k <= 3000; ++k) {
    for (auto& s : sims) s.step();
    if (k % 100 == 0) {
      CAPTURE(k);
      const std::string one = dem::simulation_state(sims[0]);
      REQUIRE(one == dem::simulation_state(sims[1]));
      REQUIRE(one == dem::simulation_state(sims[2]));
    }
  }
  CHECK(sims[0].reordered());
  CHECK(sims[0].contact_count() > 20);
}

TEST_CASE("Bad reorder_every gives file:line: key: what was expected", "[spatial_order][errors]") {
  const auto path = test::write_temp("order_bad.toml", shuffled_settle(3, 3, 1e-3, "reorder_every = -1"));
  const std::string msg = test::message_of<dem::CaseError>([&] { dem::read_case(path); });
  CHECK(msg.find("order_bad.toml:") != std::string::npos);
  CHECK(msg.find("reorder_every") != std::string::npos);
  const auto path2 = test::write_temp("order_bad2.toml", shuffled_settle(3, 3, 1e-3, "reorder_every = 1.5"));
  CHECK(test::message_of<dem::CaseError>([&] { dem::read_case(path2); }).find("reorder_every") != std::string::npos);
  // a face law: refused
  CHECK(test::message_of<dem::CaseError>([&] {
          dem::read_case(test::source("cases/pre/small_rotation.toml"), {"numerics.reorder_every=1"});
        }).find("reorder_every: spatial reordering needs linear contact laws only") != std::string::npos);
}
