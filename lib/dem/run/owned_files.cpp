#include "dem/run/owned_files.hpp"

#include <cctype>
#include <system_error>

#include <fmt/format.h>

#include "dem/run/output_files.hpp"

namespace dem {

namespace fs = std::filesystem;

namespace {

// write_file_atomic's temporary of `base`: <base>.<pid>-<serial>.tmp
std::string_view without_temporary(std::string_view name) {
  if (!name.ends_with(".tmp")) return name;
  std::string_view base = name.substr(0, name.size() - 4);
  const auto dot = base.rfind('.');
  if (dot == std::string_view::npos || dot + 1 == base.size()) return name;
  if (base.find_first_not_of("0123456789-", dot + 1) != std::string_view::npos) return name;
  return base.substr(0, dot);
}

bool ours(std::string_view name, OwnedFolder kind) {
  switch (kind) {
    case OwnedFolder::run_vtk: return is_numbered_name(name, "snapshot_", 9, ".vtp");
    case OwnedFolder::run_pictures: return is_numbered_name(name, "picture_", 9, ".png");
    case OwnedFolder::study_cache: return is_numbered_name(name, "", 16, ".json", true);
  }
  return false;
}

}  // namespace

bool is_numbered_name(std::string_view name, std::string_view prefix, int digits, std::string_view suffix, bool hex) {
  name = without_temporary(name);
  if (name.size() < prefix.size() + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix)) return false;
  const std::string_view number = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (number.size() < static_cast<std::size_t>(digits)) return false;
  for (const char ch : number)
    if (!(hex ? std::isxdigit(static_cast<unsigned char>(ch)) : std::isdigit(static_cast<unsigned char>(ch)))) return false;
  return true;
}

void check_owned_folder(const fs::path& dir, OwnedFolder kind, const std::string& what) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(dir, ec))) return;
  if (fs::is_symlink(fs::symlink_status(dir, ec)) || !fs::is_directory(dir, ec))
    throw OutputError(fmt::format("{}: {}: not a folder dem2d wrote; move it away first", dir.string(), what));
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file(ec) || entry.is_symlink(ec) || !ours(name, kind))
      throw OutputError(fmt::format("{}: {}: the folder holds '{}', which dem2d did not write; move it away first "
                                    "(only files dem2d wrote are ever removed)",
                                    dir.string(), what, name));
  }
  if (ec) throw OutputError(fmt::format("{}: {}: cannot list the folder: {}", dir.string(), what, ec.message()));
}

void remove_owned_folder(const fs::path& dir, OwnedFolder kind, const std::string& what) {
  check_owned_folder(dir, kind, what);
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (ec) throw OutputError(fmt::format("{}: {}: cannot remove: {}", dir.string(), what, ec.message()));
}

}  // namespace dem
