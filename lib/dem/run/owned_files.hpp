#pragma once
// Folders dem2d fills with files of its own (a run's vtk/ and pictures/, a study's cache/): before such a
// folder is removed (a new run into the same --out, `study --fresh`), every entry in it must be a plain
// file with a name dem2d writes there — its fixed pattern, or a temporary of one (write_file_atomic's
// <name>.<pid>-<serial>.tmp). Anything else (a user's mesh in o/vtk/, a note in DIR/cache/) refuses the
// removal with an OutputError naming it, and nothing is removed.
#include <filesystem>
#include <string>
#include <string_view>

namespace dem {

/// `name` is `prefix` + `digits` decimal digits (or hex digits) + `suffix`, or a temporary of that name.
bool is_numbered_name(std::string_view name, std::string_view prefix, int digits, std::string_view suffix, bool hex = false);

/// The kinds of folder dem2d owns.
enum class OwnedFolder { run_vtk, run_pictures, study_cache };

/// Checks every entry of `dir` (OutputError naming the first foreign one, and `what` the user asked for),
/// then removes the folder. A missing folder is nothing to do.
void remove_owned_folder(const std::filesystem::path& dir, OwnedFolder kind, const std::string& what);
/// The check alone (nothing removed).
void check_owned_folder(const std::filesystem::path& dir, OwnedFolder kind, const std::string& what);

}  // namespace dem
