// The report never leaves a half-written file under a final name (reports/report.cpp, gnuplot_plot.cpp):
// index.html and index.md go through a temporary name and a rename, so a full disk keeps the previous report
// whole and throws dem::OutputError (exit status 4); an SVG that gnuplot leaves cut (no closing </svg>, as
// on a full disk) is not counted as drawn and not kept.
#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/resource.h>

#include "dem/run/output_files.hpp"
#include "report.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;

const char* study_with_figure = R"json({
  "study": "s", "title": "A study with one figure", "kind": "refinement", "passed": true,
  "checks": [ { "quantity": "q", "reference": 1.0, "dem": 1.0, "error": 0.0, "error_kind": "abs", "tolerance": 0.1,
                "tolerance_reason": "r", "passed": true } ],
  "figures": [ { "id": "f", "title": "F", "xlabel": "x", "ylabel": "y", "logx": false, "logy": false,
                 "curves": [ { "label": "a", "x": [0, 1, 2], "y": [0, 1, 4], "style": "lines" } ] } ]
})json";

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream b;
  b << in.rdbuf();
  return b.str();
}

report::Options options_in(const fs::path& root) {
  fs::create_directories(root / "studies" / "s");
  std::ofstream(root / "studies" / "s" / "result.json") << study_with_figure;
  report::Options o;
  o.studies_dir = root / "studies";
  o.out_dir = root / "report";
  return o;
}

}  // namespace

TEST_CASE("report on a full disk keeps the previous index.html whole and throws an output error", "[report]") {
  test::TempDir tmp("dem2d_report_full_");
  const report::Options o = options_in(tmp.path);
  const auto first = report::write_report(o, tmp.path / "no_such_gnuplot");
  const std::string before = read(first.html);
  REQUIRE(before.size() > 4096);  // larger than the limit below
  // A file size limit of 4 kB: every write past it fails (EFBIG), as on a full disk.
  auto* old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit old{};
  getrlimit(RLIMIT_FSIZE, &old);
  rlimit small = old;
  small.rlim_cur = 4096;
  setrlimit(RLIMIT_FSIZE, &small);
  bool output_error = false;
  try {
    report::write_report(o, tmp.path / "no_such_gnuplot");
  } catch (const dem::OutputError&) {
    output_error = true;
  } catch (const std::exception&) {
  }
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  CHECK(output_error);
  CHECK(read(first.html) == before);
  for (const auto& entry : fs::directory_iterator(o.out_dir)) CHECK(entry.path().extension() != ".tmp");
}

TEST_CASE("a cut SVG from gnuplot is not counted as drawn and not kept", "[report]") {
  test::TempDir tmp("dem2d_report_cut_svg_");
  const report::Options o = options_in(tmp.path);
  // A gnuplot that writes the first bytes of an SVG to its output and exits 0 (a full disk cut the rest).
  const fs::path fake = tmp.path / "cut_gnuplot.sh";
  std::ofstream(fake) << "#!/bin/sh\nout=$(sed -n \"s/^set output '\\(.*\\)'/\\1/p\" \"$1\")\n"
                         "printf '<svg width=\"600\" height=\"400\"><g>' > \"$out\"\nexit 0\n";
  fs::permissions(fake, fs::perms::owner_all);
  const auto written = report::write_report(o, fake);
  CHECK(written.figures == 0);
  const std::string html = read(written.html);
  CHECK(html.find("incomplete SVG") != std::string::npos);
  for (const auto& entry : fs::directory_iterator(o.out_dir / "figures")) {
    INFO(entry.path().string());
    CHECK(entry.path().extension() != ".svg");
    CHECK(entry.path().extension() != ".partial");
  }
}
