#pragma once
// What both fuzz targets check: the input boundary either accepts a case (read_case + check_case,
// the path `dem2d check` takes, without running it) or refuses it with a dem::CaseError whose message
// starts with a location ("file:line: …" with line ≥ 1, "file: …" or "--set …"). Anything else is a finding and
// aborts: another exception type (the app would print an unlocated "error: stoul"), a crash, or a
// sanitizer report.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace fuzz {

/// A scratch file for this process (under /dev/shm when it exists), removed at exit.
const std::filesystem::path& scratch_file();

/// A scratch file `name` two folders below a scratch root for this process whose `cases` is a link to the
/// repository's cases/ (removed at exit): a study or sensitivity file there reaches its base case by the
/// "../../cases/…" path the files in verification/<study>/ use.
std::filesystem::path scratch_beside_cases(const std::string& name);

/// Aborts with "FUZZ FINDING: what" (libFuzzer keeps the input).
[[noreturn]] void finding(const std::string& what);

/// Writes `size` bytes to `path` (replacing it).
void write_file(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size);

/// Reads and checks the case `file` with `overrides` (check_case only up to 2000 elements); aborts on
/// anything but success or a located CaseError.
void check_case_file(const std::filesystem::path& file, const std::vector<std::string>& overrides);

/// The same for the case text `text` read as if it were the file `file` (dem::read_case_text): nothing
/// touches the file system, so a target runs thousands of inputs a second.
void check_case_text(std::string_view text, const std::filesystem::path& file, const std::vector<std::string>& overrides);

/// Only reads the case text (dem::read_case_text, no check_case: the reader alone, thousands of inputs a
/// second under ASan); the same policy for what it throws.
void read_case_text(std::string_view text, const std::filesystem::path& file);

/// The whole file (once per process, e.g. a fixed base case).
std::string read_text(const std::filesystem::path& path);

}  // namespace fuzz
