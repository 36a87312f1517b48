#pragma once
// PNG encoding of an 8-bit RGB image (PNG specification, ISO/IEC 15948): signature, IHDR, one IDAT
// compressed with zlib (filter type 0 on every row), IEND; every chunk with its CRC-32.
#include <cstdint>
#include <string>
#include <vector>

namespace dem {

/// The PNG file of a width × height image, `rgb` holding 3 bytes per pixel, rows top to bottom.
std::string encode_png(int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace dem
