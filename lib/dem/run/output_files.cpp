#include "dem/run/output_files.hpp"
#include "dem/run/owned_files.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>
#include <unistd.h>

#include <fmt/format.h>

namespace dem {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& file, const char* what, int err) {
  throw OutputError(fmt::format("{}: {}: {}", file.string(), what, std::strerror(err)));
}

}  // namespace

void write_file_atomic(const fs::path& file, std::string_view content, bool durable) {
  // A temporary name of its own per call: two threads (or processes) finishing the same file at once
  // (a study's duplicate runs share one cache entry) must not rename each other's temporary away.
  static std::atomic<unsigned long> serial{0};
  const fs::path tmp = fmt::format("{}.{}-{}.tmp", file.string(), static_cast<long>(getpid()), serial++);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) fail(file, "cannot write", errno);
  const bool wrote = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  int err = wrote ? 0 : errno;
  if (std::fflush(f) != 0 && !err) err = errno;
  if (!err && durable && fsync(fileno(f)) != 0 && errno != EINVAL && errno != EROFS) err = errno;
  if (std::fclose(f) != 0 && !err) err = errno;
  if (!wrote && !err) err = EIO;
  if (err) {
    std::error_code ec;
    fs::remove(tmp, ec);
    fail(file, "write failed", err);
  }
  if (std::rename(tmp.c_str(), file.c_str()) != 0) {
    const int e = errno;
    std::error_code ec;
    fs::remove(tmp, ec);
    fail(file, "cannot rename the finished file into place", e);
  }
}

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "cannot read", errno ? errno : ENOENT);
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) fail(file, "read failed", EIO);
  return s.str();
}

void StreamedFile::open(const fs::path& file) {
  file_ = file;
  partial_ = file.string() + ".partial";
  f_ = std::fopen(partial_.c_str(), "wb");
  if (!f_) fail(partial_, "cannot write", errno);
}

StreamedFile::~StreamedFile() {
  if (f_) std::fclose(f_);  // not committed (an exception): the .partial file stays as evidence
}

void StreamedFile::write(std::string_view text) {
  if (std::fwrite(text.data(), 1, text.size(), f_) != text.size()) {
    const int e = errno ? errno : EIO;
    std::fclose(f_);
    f_ = nullptr;
    fail(partial_, "write failed", e);
  }
}

void StreamedFile::commit() {
  if (!f_) return;
  int err = 0;
  if (std::fflush(f_) != 0) err = errno;
  if (std::ferror(f_) && !err) err = EIO;
  if (std::fclose(f_) != 0 && !err) err = errno;
  f_ = nullptr;
  if (err) fail(partial_, "write failed", err);
  if (std::rename(partial_.c_str(), file_.c_str()) != 0) fail(file_, "cannot rename the finished file into place", errno);
}

bool is_run_output(const std::string& name) {
  std::string base = name;
  for (const char* suffix : {".tmp", ".partial"})
    if (base.size() > std::strlen(suffix) && base.ends_with(suffix)) base.resize(base.size() - std::strlen(suffix));
  // write_file_atomic's temporaries are <name>.<pid>-<serial>.tmp
  if (name.ends_with(".tmp"))
    if (const auto dot = base.rfind('.'); dot != std::string::npos && dot + 1 < base.size() &&
                                          base.find_first_not_of("0123456789-", dot + 1) == std::string::npos)
      base.resize(dot);
  return base == "series.csv" || base == "summary.json" || base == "snapshots.pvd" || base == "vtk" || base == "pictures" ||
         base == "checkpoint.bin" || base == "wall_contacts.csv" || base == "bond_breaks.csv" ||
         base == "dump.lammpstrj" || base == "contacts.csv";
}

void prepare_run_folder(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw OutputError(fmt::format("{}: --out: exists and is not a folder", dir.string()));
  if (fs::is_directory(dir, ec)) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (!is_run_output(name))
        throw OutputError(fmt::format("{}: --out: the folder holds '{}', which dem2d run did not write; give an empty "
                                      "or new folder (a run folder is cleared before a run, so two runs never mix)",
                                      dir.string(), name));
    }
    // vtk/ and pictures/: only snapshots and pictures a run wrote (a user's file in them refuses the run)
    check_owned_folder(dir / "vtk", OwnedFolder::run_vtk, "--out");
    check_owned_folder(dir / "pictures", OwnedFolder::run_pictures, "--out");
    for (const auto& entry : fs::directory_iterator(dir)) {
      fs::remove_all(entry.path(), ec);
      if (ec) throw OutputError(fmt::format("{}: cannot remove the earlier run's output: {}", entry.path().string(), ec.message()));
    }
  }
  fs::create_directories(dir, ec);
  if (ec) throw OutputError(fmt::format("{}: cannot create the output folder: {}", dir.string(), ec.message()));
}

}  // namespace dem
