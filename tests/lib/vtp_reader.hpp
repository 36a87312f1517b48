#pragma once
// Reads one array of a .vtp snapshot written by write_vtp (appended raw data, UInt64 block headers):
// the first DataArray named `name` after `section` (e.g. "<CellData"; point data come before cell data).
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace test {

template <class T>
std::vector<T> vtp_array(const std::string& vtp, const std::string& name, const std::string& section = "") {
  const auto from = section.empty() ? 0 : vtp.find(section);
  REQUIRE(from != std::string::npos);
  const auto at = vtp.find("Name=\"" + name + "\"", from);
  REQUIRE(at != std::string::npos);
  const auto off = vtp.find("offset=\"", at);
  REQUIRE(off != std::string::npos);
  const std::size_t offset = std::stoull(vtp.substr(off + 8, vtp.find('"', off + 8) - off - 8));
  const auto data = vtp.find("<AppendedData encoding=\"raw\">");
  REQUIRE(data != std::string::npos);
  const std::size_t base = vtp.find('_', data) + 1 + offset;
  std::uint64_t bytes = 0;
  REQUIRE(base + sizeof bytes <= vtp.size());
  std::memcpy(&bytes, vtp.data() + base, sizeof bytes);
  REQUIRE(bytes % sizeof(T) == 0);
  REQUIRE(base + sizeof bytes + bytes <= vtp.size());
  std::vector<T> v(bytes / sizeof(T));
  std::memcpy(v.data(), vtp.data() + base + sizeof bytes, bytes);
  return v;
}

}  // namespace test
