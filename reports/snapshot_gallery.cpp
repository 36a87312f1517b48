// Snapshot galleries (snapshot_gallery.hpp).
#include "snapshot_gallery.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <system_error>

#include "text_format.hpp"
#include "dem/run/output_files.hpp"

namespace report {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view png_signature = "\x89PNG\r\n\x1a\n";

/// "K19 dt=1e-4 · t = 0.9 s (step 9000)"; "end" says so.
std::string caption_of(const nlohmann::json& e) {
  const auto variant = text_field(e, "variant");
  const auto at = text_field(e, "at");
  const auto time = number_field(e, "time");
  const auto step = number_field(e, "step");
  std::string out = variant.empty() ? "" : variant + " \u00b7 ";
  if (at == "end") out += "end of the run: ";
  out += time ? "t = " + format_number(*time) + " s" : "t = " + (at.empty() ? std::string(missing_value) : at);
  if (step) out += " (step " + std::to_string(std::llround(*step)) + ")";
  return out;
}

/// The title of a snapshot with its common scale, if it has one.
std::string title_of(const nlohmann::json& e) {
  std::string title = text_field(e, "title");
  if (title.empty()) title = text_field(e, "id");
  if (const auto f = number_field(e, "max_force"))
    title += " (line width: |f_n| = " + format_number(*f) + " N drawn widest, in every picture)";
  return title;
}

/// The picture's file inside the study's folder, or "" with `why` set.
fs::path picture_path(const StudyResult& study, const nlohmann::json& e, std::string& why) {
  const auto file = text_field(e, "file");
  if (file.empty()) {
    why = text_field(e, "note").empty() ? "no picture file recorded" : text_field(e, "note");
    return {};
  }
  const fs::path rel = fs::path(file).lexically_normal();
  if (rel.is_absolute() || rel.empty() || *rel.begin() == "..") {
    why = "picture path outside the study folder: " + file;
    return {};
  }
  return study.path.parent_path() / rel;
}

}  // namespace

std::string base64(const std::string& bytes) {
  static constexpr char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t k = 0; k < bytes.size(); k += 3) {
    const auto b = [&](std::size_t i) { return i < bytes.size() ? static_cast<unsigned char>(bytes[i]) : 0u; };
    const unsigned n = (b(k) << 16) | (b(k + 1) << 8) | b(k + 2);
    out += digits[(n >> 18) & 63];
    out += digits[(n >> 12) & 63];
    out += k + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
    out += k + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

std::vector<SnapshotPicture> load_snapshots(const StudyResult& study, const fs::path& out_dir, const std::string& stem) {
  std::vector<SnapshotPicture> out;
  const auto& list = array_field(study.result, "snapshots");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const auto& e = list[k];
    SnapshotPicture p{text_field(e, "id"), title_of(e), caption_of(e), "", "", "", 0};
    std::string why;
    const fs::path file = picture_path(study, e, why);
    const std::string bytes = file.empty() ? std::string() : read_text_file(file);
    if (!file.empty() && bytes.compare(0, png_signature.size(), png_signature) != 0)
      why = bytes.empty() ? "missing: " + text_field(e, "file") + " is not there (rerun the study)"
                          : "not a PNG file: " + text_field(e, "file");
    if (!why.empty()) {
      p.note = why;
      out.push_back(std::move(p));
      continue;
    }
    p.data_uri = "data:image/png;base64," + base64(bytes);
    if (bytes.size() >= 24)  // IHDR: the width, big-endian, after the signature, length and type
      for (int i = 16; i < 20; ++i) p.width = p.width * 256 + static_cast<unsigned char>(bytes[i]);
    p.file = fmt::format("figures/{}-snapshot-{}.png", stem, k + 1);
    try {
      dem::write_file_atomic(out_dir / p.file, bytes, false);  // never a cut copy under the final name
    } catch (const dem::OutputError&) {
      p.file.clear();  // the page still shows it; index.md names it as not copied
    }
    out.push_back(std::move(p));
  }
  return out;
}

std::string snapshot_gallery_html(const std::vector<SnapshotPicture>& pictures, const std::string& anchor_prefix) {
  if (pictures.empty()) return {};
  std::string out = "<h3>Snapshots</h3>\n";
  int shown = 240;  // px: the width of each picture of the current id
  for (std::size_t k = 0; k < pictures.size(); ++k) {
    const SnapshotPicture& p = pictures[k];
    if (k == 0 || pictures[k - 1].id != p.id || pictures[k - 1].title != p.title) {
      const bool first_of_id = k == 0 || pictures[k - 1].id != p.id;  // an id once, also when its title changes
      const std::string anchor = anchor_prefix.empty() || !first_of_id ? "" : " id=\"" + anchor_prefix + slug(p.id) + "\"";
      out += (k ? "</div>\n" : "") + fmt::format("<h4{}>{}</h4>\n<div class=\"gallery\">\n", anchor, html_escape(p.title));
      std::size_t n = 0;
      for (std::size_t j = k; j < pictures.size() && pictures[j].id == p.id && pictures[j].title == p.title; ++j) ++n;
      shown = std::max(240, static_cast<int>((1290 - 16 * (n - 1)) / n));
    }
    const int width = p.width > 0 ? std::min(p.width, shown) : shown;
    out += fmt::format("<figure class=\"snapshot\" style=\"width: {}px\">\n", width);
    if (!p.data_uri.empty())
      out += fmt::format("<img src=\"{}\" alt=\"{}\">\n", p.data_uri, html_escape(p.title + ", " + p.caption));
    else
      out += "<div class=\"missing-figure\">missing picture: " + html_escape(p.note) + "</div>\n";
    out += "<figcaption>" + html_escape(p.caption) + "</figcaption>\n</figure>\n";
  }
  return out + "</div>\n";
}

std::string snapshot_gallery_markdown(const std::vector<SnapshotPicture>& pictures) {
  if (pictures.empty()) return {};
  std::string out = "### Snapshots\n\n";
  for (std::size_t k = 0; k < pictures.size(); ++k) {
    const SnapshotPicture& p = pictures[k];
    if (k == 0 || pictures[k - 1].id != p.id || pictures[k - 1].title != p.title)
      out += "#### " + markdown_escape(p.title) + "\n\n";
    if (!p.file.empty())
      out += fmt::format("![{}]({})\n\n{}\n\n", markdown_escape(p.caption), p.file, markdown_escape(p.caption));
    else
      out += "*" + markdown_escape(p.caption) + ": missing picture: " +
             markdown_escape(p.note.empty() ? std::string("not copied") : p.note) + "*\n\n";
  }
  return out;
}

}  // namespace report
