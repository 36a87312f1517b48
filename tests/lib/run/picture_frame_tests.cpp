// The frame of a force-network picture (lib/dem/run/picture/force_network.hpp, picture_frame) holds every
// active element whole: each disk (and each PRE's circumscribed circle, r√2) lies inside the scene in pixels,
// whichever element is the leftmost, rightmost, lowest or highest. Two sets: a row of disks of growing
// radius, and the same with a PRE last. Planted bug that turned this red (g578749-021): the extent taken
// from element i + 1's x (the first element left out, the last read past the array).
#include <catch2/catch.hpp>

#include <cmath>

#include "dem/core/simulation.hpp"
#include "dem/run/picture/force_network.hpp"
#include "../test_support.hpp"

TEST_CASE("The picture frame holds every active element whole", "[picture]") {
  for (const bool pre_last : {false, true}) {
    CAPTURE(pre_last);
    auto m = test::make_model({{"sand", 2650.0}}, 1e-5);
    const double xs[4] = {-0.3, 0.05, 0.2, 0.9}, ys[4] = {0.1, -0.2, 0.4, 0.0}, rs[4] = {0.01, 0.02, 0.03, 0.05};
    for (int k = 0; k < 4; ++k)
      dem::add_element(m, pre_last && k == 3 ? dem::Shape::pre : dem::Shape::disk, 0, rs[k], {xs[k], ys[k]});
    dem::Simulation sim(m);
    const dem::PictureFrame f = dem::picture_frame(sim, {});
    for (int k = 0; k < 4; ++k) {
      CAPTURE(k);
      const double r = (pre_last && k == 3 ? std::sqrt(2.0) : 1.0) * rs[k];
      const dem::Vec2 lo = f.to_px({xs[k] - r, ys[k] + r}), hi = f.to_px({xs[k] + r, ys[k] - r});
      CHECK(lo.x >= 0.0);
      CHECK(lo.y >= 0.0);
      CHECK(hi.x <= f.width);
      CHECK(hi.y <= f.scene_height);
    }
  }
}
