// The force-network pictures' rasteriser (lib/dem/run/picture/canvas.hpp): a polygon is filled wherever
// it lies whichever corner comes first, and it reads its eight corner numbers and nothing beyond them.
// Planted bugs that turn these red: the box's top taken from the first corner's x; a ninth and tenth
// number read past the corners.
#include <catch2/catch.hpp>

#include <sys/mman.h>
#include <unistd.h>

#include <array>
#include <new>

#include "dem/run/picture/canvas.hpp"

namespace {
constexpr dem::Rgb kWhite{255, 255, 255}, kFill{200, 0, 0}, kEdge{0, 0, 200};

/// A diamond centred at (30, 20) reaching 10 px along each axis, its corners in order from `first`:
/// top (30, 10), right (40, 20), bottom (30, 30), left (20, 20). The first corner's x (20 to 40) lies
/// outside the y range of the others whenever it is the top or the bottom.
std::array<double, 8> diamond(int first) {
  const double corners[4][2] = {{30, 10}, {40, 20}, {30, 30}, {20, 20}};
  std::array<double, 8> xy{};
  for (int k = 0; k < 4; ++k) {
    xy[2 * k] = corners[(first + k) % 4][0];
    xy[2 * k + 1] = corners[(first + k) % 4][1];
  }
  return xy;
}

bool filled(const dem::Canvas& c, int x, int y) {
  const dem::Rgb p = c.at(x, y);
  return p.r == kFill.r && p.g == kFill.g && p.b == kFill.b;
}
}  // namespace

TEST_CASE("canvas: a polygon is filled out to each corner whichever corner comes first", "[picture]") {
  for (int first = 0; first < 4; ++first) {
    CAPTURE(first);
    dem::Canvas c(60, 40, kWhite);
    c.polygon(diamond(first), kFill, kEdge, 0.5);
    // inside, two pixels from each corner along the axis, and the centre
    CHECK(filled(c, 29, 13));  // below the top corner
    CHECK(filled(c, 36, 19));  // left of the right corner
    CHECK(filled(c, 29, 26));  // above the bottom corner
    CHECK(filled(c, 23, 19));  // right of the left corner
    CHECK(filled(c, 29, 19));
    // outside: beyond each corner and off the diagonals
    CHECK(c.at(29, 7).g == 255);
    CHECK(c.at(43, 19).g == 255);
    CHECK(c.at(29, 33).g == 255);
    CHECK(c.at(16, 19).g == 255);
    CHECK(c.at(22, 12).g == 255);
  }
}

TEST_CASE("canvas: a polygon reads its eight corner numbers and nothing past them", "[picture]") {
  // The corners end exactly at a page that may not be read: a read past them stops the test (SIGSEGV).
  const long page = sysconf(_SC_PAGESIZE);
  void* mem = mmap(nullptr, static_cast<std::size_t>(2 * page), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  REQUIRE(mem != MAP_FAILED);
  char* guard = static_cast<char*>(mem) + page;
  REQUIRE(mprotect(guard, static_cast<std::size_t>(page), PROT_NONE) == 0);
  auto* xy = new (guard - sizeof(std::array<double, 8>)) std::array<double, 8>(diamond(0));
  dem::Canvas c(60, 40, kWhite);
  c.polygon(*xy, kFill, kEdge, 0.5);
  CHECK(filled(c, 29, 19));
  munmap(mem, static_cast<std::size_t>(2 * page));
}
