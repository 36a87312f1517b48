// The snapshots of a study (result.json "snapshots", verification/RESULT_FORMAT.md): force-network
// pictures of its runs, shown as a captioned gallery per snapshot id. The HTML page embeds each PNG
// (a data: URI, so the page stays one self-contained file); the Markdown twin links a copy in
// figures/. A picture whose file is missing (or lies outside the study's folder) gets a "missing"
// note in place of the image, never a broken <img>.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "study_result.hpp"

namespace report {

struct SnapshotPicture {
  std::string id, title;   // the snapshot's id and caption (shared by its pictures)
  std::string caption;     // under the picture: variant, time, step
  std::string data_uri;    // "data:image/png;base64,…"; "" when missing
  std::string file;        // the copy for index.md, relative to out_dir ("figures/…png"); "" when missing
  std::string note;        // why missing
  int width = 0;           // the PNG's own width [px] (its IHDR), 0 when missing
};

/// Reads the pictures a study's result.json lists (paths relative to the study's folder), copies them
/// to <out_dir>/figures/<stem>-snapshot-<k>.png and encodes them for the page.
std::vector<SnapshotPicture> load_snapshots(const StudyResult& study, const std::filesystem::path& out_dir,
                                            const std::string& stem);

/// The gallery: per snapshot id a heading (its title) and the pictures, each with its caption, side by
/// side at min(own width, max(240 px, the page's 1290 px shared among the id's pictures)).
/// A heading gets the id `anchor_prefix` + slug(id) when the prefix is not empty (the claims link to it).
std::string snapshot_gallery_html(const std::vector<SnapshotPicture>& pictures, const std::string& anchor_prefix = "");
std::string snapshot_gallery_markdown(const std::vector<SnapshotPicture>& pictures);

/// Base64 (RFC 4648, with padding).
std::string base64(const std::string& bytes);

}  // namespace report
