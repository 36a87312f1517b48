#pragma once
// Result files that are never half-written and never mixed with another run's: every file is written
// to a temporary name and renamed into place when complete (a rename is atomic on one file system);
// every write is checked, and a failure (full disk, unwritable folder) throws OutputError naming the
// file and the reason, so that the command exits non-zero instead of leaving an empty file behind.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace dem {

struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Writes `content` to `file` via a temporary `file.<pid>-<serial>.tmp` of its own + rename (safe when
/// several threads or processes finish the same file at once). Throws OutputError. `durable`: fsync before the
/// rename (also survives a power cut; snapshots skip it for speed, a killed process never sees them half).
void write_file_atomic(const std::filesystem::path& file, std::string_view content, bool durable = true);

/// Reads a whole file (binary). Throws OutputError if it cannot be read.
std::string read_file(const std::filesystem::path& file);

/// A file written in pieces (the time series): written as `<file>.partial`, renamed to `<file>` by
/// commit(). A run that is killed leaves only the `.partial` file. Every write is checked.
class StreamedFile {
 public:
  StreamedFile() = default;
  void open(const std::filesystem::path& file);
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;
  ~StreamedFile();
  bool is_open() const { return f_ != nullptr; }
  void write(std::string_view text);
  void commit();  // flush, close, rename into place

 private:
  std::filesystem::path file_, partial_;
  std::FILE* f_ = nullptr;
};

/// The names a run writes into its output folder (and their temporary forms).
bool is_run_output(const std::string& name);

/// Prepares a run's output folder so that it never mixes two runs: creates it, or, if it exists,
/// deletes what an earlier run wrote there (series, summary, snapshots, vtk/, checkpoint). A folder
/// holding anything else is refused (OutputError): it was not written by `dem2d run`.
void prepare_run_folder(const std::filesystem::path& dir);

}  // namespace dem
