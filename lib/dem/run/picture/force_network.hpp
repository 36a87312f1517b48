#pragma once
// Contact-force network pictures (PNG) like Kiyama & Fujimura's Fig. 6, 8 and 9: disks drawn as
// circles, PREs as their rotated squares (side 2r), segment walls as thick lines and point walls as
// dots, and one line per contact between the centres (element centre to the contact point r·n for a
// wall contact) whose width is proportional to |f_n|: the largest |f_n| of the picture (or the stated
// `max_force`) is drawn `max_line` pixels wide; compression black, tension red. A legend strip below
// the scene states the time, the step and the scale. Removed (inactive) elements are not drawn.
#include <filesystem>
#include <optional>
#include <vector>

#include "dem/core/simulation.hpp"
#include "dem/core/vec2.hpp"
#include "dem/run/picture/canvas.hpp"

namespace dem {

struct PictureOptions {
  int width = 800;                  // image width [px]; the height follows the scene's aspect
  std::optional<double> max_force;  // |f_n| drawn max_line wide [N]; none: the picture's largest
  double max_line = 0.0;            // width of the largest force line [px]; 0: 0.6 × smallest radius
  std::vector<Vec2> broken_bonds;   // where bonded links broke so far [m] (output.bond_breaks): drawn as ×
};

/// World (m, y up) to pixels (y down) for the scene part of the picture.
struct PictureFrame {
  double x0 = 0.0, y1 = 0.0;  // world left edge and top edge [m]
  double scale = 1.0;         // px per m
  int width = 0, scene_height = 0;
  int legend_height = 0;  // set by draw_force_network (the legend's sample band is as tall as the widest line)
  Vec2 to_px(Vec2 p) const { return {(p.x - x0) * scale, (y1 - p.y) * scale}; }
};

/// The frame of the scene: the active elements' extent and the walls' (walls reaching far beyond the
/// elements are cut at one element extent around them), with a margin.
PictureFrame picture_frame(const Simulation& sim, const PictureOptions& o);

/// The picture as pixels, and the width [px] given to the largest force.
struct ForcePicture {
  Canvas canvas;
  PictureFrame frame;
  double max_force = 0.0, max_line = 0.0;
};
ForcePicture draw_force_network(const Simulation& sim, const PictureOptions& o);

/// Draws and writes the PNG (write-then-rename; OutputError on failure).
void write_force_network_png(const std::filesystem::path& file, const Simulation& sim, const PictureOptions& o);

}  // namespace dem
