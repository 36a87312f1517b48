#pragma once
// A tiny rasteriser for the force-network pictures: an RGB canvas with antialiased thick lines, disks,
// rings and polygon outlines (coverage from the exact distance to the shape, one pixel of ramp), and
// a 5 × 7 pixel font for the legend. Pixel coordinates: x to the right, y downwards, pixel (i, j)
// covering [i, i+1) × [j, j+1), its centre at (i + 0.5, j + 0.5).
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace dem {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

class Canvas {
 public:
  Canvas(int width, int height, Rgb background);
  int width() const { return w_; }
  int height() const { return h_; }
  const std::vector<std::uint8_t>& pixels() const { return px_; }  // 3 bytes per pixel, rows top down
  Rgb at(int x, int y) const;

  /// A line of the given width [px] with round caps from (x0, y0) to (x1, y1); a width below one pixel
  /// is drawn one pixel wide with the colour's opacity scaled by the width (the ink stays proportional).
  void line(double x0, double y0, double x1, double y1, double width, Rgb c);
  /// A filled disk and a ring (circle outline of the given width, centred on the radius).
  void disk(double cx, double cy, double r, Rgb c);
  void ring(double cx, double cy, double r, double width, Rgb c);
  /// A filled convex polygon (corners in order) and its outline.
  void polygon(const std::array<double, 8>& xy, Rgb fill, Rgb edge, double edge_width);
  /// The same for any convex outline, corners (x0, y0, x1, y1, …) in either order.
  void polygon(const std::vector<double>& xy, Rgb fill, Rgb edge, double edge_width);
  /// Text in the 5 × 7 font scaled by `scale` (integer pixels per font pixel), top-left at (x, y).
  /// Characters outside the font draw as a box. Returns the x after the text.
  int text(int x, int y, std::string_view s, int scale, Rgb c);

 private:
  void blend(int x, int y, Rgb c, double coverage);
  int w_, h_;
  std::vector<std::uint8_t> px_;
};

}  // namespace dem
