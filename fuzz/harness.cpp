#include "harness.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iterator>
#include <string_view>

#include <unistd.h>

#include "dem/cases/case_file.hpp"

namespace fuzz {

namespace {

std::filesystem::path make_scratch() {
  const std::filesystem::path dir = std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm")
                                                                             : std::filesystem::temp_directory_path();
  return dir / ("dem2d_fuzz_" + std::to_string(::getpid()) + ".toml");
}

void remove_scratch() {
  std::error_code ec;
  std::filesystem::remove(scratch_file(), ec);
}


constexpr std::size_t kMaxCheckedElements = 2000;
constexpr std::ptrdiff_t kMaxCheckedPres = 100;

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

}  // namespace

const std::filesystem::path& scratch_file() {
  static const std::filesystem::path p = [] {
    std::atexit(remove_scratch);
    return make_scratch();
  }();
  return p;
}

void finding(const std::string& what) {
  std::fprintf(stderr, "\nFUZZ FINDING: %s\n", what.c_str());
  std::abort();
}

namespace {
std::filesystem::path scratch_root() {
  return scratch_file().parent_path() / ("dem2d_fuzz_" + std::to_string(::getpid()) + ".d");
}
void remove_scratch_root() {
  std::error_code ec;
  std::filesystem::remove_all(scratch_root(), ec);  // the link, not what it points to
}
}  // namespace

std::filesystem::path scratch_beside_cases(const std::string& name) {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path root = scratch_root();
    std::filesystem::create_directories(root / "verification" / "fuzz");
    std::error_code ec;
    std::filesystem::create_directory_symlink(std::filesystem::path(DEM2D_SOURCE_DIR) / "cases", root / "cases", ec);
    std::atexit(remove_scratch_root);
    return root / "verification" / "fuzz";
  }();
  return dir / name;
}

void write_file(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) finding("cannot write the scratch file " + path.string());
}

namespace {

// Reads (`read`) and checks a case; aborts on anything but success or a CaseError located at `file`.
template <class Read>
void check_case_with(const std::filesystem::path& file, Read read, bool check = true) {
  try {
    const dem::Case c = read();
    if (!check) return;
    // check_case's neighbour search is quadratic when one element is much larger than the others
    // (one cell for all): legitimate, but 10^4 elements take > 10 s under ASan + coverage. Larger
    // models are read, not checked.
    // The time-step guard of a bonded PRE lattice solves for the largest eigenvalue of its stiffness
    // (core/stability_eigen.cpp, a dozen Lanczos runs): 0.4 s for the 10 x 40 beam in Release, 23 s
    // under ASan + coverage, past libFuzzer's 10 s timeout. Lattices of more than kMaxCheckedPres are
    // read, not checked (4 x 16 takes 3 s; the guard itself is tested in tests/lib/core/).
    const auto pres = std::count(c.model.elements.shape.begin(), c.model.elements.shape.end(), dem::Shape::pre);
    if (c.model.elements.size() <= kMaxCheckedElements && pres <= kMaxCheckedPres) (void)dem::check_case(c);
  } catch (const dem::CaseError& e) {
    const std::string_view msg = e.what();
    if (!starts_with(msg, file.string() + ":") && !starts_with(msg, "--set "))
      finding("CaseError without a location: " + std::string(msg));
    if (starts_with(msg, file.string() + ":0:"))  // a node toml++ did not read from the file
      finding("CaseError at line 0: " + std::string(msg));
  } catch (const std::exception& e) {
    finding(std::string("exception other than dem::CaseError: ") + e.what());
  } catch (...) {
    finding("unknown exception");
  }
}

}  // namespace

void check_case_file(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  check_case_with(file, [&] { return dem::read_case(file, overrides); });
}

void check_case_text(std::string_view text, const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  check_case_with(file, [&] { return dem::read_case_text(text, file, overrides); });
}

void read_case_text(std::string_view text, const std::filesystem::path& file) {
  check_case_with(file, [&] { return dem::read_case_text(text, file); }, false);
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in.good() && !in.eof()) finding("cannot read " + path.string());
  return text;
}

}  // namespace fuzz
