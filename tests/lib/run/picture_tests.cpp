// Contact-force network pictures (lib/dem/run/picture/): the PNG encoder (signature, chunk CRCs, the
// pixels back through zlib's inflate), the rasteriser on a known scene (a contact line where the
// contact is, its width proportional to the normal force, removed elements not drawn), the [output]
// keys (units, file:line: key: errors) and the pictures a run writes (no stale ones, at the steps of
// the chosen times).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <zlib.h>

#include <optional>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/picture/force_network.hpp"
#include "dem/run/picture/png.hpp"
#include "dem/run/run.hpp"

#include "../test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

std::uint32_t be32(const std::string& s, std::size_t at) {
  return (std::uint32_t(std::uint8_t(s[at])) << 24) | (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
         (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
}

struct Decoded {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  std::vector<std::string> chunks;
};

/// A minimal PNG reader for what encode_png writes (8-bit RGB, filter 0): checks every CRC.
Decoded decode_png(const std::string& png) {
  Decoded d;
  REQUIRE(png.size() > 8);
  REQUIRE(png.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) == 0);
  std::string idat;
  for (std::size_t at = 8; at < png.size();) {
    REQUIRE(at + 12 <= png.size());
    const std::uint32_t len = be32(png, at);
    const std::string type = png.substr(at + 4, 4);
    REQUIRE(at + 12 + len <= png.size());
    const auto* p = reinterpret_cast<const Bytef*>(png.data() + at + 4);
    CHECK(be32(png, at + 8 + len) == crc32(crc32(0L, Z_NULL, 0), p, len + 4));
    d.chunks.push_back(type);
    if (type == "IHDR") {
      d.width = static_cast<int>(be32(png, at + 8));
      d.height = static_cast<int>(be32(png, at + 12));
      CHECK(png.substr(at + 16, 5) == std::string("\x08\x02\x00\x00\x00", 5));
    }
    if (type == "IDAT") idat += png.substr(at + 8, len);
    at += 12 + len;
  }
  const std::size_t row = static_cast<std::size_t>(d.width) * 3;
  std::string raw((row + 1) * static_cast<std::size_t>(d.height), '\0');
  uLongf n = raw.size();
  REQUIRE(uncompress(reinterpret_cast<Bytef*>(raw.data()), &n, reinterpret_cast<const Bytef*>(idat.data()),
                     static_cast<uLong>(idat.size())) == Z_OK);
  REQUIRE(n == raw.size());
  for (int y = 0; y < d.height; ++y) {
    CHECK(raw[static_cast<std::size_t>(y) * (row + 1)] == '\0');
    d.rgb.insert(d.rgb.end(), raw.begin() + static_cast<std::ptrdiff_t>(y * (row + 1) + 1),
                 raw.begin() + static_cast<std::ptrdiff_t>((y + 1) * (row + 1)));
  }
  return d;
}

/// Three disks of r = 1 cm in a row, no gravity: A–B overlap 0.2 mm, B–C 0.1 mm (f_n of B–C half of
/// A–B's); a floor wall far below them.
std::string row_case(const std::string& output) {
  return R"([case]
title = "three disks in a row"
[physics]
gravity = ["0 m/s^2", "0 m/s^2"]
[[material]]
name = "sand"
density = "2650 kg/m^3"
[[material]]
name = "steel"
[[contact]]
between = ["sand", "sand"]
law = "linear"
kn = "1e5 N/m"
ks_ratio = 0.25
friction = 0.5
damping_ratio = 0.0
[[contact]]
between = ["sand", "steel"]
law = "linear"
kn = "1e5 N/m"
ks_ratio = 0.25
friction = 0.5
damping_ratio = 0.0
[[element]]
material = "sand"
radius = "1 cm"
position = ["0 cm", "0 cm"]
[[element]]
material = "sand"
radius = "1 cm"
position = ["1.98 cm", "0 cm"]
[[element]]
material = "sand"
radius = "1 cm"
position = ["3.97 cm", "0 cm"]
[[wall]]
name = "floor"
from = ["-1 cm", "-3 cm"]
to = ["5 cm", "-3 cm"]
material = "steel"
[numerics]
dt = "1e-6 s"
duration = "10 us"
)" + output;
}

/// The three-disk row of row_case as a model, written to `file` and read back.
dem::Model row_model(const std::string& file) { return dem::read_case(test::write_temp(file, row_case(""))).model; }

/// Dark (contact-line) pixels in the pixel column x between rows y0 and y1.
int dark_in_column(const dem::Canvas& cv, int x, int y0, int y1) {
  int n = 0;
  for (int y = std::max(y0, 0); y < std::min(y1, cv.height()); ++y) n += cv.at(x, y).r < 60;
  return n;
}

}  // namespace

TEST_CASE("png: signature, chunk CRCs and the pixels back through inflate", "[picture]") {
  const int w = 7, h = 3;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w * h * 3));
  for (std::size_t k = 0; k < rgb.size(); ++k) rgb[k] = static_cast<std::uint8_t>((k * 37 + 11) % 256);
  const std::string png = dem::encode_png(w, h, rgb);
  const Decoded d = decode_png(png);
  CHECK(d.chunks == std::vector<std::string>{"IHDR", "IDAT", "IEND"});
  CHECK(d.width == w);
  CHECK(d.height == h);
  CHECK(d.rgb == rgb);
  // A corrupted byte is caught by the CRC (the decoder above is able to fail).
  std::string bad = png;
  bad[20] = static_cast<char>(bad[20] ^ 1);  // inside IHDR's data
  CHECK(be32(bad, 8 + 8 + 13) != crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bad.data() + 12), 17));
  CHECK_THROWS(dem::encode_png(w, h, std::vector<std::uint8_t>(5)));
}

TEST_CASE("picture: a contact line lies between the centres, its width proportional to f_n", "[picture]") {
  dem::Simulation sim(row_model("picture_row.toml"));
  sim.step();
  const auto ab = sim.contact(0, 1, false), bc = sim.contact(1, 2, false);
  REQUIRE(ab.fn > 0.0);
  REQUIRE(bc.fn == Approx(0.5 * ab.fn).epsilon(0.02));
  dem::PictureOptions o;
  o.width = 800;
  o.max_line = 12.0;
  const dem::ForcePicture pic = dem::draw_force_network(sim, o);
  CHECK(pic.max_force == Approx(ab.fn));
  const dem::Vec2 a = pic.frame.to_px({0.0, 0.0}), b = pic.frame.to_px({0.0198, 0.0}), cc = pic.frame.to_px({0.0397, 0.0});
  // Between the centres, away from the contact point (where the outlines cross): black line pixels.
  const int x_ab = static_cast<int>(0.75 * a.x + 0.25 * b.x), x_bc = static_cast<int>(0.75 * b.x + 0.25 * cc.x);
  const int y = static_cast<int>(a.y);
  const auto black = pic.canvas.at(x_ab, y);
  CHECK(black.r == 0);
  CHECK(black.g == 0);
  // Off the line (a third of a radius above): the element fill, not the line.
  const double r_px = 0.01 * pic.frame.scale;
  const dem::Rgb fill = pic.canvas.at(x_ab, static_cast<int>(a.y - r_px / 3));
  CHECK(fill.r > 200);
  CHECK(fill.r < 255);  // grey: neither the background nor a colour
  CHECK(fill.g == fill.r);
  CHECK(fill.b == fill.r);
  // Widths: 12 px for the largest force, 6 px for half of it (antialiased edges: ±1 px).
  const int w_ab = dark_in_column(pic.canvas, x_ab, y - 40, y + 40), w_bc = dark_in_column(pic.canvas, x_bc, y - 40, y + 40);
  CHECK(w_ab == Approx(12).margin(1));
  CHECK(w_bc == Approx(6).margin(1));
  // The legend states the scale: a sample line max_line wide below the scene.
  CHECK(pic.canvas.height() > pic.frame.scene_height);
  // A stated max_force: the same forces drawn thinner.
  o.max_force = 2.0 * ab.fn;
  const dem::ForcePicture fixed = dem::draw_force_network(sim, o);
  CHECK(dark_in_column(fixed.canvas, x_ab, y - 40, y + 40) == Approx(6).margin(1));
}

TEST_CASE("picture: the legend's sample line stands clear of its label - which follows it on the same row", "[picture]") {
  dem::Simulation sim(row_model("picture_legend.toml"));
  sim.step();
  dem::PictureOptions o;
  o.width = 800;  // legend scale s = 2
  o.max_line = 12.0;
  const dem::ForcePicture pic = dem::draw_force_network(sim, o);
  // The legend under the scene: a text row (10 s px) 2 s below the scene, then the sample band: the
  // sample line, max_line wide from x = 4 s (its round caps included) over 24 s px plus the caps, its label
  // 6 s px after it, on the band's middle.
  const int s = 2, line_h = 10 * s, x = 4 * s;
  const double cap = 0.5 * std::max(pic.max_line, 1.0);
  const int sample_h = std::max(line_h, static_cast<int>(std::ceil(pic.max_line)) + 4 * s);
  const int top = pic.frame.scene_height + 2 * s + line_h, mid = top + sample_h / 2;
  const int line_end = static_cast<int>(std::ceil(x + 2 * cap + 24 * s));
  const auto dark = [&](int col, int row) { return pic.canvas.at(col, row).r < 160; };
  for (int col = static_cast<int>(x + cap); col <= static_cast<int>(x + cap + 24 * s); ++col) {
    CAPTURE(col);
    CHECK(dark(col, mid));  // the sample line
  }
  int before = 0, in_gap = 0, label = 0;
  for (int row = top; row < top + sample_h; ++row) {
    for (int col = 0; col < x - 1; ++col) before += dark(col, row);
    for (int col = line_end + 2; col < line_end + 5 * s; ++col) in_gap += dark(col, row);
    for (int col = line_end + 5 * s; col < line_end + 40 * s; ++col) label += dark(col, row);
  }
  CHECK(before == 0);  // nothing left of the line
  CHECK(in_gap == 0);  // a clear gap between the line and its label
  CHECK(label > 0);    // the label follows the gap
  // The label's ink (7 s rows of the font) is centred on the sample line, to a font pixel: rows from
  // the end of the first text row's ink (3 s above the band) to the band's end
  int first = -1, last = -1;
  for (int row = top - 3 * s; row < top + sample_h; ++row)
    for (int col = line_end + 5 * s; col < line_end + 40 * s; ++col)
      if (dark(col, row)) {
        if (first < 0) first = row;
        last = row;
      }
  REQUIRE(first >= 0);
  CAPTURE(first, last, mid);
  CHECK(std::abs(0.5 * (first + last) - mid) <= s);
  // The strip ends a few font pixels below its last text row ("compression, tension"): no empty band.
  int last_ink = -1;
  for (int row = pic.frame.scene_height; row < pic.canvas.height(); ++row)
    for (int col = 0; col < pic.canvas.width(); ++col) {
      const dem::Rgb p = pic.canvas.at(col, row);
      if (p.r != 245 || p.g != 245 || p.b != 245) last_ink = row;
    }
  REQUIRE(last_ink > mid);
  CHECK(pic.canvas.height() - 1 - last_ink <= 6 * s);
}

TEST_CASE("picture: a wall contact's line runs from the centre down to the wall and no further", "[picture]") {
  const dem::Case c = dem::read_case(test::source("cases/basic/rest_on_wall.toml"));  // a disk on a floor
  dem::Simulation sim(c.model);
  for (int k = 0; k < 100; ++k) sim.step();
  REQUIRE(sim.contact(0, 0, true).fn > 0.0);
  dem::PictureOptions o;
  o.width = 800;
  o.max_line = 8.0;
  const dem::ForcePicture pic = dem::draw_force_network(sim, o);
  const dem::Elements& e = sim.model().elements;
  const dem::Vec2 centre = pic.frame.to_px({e.x[0], e.y[0]});
  const double r_px = e.radius[0] * pic.frame.scale;
  REQUIRE(r_px > 40.0);
  const int col = static_cast<int>(centre.x), y = static_cast<int>(centre.y);
  // above the centre (beyond the line's round cap): the disk's fill only
  CHECK(dark_in_column(pic.canvas, col, y - static_cast<int>(0.9 * r_px), y - 6) == 0);
  // below it, down to the contact point r below the centre, where the floor (drawn dark too) begins:
  // the line, every pixel
  const int y1 = y + static_cast<int>(r_px) - 1;
  CHECK(dark_in_column(pic.canvas, col, y + 6, y1) == y1 - (y + 6));
}

TEST_CASE("picture: removed elements and their contacts are not drawn", "[picture]") {
  const auto path = test::write_temp("picture_row_removed.toml", row_case(""));
  dem::Case c = dem::read_case(path);
  c.model.elements.active[2] = 0;
  dem::Simulation sim(c.model);
  sim.step();
  dem::PictureOptions o;
  o.max_line = 12.0;
  const dem::ForcePicture pic = dem::draw_force_network(sim, o);
  const dem::Vec2 b = pic.frame.to_px({0.0198, 0.0}), cc = pic.frame.to_px({0.0397, 0.0});
  const auto at_c = pic.canvas.at(static_cast<int>(cc.x), static_cast<int>(cc.y));
  CHECK(at_c.r == 255);  // background: no disk, no line
  CHECK(dark_in_column(pic.canvas, static_cast<int>(0.75 * b.x + 0.25 * cc.x), static_cast<int>(b.y) - 40,
                       static_cast<int>(b.y) + 40) == 0);
}

TEST_CASE("picture: [output] picture keys take units and name file:line: key on errors", "[picture][case]") {
  const auto good = test::write_temp(
      "picture_keys.toml", row_case("[output]\npictures = true\npicture_every = \"2 us\"\npicture_times = [\"0 s\", \"3e-6 s\"]\n"
                                    "picture_width = 300\npicture_max_force = \"2 N\"\n"));
  const dem::Case c = dem::read_case(good);
  CHECK(c.output.pictures);
  CHECK(c.output.picture_every == Approx(2e-6));
  CHECK(c.output.picture_times == std::vector<double>{0.0, 3e-6});
  CHECK(c.output.picture_width == 300);
  REQUIRE(c.output.picture_max_force);
  CHECK(*c.output.picture_max_force == 2.0);
  struct Bad {
    const char* line;
    const char* key;
    const char* expected;
  };
  const auto bad = GENERATE(Bad{"picture_every = \"2 m\"", "output.picture_every", "expected a time"},
                            Bad{"picture_every = \"1e-7 s\"", "output.picture_every", "shorter than dt"},
                            Bad{"picture_every = \"-1 s\"", "output.picture_every", "must not be negative"},
                            Bad{"picture_times = [\"2 us\", \"1 us\"]", "output.picture_times", "must increase strictly"},
                            Bad{"picture_times = [\"1 us\", \"1 us\"]", "output.picture_times", "must increase strictly"},
                            Bad{"picture_times = \"1 us\"", "output.picture_times", "non-empty array"},
                            Bad{"picture_width = 10", "output.picture_width", "64"},
                            Bad{"picture_max_force = \"2 N/m\"", "output.picture_max_force", "expected a force"},
                            Bad{"picture_colour = \"red\"", "output.picture_colour", "unknown key"});
  CAPTURE(bad.line);
  const std::string text = row_case("[output]\n" + std::string(bad.line) + "\n");
  const auto path = test::write_temp("picture_bad.toml", text);
  const int line = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  const auto msg = test::message_of<dem::CaseError>([&] { dem::read_case(path); });
  CHECK_THAT(msg, StartsWith(path.string() + ":" + std::to_string(line) + ": " + bad.key + ": "));
  CHECK_THAT(msg, Contains(bad.expected));
}

TEST_CASE("picture: a run writes its pictures at the chosen steps, and never an earlier run's", "[picture][run]") {
  const auto out = test::fresh_dir("dem2d_unit_pictures", "run");
  fs::create_directories(out / "pictures");
  std::ofstream(out / "pictures" / "picture_999999999.png") << "old";
  const auto path = test::write_temp(
      "picture_run.toml", row_case("[output]\nvtk = false\npictures = true\npicture_times = [\"3e-6 s\", \"3.5e-6 s\", \"1 s\"]\n"
                                   "picture_width = 200\n"));
  dem::RunOptions opt;
  opt.out_dir = out;
  const dem::RunResult r = dem::run_case(dem::read_case(path), opt);
  REQUIRE(r.status == "completed");
  std::vector<std::string> names;
  for (const auto& f : fs::directory_iterator(out / "pictures")) names.push_back(f.path().filename().string());
  std::sort(names.begin(), names.end());
  // start, t = 3 us (step 3), 3.5 us (step 4: the first step at or after it), the end (step 10); 1 s is
  // after the end.
  CHECK(names == std::vector<std::string>{"picture_000000000.png", "picture_000000003.png", "picture_000000004.png",
                                          "picture_000000010.png"});
  const Decoded d = decode_png(test::slurp(out / "pictures" / "picture_000000003.png"));
  CHECK(d.width == 200);
  CHECK(r.summary["pictures"].size() == 4);
  CHECK(r.summary["pictures"][1]["file"] == "pictures/picture_000000003.png");
  CHECK(r.summary["pictures"][2]["step"] == 4);  // the step of each picture (study snapshots read it)
  CHECK(r.summary["pictures"][2]["time"].get<double>() == Approx(4e-6));
}

TEST_CASE("picture: a broken bond is marked with an orange cross where it broke - nothing where none did", "[picture]") {
  dem::Simulation sim(row_model("picture_row_breaks.toml"));
  sim.step();
  dem::PictureOptions o;
  o.max_line = 12.0;
  const dem::Vec2 mark{0.0099, 0.006};  // above the contact line between elements 0 and 1, inside the fill
  const dem::ForcePicture none = dem::draw_force_network(sim, o);
  o.broken_bonds = {mark};
  const dem::ForcePicture marked = dem::draw_force_network(sim, o);
  const dem::Vec2 p = marked.frame.to_px(mark);
  auto orange = [](dem::Rgb c) { return c.r > 200 && c.g > 80 && c.g < 160 && c.b < 60; };
  CHECK(orange(marked.canvas.at(static_cast<int>(p.x), static_cast<int>(p.y))));
  CHECK_FALSE(orange(none.canvas.at(static_cast<int>(p.x), static_cast<int>(p.y))));
}

namespace {
/// `pairs` disk pairs far apart, each overlapping by 0.02 mm (|f_n| = K δ = 2 N after the first step), the
/// first one by 2 mm (200 N): one impact far above the rest.
std::string pairs_case(int pairs) {
  std::string s = R"([case]
title = "disk pairs"
[physics]
gravity = [0.0, 0.0]
[[material]]
name = "sand"
density = 2650.0
[[contact]]
between = ["sand", "sand"]
kn = 1e5
damping_ratio = 0.0
[numerics]
dt = 1e-7
duration = 1e-7
allow_unstable = true
)";
  for (int k = 0; k < pairs; ++k) {
    const double x = 0.1 * k, gap = k == 0 ? 0.018 : 0.01998;
    s += fmt::format("[[element]]\nmaterial = \"sand\"\nradius = 0.01\nposition = [{}, 0.0]\n", x);
    s += fmt::format("[[element]]\nmaterial = \"sand\"\nradius = 0.01\nposition = [{}, 0.0]\n", x + gap);
  }
  return s;
}
}  // namespace

TEST_CASE("picture: without a fixed scale the widest line is the 99th percentile of |f_n| - one impact does not hide the rest", "[picture]") {
  auto scale_of = [](int pairs, std::optional<double> fixed) {
    const auto path = test::write_temp(fmt::format("picture_pairs_{}.toml", pairs), pairs_case(pairs));
    dem::Simulation sim(dem::read_case(path).model);
    sim.step();
    dem::PictureOptions o;
    o.max_force = fixed;
    return dem::draw_force_network(sim, o).max_force;
  };
  CHECK(scale_of(150, std::nullopt) == Approx(2.0).epsilon(1e-3));   // 150 contacts: the 99th percentile
  CHECK(scale_of(10, std::nullopt) == Approx(200.0).epsilon(1e-3));  // too few for a percentile: the largest
  CHECK(scale_of(150, 50.0) == 50.0);                                // a fixed scale is kept
}
