// The report's snapshot gallery (reports/snapshot_gallery.hpp): pictures listed in result.json are
// embedded in the page (data: URIs, the page stays self-contained) with their captions, copied for the
// Markdown twin; a missing file, a recorded "no picture" and a path outside the study folder each get
// a "missing picture" note, never an <img> that cannot load.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "report.hpp"
#include "temp_dir.hpp"
#include "snapshot_gallery.hpp"

namespace {

namespace fs = std::filesystem;

struct TempDir : test::TempDir {
  TempDir() : test::TempDir("dem2d_report_snapshot_test_") {}
};

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

// A 1 × 1 PNG (a white pixel).
const std::string kPng(
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x01\x00\x00\x00\x01\x08\x02"
    "\x00\x00\x00\x90\x77\x53\xde\x00\x00\x00\x0c\x49\x44\x41\x54\x78\x9c\x63\xf8\xff\xff\x3f\x00\x05\xfe\x02"
    "\xfe\x0d\xef\x46\xb8\x00\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82",
    69);

const char* kStudy = R"json({
  "study": "silo", "title": "Silo", "kind": "single", "passed": true,
  "checks": [ { "quantity": "w", "reference": 1, "dem": 1, "error": 0, "error_kind": "abs", "tolerance": 0.1,
                "tolerance_reason": "r", "passed": true, "note": "" } ],
  "snapshots": [
    { "id": "fig8", "title": "Fig. 8: discharge", "variant": "K19 dt=1e-4", "at": "0.9 s", "time": 0.9, "step": 9000,
      "file": "snapshots/fig8/K19_dt_1e-4/pictures/picture_000009000.png", "max_force": 200.0 },
    { "id": "fig8", "title": "Fig. 8: discharge", "variant": "K19 dt=1e-4", "at": "1 s", "time": 1.0, "step": 10000,
      "file": "snapshots/fig8/K19_dt_1e-4/pictures/picture_000010000.png", "max_force": 200.0 },
    { "id": "fig8", "title": "Fig. 8: discharge", "variant": "K19 dt=1e-4", "at": "1.4 s", "time": null, "step": null,
      "file": null, "note": "no picture: the run ended (settled) before 1.4 s", "max_force": 200.0 },
    { "id": "fig6", "title": "Fig. 6: settled", "variant": "K19 dt=1e-4", "at": "end", "time": 0.66, "step": 6600,
      "file": "../elsewhere/picture.png", "max_force": null }
  ]
})json";

}  // namespace

TEST_CASE("snapshot pictures are embedded as a captioned gallery, a missing one gets a note", "[report][snapshot]") {
  TempDir tmp;
  const fs::path studies = tmp.path / "studies";
  fs::create_directories(studies / "silo" / "snapshots/fig8/K19_dt_1e-4/pictures");
  std::ofstream(studies / "silo" / "result.json") << kStudy;
  std::ofstream(studies / "silo" / "snapshots/fig8/K19_dt_1e-4/pictures/picture_000009000.png", std::ios::binary) << kPng;
  fs::create_directories(studies / "elsewhere");  // a file outside the study folder is never read
  std::ofstream(studies / "elsewhere" / "picture.png", std::ios::binary) << kPng;
  // picture_000010000.png is not there

  report::Options options;
  options.studies_dir = studies;
  options.out_dir = tmp.path / "report";
  const auto written = report::write_report(options);
  const std::string html = read(written.html);
  CHECK(count(html, "<h3>Snapshots</h3>") == 1);
  CHECK(count(html, ">Fig. 8: discharge (line width: |f_n| = 200 N drawn widest, in every picture)</h4>") == 1);
  CHECK(count(html, ">Fig. 6: settled</h4>") == 1);
  CHECK(count(html, "<img src=\"data:image/png;base64," + report::base64(kPng) + "\"") == 1);
  CHECK(count(html, "<img ") == 1);  // only the picture that is there
  CHECK(count(html, "<figcaption>K19 dt=1e-4 &middot; t = 0.9 s (step 9000)</figcaption>") +
            count(html, "<figcaption>K19 dt=1e-4 \u00b7 t = 0.9 s (step 9000)</figcaption>") == 1);
  CHECK(count(html, "missing picture: ") == 3);
  CHECK(html.find("picture_000010000.png is not there") != std::string::npos);
  CHECK(html.find("the run ended (settled) before 1.4 s") != std::string::npos);
  CHECK(html.find("picture path outside the study folder") != std::string::npos);
  CHECK(html.find("end of the run: t = 0.66 s (step 6600)") != std::string::npos);

  const std::string markdown = read(written.markdown);
  CHECK(markdown.find("### Snapshots") != std::string::npos);
  CHECK(markdown.find("(figures/silo-snapshot-1.png)") != std::string::npos);
  CHECK(read(options.out_dir / "figures" / "silo-snapshot-1.png") == kPng);
  CHECK(count(markdown, "missing picture: ") == 3);
  // one heading per figure, as in the HTML
  CHECK(count(markdown, "#### ") == 2);
  CHECK(count(markdown, "#### Fig. 8: discharge") == 1);
  CHECK(count(markdown, "#### Fig. 6: settled") == 1);
}

TEST_CASE("base64 pads as RFC 4648 says", "[report][snapshot]") {
  CHECK(report::base64("") == "");
  CHECK(report::base64("M") == "TQ==");
  CHECK(report::base64("Ma") == "TWE=");
  CHECK(report::base64("Man") == "TWFu");
  CHECK(report::base64(std::string("\xff\xfe\0", 3)) == "//4A");
}
