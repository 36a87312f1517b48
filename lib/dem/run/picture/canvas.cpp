#include "dem/run/picture/canvas.hpp"

#include <algorithm>
#include <cmath>

namespace dem {

namespace {

/// The 5 × 7 font: per character, 7 rows of 5 pixels ('#' ink).
struct Glyph {
  char c;
  const char* rows;  // 35 characters
};
constexpr Glyph kFont[] = {
    {'0', ".###.#...##..###.#.###..##...#.###."},
    {'1', "..#...##....#....#....#....#...###."},
    {'2', ".###.#...#....#...#...#...#...#####"},
    {'3', "####.....#....#.###.....#....#####."},
    {'4', "...#...##..#.#.#..#.#####...#....#."},
    {'5', "######....####.....#....##...#.###."},
    {'6', "..##..#...#....####.#...##...#.###."},
    {'7', "#####....#...#...#...#....#....#..."},
    {'8', ".###.#...##...#.###.#...##...#.###."},
    {'9', ".###.#...##...#.####....#...#..##.."},
    {'.', "..........................##...##.."},
    {'-', "...............#####..............."},
    {'+', ".......#....#..#####..#....#......."},
    {'=', "..........#####.....#####.........."},
    {'|', "..#....#....#....#....#....#....#.."},
    {'/', "....#....#...#...#...#...#....#...."},
    {':', "......##...##........##...##......."},
    {' ', "..................................."},
    {'a', "...........###.....#.#####...#.####"},
    {'c', "...........###.#....#....#...#.###."},
    {'d', "....#....#.##.##..###...##...#.####"},
    {'e', "...........###.#...#######.....###."},
    {'f', "..##..#..#.#...###...#....#....#..."},
    {'h', "#....#....#.##.##..##...##...##...#"},
    {'i', "..#........##....#....#....#...###."},
    {'l', ".##....#....#....#....#....#...###."},
    {'m', "..........##.#.#.#.##.#.##...##...#"},
    {'n', "..........#.##.##..##...##...##...#"},
    {'o', "...........###.#...##...##...#.###."},
    {'p', "..........####.#...##...#####.#...."},
    {'r', "..........#.##.##..##....#....#...."},
    {'s', "...........###.#.....###.....#####."},
    {'t', ".#....#...###...#....#....#..#..##."},
    {'w', "..........#...##...##.#.##.#.#.#.#."},
    {'x', "..........#...#.#.#...#...#.#.#...#"},
    {'N', "#...##...###..##.#.##..###...##...#"},
    {'(', "...#...#...#....#....#.....#.....#."},
    {')', ".#.....#.....#....#....#...#...#..."},
    {'k', "#....#....#..#.#.#..##...#.#..#..#."},
    {'g', "...........#####...#.####....#.###."},
    {'u', "..........#...##...##...##..##.##.#"},
    {'b', "#....#....#.##.##..##...##...#####."},
    {',', ".....................##....#...#..."},
    {'y', "..........#...##...#.####....#.###."},
    {'v', "..........#...##...##...#.#.#...#.."},
    {'>', ".#.....#.....#.....#...#...#...#..."},
};

const char* glyph(char c) {
  for (const auto& g : kFont)
    if (g.c == c) return g.rows;
  return nullptr;
}

double clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

/// Distance from p to the segment a–b.
double segment_distance(double px, double py, double ax, double ay, double bx, double by) {
  const double ux = bx - ax, uy = by - ay, len2 = ux * ux + uy * uy;
  double s = len2 > 0.0 ? ((px - ax) * ux + (py - ay) * uy) / len2 : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  return std::hypot(px - (ax + s * ux), py - (ay + s * uy));
}

}  // namespace

Canvas::Canvas(int width, int height, Rgb background)
    : w_(width), h_(height), px_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
  for (std::size_t k = 0; k < px_.size(); k += 3) {
    px_[k] = background.r;
    px_[k + 1] = background.g;
    px_[k + 2] = background.b;
  }
}

Rgb Canvas::at(int x, int y) const {
  const std::size_t k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)) * 3;
  return {px_[k], px_[k + 1], px_[k + 2]};
}

void Canvas::blend(int x, int y, Rgb c, double coverage) {
  if (x < 0 || y < 0 || x >= w_ || y >= h_ || coverage <= 0.0) return;
  const double a = clamp01(coverage);
  const std::size_t k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)) * 3;
  const std::uint8_t src[3] = {c.r, c.g, c.b};
  for (int q = 0; q < 3; ++q) px_[k + q] = static_cast<std::uint8_t>(std::lround(px_[k + q] + a * (src[q] - px_[k + q])));
}

void Canvas::line(double x0, double y0, double x1, double y1, double width, Rgb c) {
  const double opacity = width < 1.0 ? std::max(width, 0.0) : 1.0;
  const double half = std::max(width, 1.0) / 2.0;
  const int i0 = static_cast<int>(std::floor(std::min(x0, x1) - half - 1)), i1 = static_cast<int>(std::ceil(std::max(x0, x1) + half + 1));
  const int j0 = static_cast<int>(std::floor(std::min(y0, y1) - half - 1)), j1 = static_cast<int>(std::ceil(std::max(y0, y1) + half + 1));
  for (int j = std::max(j0, 0); j <= std::min(j1, h_ - 1); ++j)
    for (int i = std::max(i0, 0); i <= std::min(i1, w_ - 1); ++i) {
      const double d = segment_distance(i + 0.5, j + 0.5, x0, y0, x1, y1);
      blend(i, j, c, opacity * clamp01(half + 0.5 - d));
    }
}

void Canvas::disk(double cx, double cy, double r, Rgb c) {
  const int i0 = static_cast<int>(std::floor(cx - r - 1)), i1 = static_cast<int>(std::ceil(cx + r + 1));
  const int j0 = static_cast<int>(std::floor(cy - r - 1)), j1 = static_cast<int>(std::ceil(cy + r + 1));
  for (int j = std::max(j0, 0); j <= std::min(j1, h_ - 1); ++j)
    for (int i = std::max(i0, 0); i <= std::min(i1, w_ - 1); ++i)
      blend(i, j, c, clamp01(r + 0.5 - std::hypot(i + 0.5 - cx, j + 0.5 - cy)));
}

void Canvas::ring(double cx, double cy, double r, double width, Rgb c) {
  const double half = std::max(width, 1.0) / 2.0, opacity = width < 1.0 ? std::max(width, 0.0) : 1.0;
  const int i0 = static_cast<int>(std::floor(cx - r - half - 1)), i1 = static_cast<int>(std::ceil(cx + r + half + 1));
  const int j0 = static_cast<int>(std::floor(cy - r - half - 1)), j1 = static_cast<int>(std::ceil(cy + r + half + 1));
  for (int j = std::max(j0, 0); j <= std::min(j1, h_ - 1); ++j)
    for (int i = std::max(i0, 0); i <= std::min(i1, w_ - 1); ++i)
      blend(i, j, c, opacity * clamp01(half + 0.5 - std::abs(std::hypot(i + 0.5 - cx, j + 0.5 - cy) - r)));
}

void Canvas::polygon(const std::array<double, 8>& xy, Rgb fill, Rgb edge, double edge_width) {
  polygon(std::vector<double>(xy.begin(), xy.end()), fill, edge, edge_width);
}

void Canvas::polygon(const std::vector<double>& xy, Rgb fill, Rgb edge, double edge_width) {
  // Fill: coverage from the signed distance to the convex outline (inside: every edge on one side).
  const int nc = static_cast<int>(xy.size() / 2);
  if (nc < 3) return;
  double xmin = xy[0], xmax = xy[0], ymin = xy[1], ymax = xy[1];
  for (int k = 1; k < nc; ++k) {
    xmin = std::min(xmin, xy[2 * k]), xmax = std::max(xmax, xy[2 * k]);
    ymin = std::min(ymin, xy[2 * k + 1]), ymax = std::max(ymax, xy[2 * k + 1]);
  }
  double area2 = 0.0;  // orientation of the corners
  for (int k = 0; k < nc; ++k) {
    const int n = (k + 1) % nc;
    area2 += xy[2 * k] * xy[2 * n + 1] - xy[2 * n] * xy[2 * k + 1];
  }
  const double sign = area2 >= 0.0 ? 1.0 : -1.0;
  for (int j = std::max(static_cast<int>(ymin) - 1, 0); j <= std::min(static_cast<int>(ymax) + 1, h_ - 1); ++j)
    for (int i = std::max(static_cast<int>(xmin) - 1, 0); i <= std::min(static_cast<int>(xmax) + 1, w_ - 1); ++i) {
      double inside = 1e300;  // distance to the nearest edge line, negative outside
      for (int k = 0; k < nc; ++k) {
        const int n = (k + 1) % nc;
        const double ex = xy[2 * n] - xy[2 * k], ey = xy[2 * n + 1] - xy[2 * k + 1], len = std::hypot(ex, ey);
        if (len == 0.0) continue;
        inside = std::min(inside, sign * (ex * (j + 0.5 - xy[2 * k + 1]) - ey * (i + 0.5 - xy[2 * k])) / len);
      }
      blend(i, j, fill, clamp01(inside + 0.5));
    }
  for (int k = 0; k < nc; ++k) {
    const int n = (k + 1) % nc;
    line(xy[2 * k], xy[2 * k + 1], xy[2 * n], xy[2 * n + 1], edge_width, edge);
  }
}

int Canvas::text(int x, int y, std::string_view s, int scale, Rgb c) {
  for (char ch : s) {
    const char* g = glyph(ch);
    for (int r = 0; r < 7; ++r)
      for (int q = 0; q < 5; ++q) {
        const bool ink = g ? g[r * 5 + q] == '#' : (r == 0 || r == 6 || q == 0 || q == 4);
        if (!ink) continue;
        for (int dy = 0; dy < scale; ++dy)
          for (int dx = 0; dx < scale; ++dx) blend(x + q * scale + dx, y + r * scale + dy, c, 1.0);
      }
    x += 6 * scale;
  }
  return x;
}

}  // namespace dem
