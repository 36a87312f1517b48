#include "dem/run/picture/force_network.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "dem/core/spatial_order.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/picture/png.hpp"

namespace dem {

namespace {

constexpr Rgb kBackground{255, 255, 255}, kElementFill{226, 226, 226}, kElementEdge{120, 120, 120},
    kWall{30, 60, 150}, kCompression{0, 0, 0}, kTension{210, 30, 30}, kText{0, 0, 0}, kLegendBack{245, 245, 245},
    kBroken{230, 120, 0};

constexpr std::size_t kRobustFrom = 20;  // contacts needed for a percentile scale

struct Box {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  void add(double x, double y, double r = 0.0) {
    x0 = std::min(x0, x - r), x1 = std::max(x1, x + r), y0 = std::min(y0, y - r), y1 = std::max(y1, y + r);
  }
  bool empty() const { return !(x1 >= x0 && y1 >= y0); }
};

int legend_scale(int width) { return width >= 600 ? 2 : 1; }

}  // namespace

PictureFrame picture_frame(const Simulation& sim, const PictureOptions& o) {
  const Elements& e = sim.model().elements;
  Box el, all;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i]) el.add(e.x[i], e.y[i], e.shape[i] == Shape::pre ? e.radius[i] * std::sqrt(2.0) : e.radius[i]);  // (polygon: circumradius)
  Box walls;
  for (const Wall& w : sim.model().walls) {
    walls.add(w.a.x, w.a.y);
    if (w.kind == WallKind::segment) walls.add(w.b.x, w.b.y);
  }
  if (el.empty()) all = walls;
  else {
    all = el;
    if (!walls.empty()) {  // walls count up to one element extent beyond the elements
      const double wx = std::max(el.x1 - el.x0, 1e-12), wy = std::max(el.y1 - el.y0, 1e-12);
      all.x0 = std::min(all.x0, std::max(walls.x0, el.x0 - wx)), all.x1 = std::max(all.x1, std::min(walls.x1, el.x1 + wx));
      all.y0 = std::min(all.y0, std::max(walls.y0, el.y0 - wy)), all.y1 = std::max(all.y1, std::min(walls.y1, el.y1 + wy));
    }
  }
  if (all.empty()) all.add(0.0, 0.0, 1.0);
  double w = all.x1 - all.x0, h = all.y1 - all.y0;
  const double size = std::max({w, h, 1e-9});
  w = std::max(w, 0.05 * size), h = std::max(h, 0.05 * size);
  const double margin = 0.03 * std::max(w, h);
  PictureFrame f;
  f.width = o.width;
  f.scale = o.width / (w + 2 * margin);
  f.x0 = all.x0 - margin - 0.5 * (w - (all.x1 - all.x0));
  f.y1 = all.y1 + margin + 0.5 * (h - (all.y1 - all.y0));
  f.scene_height = std::clamp(static_cast<int>(std::ceil((h + 2 * margin) * f.scale)), 1, 4 * o.width);
  return f;
}

ForcePicture draw_force_network(const Simulation& sim, const PictureOptions& o) {
  const Elements& e = sim.model().elements;
  PictureFrame f = picture_frame(sim, o);
  double r_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i]) r_min = std::min(r_min, e.radius[i]);
  const auto contacts = contacts_in_id_order(sim);  // drawn in the same order with spatial reordering
  // The scale: a fixed max_force, else the 99th percentile of |f_n| over the drawn contacts (with fewer than
  // kRobustFrom of them, the largest): a single impact far above the rest must not make the network
  // invisible; lines above the scale are drawn at most 1.5 × max_line, and the legend says which.
  std::vector<double> drawn;
  for (const auto& c : contacts)
    if (e.active[c.i] && (c.wall || e.active[c.j]) && c.fn != 0.0) drawn.push_back(std::abs(c.fn));
  const bool robust = !o.max_force && drawn.size() >= kRobustFrom;
  double fscale = 0.0;
  if (robust) {
    const auto k = static_cast<std::ptrdiff_t>(std::ceil(0.99 * static_cast<double>(drawn.size()))) - 1;
    std::nth_element(drawn.begin(), drawn.begin() + k, drawn.end());
    fscale = drawn[static_cast<std::size_t>(k)];
  } else {
    for (const double f : drawn) fscale = std::max(fscale, f);
  }
  const double max_force = o.max_force ? *o.max_force : fscale;
  const double max_line =
      o.max_line > 0.0 ? o.max_line : std::clamp(0.6 * (std::isfinite(r_min) ? r_min * f.scale : 10.0), 1.0, 30.0);
  // Legend: three rows, the middle one tall enough for the sample line.
  const int s = legend_scale(f.width), line_h = 10 * s;
  const int sample_h = std::max(line_h, static_cast<int>(std::ceil(std::min(max_line, 1.5 * max_line))) + 4 * s);
  f.legend_height = 2 * line_h + sample_h + 4 * s;
  ForcePicture pic{Canvas(f.width, f.scene_height + f.legend_height, kBackground), f, max_force, max_line};
  Canvas& cv = pic.canvas;
  // Elements, in the order of their ids (spatial_order.hpp).
  for (std::size_t id = 0; id < e.size(); ++id) {
    const std::size_t i = sim.index_of(static_cast<std::uint32_t>(id));
    if (!e.active[i]) continue;
    const Vec2 c = f.to_px({e.x[i], e.y[i]});
    const double r = e.radius[i] * f.scale;
    if (e.shape[i] == Shape::pre) {  // the square of side 2r, turned by φ (y flips in pixels)
      const double cs = std::cos(e.phi[i]), sn = std::sin(e.phi[i]);
      std::array<double, 8> xy{};
      const double corners[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
      for (int k = 0; k < 4; ++k) {
        const double u = corners[k][0] * e.radius[i], v = corners[k][1] * e.radius[i];
        const Vec2 p = f.to_px({e.x[i] + cs * u - sn * v, e.y[i] + sn * u + cs * v});
        xy[2 * k] = p.x, xy[2 * k + 1] = p.y;
      }
      cv.polygon(xy, kElementFill, kElementEdge, 1.0);
    } else if (e.shape[i] == Shape::polygon) {  // its corners (P3)
      std::vector<double> xy;
      for (const Vec2& q : element_corners(sim.model(), i)) {
        const Vec2 p = f.to_px(q);
        xy.push_back(p.x), xy.push_back(p.y);
      }
      cv.polygon(xy, kElementFill, kElementEdge, 1.0);
    } else {
      cv.disk(c.x, c.y, r, kElementFill);
      cv.ring(c.x, c.y, r - 0.5, 1.0, kElementEdge);
    }
  }
  // Walls.
  const double wall_width = std::clamp(0.25 * (std::isfinite(r_min) ? r_min * f.scale : 8.0), 2.0, 8.0);
  for (const Wall& w : sim.model().walls) {
    if (w.open) continue;  // an opened gate (a silo's slit in discharge) is not drawn
    const Vec2 a = f.to_px(w.a);
    if (w.kind == WallKind::point) cv.disk(a.x, a.y, 0.8 * wall_width + 1.0, kWall);
    else {
      const Vec2 b = f.to_px(w.b);
      cv.line(a.x, a.y, b.x, b.y, wall_width, kWall);
    }
  }
  // Contact lines, width ∝ |f_n| (a fixed max_force: lines of larger forces are drawn at most 1.5 ×).
  for (const auto& c : contacts) {
    if (!e.active[c.i] || (!c.wall && !e.active[c.j])) continue;
    if (!(max_force > 0.0) || c.fn == 0.0) continue;
    const double width = max_line * std::min(std::abs(c.fn) / max_force, 1.5);
    const Vec2 a = f.to_px({e.x[c.i], e.y[c.i]});
    Vec2 b = c.wall ? (c.at_point ? f.to_px({c.px, c.py}) : f.to_px({e.x[c.i] + e.radius[c.i] * c.nx, e.y[c.i] + e.radius[c.i] * c.ny}))
                    : f.to_px({e.x[c.j], e.y[c.j]});
    if (c.wall) {  // the round cap ends on the wall, not beyond it
      const double len = std::hypot(b.x - a.x, b.y - a.y), back = std::min(0.5 * width, 0.5 * len);
      if (len > 0.0) b = {b.x - (b.x - a.x) * back / len, b.y - (b.y - a.y) * back / len};
    }
    cv.line(a.x, a.y, b.x, b.y, width, c.fn > 0.0 ? kCompression : kTension);
  }
  // Broken bonds (the crack pattern): a × at each link that broke, over everything else.
  const double arm = std::clamp(0.25 * (std::isfinite(r_min) ? r_min * f.scale : 8.0), 2.0, 10.0);
  for (const Vec2& p : o.broken_bonds) {
    const Vec2 q = f.to_px(p);
    cv.line(q.x - arm, q.y - arm, q.x + arm, q.y + arm, 1.5, kBroken);
    cv.line(q.x - arm, q.y + arm, q.x + arm, q.y - arm, 1.5, kBroken);
  }
  // Legend strip.
  const int y0 = f.scene_height;
  for (int y = y0; y < cv.height(); ++y) cv.line(0, y + 0.5, f.width, y + 0.5, 1.0, kLegendBack);
  const int x = 4 * s;
  cv.text(x, y0 + 2 * s, fmt::format("t = {:.6g} s, step {}", sim.time(), sim.steps()), s, kText);
  const double mid = y0 + 2 * s + line_h + 0.5 * sample_h;
  const double cap = 0.5 * std::max(max_line, 1.0);  // round caps reach half the width beyond the ends
  cv.line(x + cap, mid, x + cap + 24 * s, mid, max_line, kCompression);
  cv.text(static_cast<int>(x + 2 * cap + 24 * s + 6 * s), static_cast<int>(mid) - 4 * s,
          fmt::format("|fn| = {:.4g} N ({}) is {:.3g} px wide, width prop. to |fn|", max_force,
                      o.max_force ? "fixed" : robust ? "99th percentile" : "max", max_line),
          s, kText);
  const int yb = y0 + 2 * s + line_h + sample_h;
  const int after = cv.text(x, yb, "compression", s, kCompression);
  const int after_tension = cv.text(cv.text(after, yb, ", ", s, kText), yb, "tension", s, kTension);
  if (!o.broken_bonds.empty())
    cv.text(cv.text(after_tension, yb, ", ", s, kText), yb, fmt::format("x {} broken bond{}", o.broken_bonds.size(), o.broken_bonds.size() == 1 ? "" : "s"), s, kBroken);
  return pic;
}

void write_force_network_png(const std::filesystem::path& file, const Simulation& sim, const PictureOptions& o) {
  const ForcePicture pic = draw_force_network(sim, o);
  write_file_atomic(file, encode_png(pic.canvas.width(), pic.canvas.height(), pic.canvas.pixels()), false);
}

}  // namespace dem
