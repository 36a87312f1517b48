#pragma once
// A prescribed velocity history (walls, driven elements): piecewise linear in time between the
// given points, constant before the first and after the last.
#include <vector>

#include "dem/core/vec2.hpp"

namespace dem {

struct VelocityHistory {
  std::vector<double> t;  // [s], strictly increasing
  std::vector<Vec2> v;    // [m/s]

  Vec2 at(double time) const {
    if (t.empty()) return {};
    if (time <= t.front()) return v.front();
    if (time >= t.back()) return v.back();
    std::size_t k = 1;
    while (t[k] < time) ++k;
    const double s = (time - t[k - 1]) / (t[k] - t[k - 1]);
    return v[k - 1] * (1.0 - s) + v[k] * s;
  }
};

}  // namespace dem
