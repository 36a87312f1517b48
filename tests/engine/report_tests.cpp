// Unit tests of the report generator (reports/report.hpp) on fixture result.json files written to a
// temporary folder: one passing study (series + figure + tables), one failing, one malformed.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>

#include "gnuplot_plot.hpp"
#include "report.hpp"
#include "temp_dir.hpp"
#include "report_content.hpp"
#include "study_result.hpp"

namespace {

namespace fs = std::filesystem;

struct TempDir : test::TempDir {
  TempDir() : test::TempDir("dem2d_report_test_") {}
};

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

const char* passing_study = R"json({
  "study": "impact_restitution",
  "title": "Normal impact: restitution & contact duration",
  "requirement": "The linear spring-dashpot reproduces the analytic restitution coefficient.",
  "kind": "refinement",
  "case": "cases/impact/disk_wall.toml",
  "parameter": "numerics.dt",
  "reference": "closed form e(zeta) (K18), reference/",
  "setup": { "zeta": 0.3, "radius [m]": 0.01, "law": "linear_dashpot" },
  "provenance": { "code_version": "v0.1-3-gabc", "build_type": "Release", "date": "2024-05-01T10:00:00Z",
                  "machine": "testhost", "overrides": ["numerics.dt=1e-6"] },
  "passed": true,
  "checks": [
    { "quantity": "e, zeta=0.3 (K18)", "reference": 0.3723261049, "dem": 0.37241, "error": 8.4e-5,
      "error_kind": "abs", "tolerance": 1e-3, "tolerance_reason": "first order in dt at dt = t_c/50",
      "observed_order": 1.01, "expected_order": 1.0, "order_band": 0.15, "passed": true, "note": "" }
  ],
  "series": [
    { "name": "e, zeta=0.3 (K18)", "parameter": "dt [s]", "h": [1e-5, 5e-6, 2.5e-6],
      "value": [0.36, 0.366, 0.369], "reference": 0.3723, "error": [1.23e-2, 6.3e-3, 3.3e-3],
      "observed_order": [null, 0.965, 0.933], "fitted_order": 0.95, "expected_order": 1.0,
      "richardson": 0.372, "gci_fine": 0.0012, "asymptotic_ratio": 1.003, "asymptotic": true }
  ],
  "figures": [
    { "id": "delta_t", "title": "Overlap history delta_t", "xlabel": "t [s]", "ylabel": "delta [mm]",
      "logx": false, "logy": false,
      "curves": [ { "label": "reference", "x": [0, 1, 2, 3], "y": [0, 0.8, 0.9, 0.1], "style": "lines" },
                  { "label": "DEM", "x": [0, 1, 2, 3], "y": [0, 0.79, 0.91, 0.12], "style": "points" } ] }
  ],
  "tables": [
    { "title": "Mode map", "columns": ["alpha", "ref", "dem"], "rows": [["5", "stick", "stick"], [10, "slip", "slip"]] },
    { "title": "Mode map (text)", "preformatted": "alpha  mode\n5      <stick>" }
  ]
})json";

const char* failing_study = R"json({
  "study": "block_on_slope",
  "title": "Block on a slope",
  "requirement": "Sliding distance matches Sagaseta.",
  "kind": "single",
  "case": "cases/slope/block.toml",
  "parameter": "",
  "reference": "Sagaseta closed form",
  "provenance": { "code_version": "v0.1-3-gabc", "build_type": "Release", "date": "2024-05-01T11:00:00Z",
                  "machine": "testhost" },
  "passed": false,
  "checks": [
    { "quantity": "slide distance [mm]", "reference": 12.5, "dem": 14.1, "error": 0.128,
      "error_kind": "rel", "tolerance": 0.02, "tolerance_reason": "2 % from the paper",
      "observed_order": null, "expected_order": null, "order_band": null, "passed": false,
      "note": "friction law mismatch?" }
  ],
  "series": [
    { "name": "all zero", "parameter": "dt [s]", "h": [1e-3, 5e-4], "value": [1, 1], "reference": 1,
      "error": [0, null], "observed_order": [null, null], "fitted_order": null, "expected_order": 2,
      "richardson": null, "gci_fine": null, "asymptotic_ratio": null, "asymptotic": null }
  ]
})json";

}  // namespace

TEST_CASE("report of two studies: HTML self-contained, Markdown links figures", "[report]") {
  TempDir tmp;
  const auto studies = tmp.path / "studies";
  write(studies / "impact_restitution" / "result.json", passing_study);
  write(studies / "block_on_slope" / "result.json", failing_study);
  fs::create_directories(studies / "no_result_yet");  // skipped: no result.json

  report::Options options;
  options.studies_dir = studies;
  options.out_dir = tmp.path / "report";
  options.title = "Fixture report";
  options.provenance = {{"code_version", "v0.1-3-gabc"}, {"build_type", "Release"}};
  const auto written = report::write_report(options);

  CHECK(written.studies == 2);
  CHECK(written.figures == 2);  // the all-zero series is skipped
  REQUIRE(fs::exists(written.html));
  const auto html = read(written.html);
  CHECK(html.find("impact_restitution") != std::string::npos);
  CHECK(html.find("block_on_slope") != std::string::npos);
  CHECK(count(html, "<svg") == 2);
  CHECK(html.find("FAIL") != std::string::npos);
  CHECK(html.find("PASS") != std::string::npos);
  CHECK(html.find("slope 1") != std::string::npos);  // reference slope label, inside the SVG
  CHECK(html.find("all errors are zero or missing") != std::string::npos);
  CHECK(html.find("restitution &amp; contact") != std::string::npos);  // escaped
  CHECK(html.find("&lt;stick&gt;") != std::string::npos);
  CHECK(html.find("v0.1-3-gabc") != std::string::npos);
  CHECK(html.find("1 passed") != std::string::npos);
  CHECK(html.find("1 failed") != std::string::npos);
  CHECK(html.find("without verdict") == std::string::npos);  // every check has one
  // a study's table with its rows, a number cell and text cells
  CHECK(count(html, ">stick<") == 2);
  CHECK(count(html, ">slip<") == 2);
  CHECK(html.find(">10<") != std::string::npos);
  // each convergence series with its one-line summary under the figure
  const std::string summary = report::series_summary(nlohmann::json::parse(passing_study)["series"][0]);
  CAPTURE(summary);
  REQUIRE_FALSE(summary.empty());
  CHECK(html.find("<p class=\"small\">" + summary + "</p>") != std::string::npos);
  // Self-contained: no external resources, no http at all (SVG namespaces are stripped).
  CHECK(html.find("http") == std::string::npos);
  CHECK_FALSE(std::regex_search(html, std::regex(R"(\b(src|href)\s*=\s*["'](?!#))")));
  CHECK(html.find("<?xml") == std::string::npos);

  REQUIRE(fs::exists(written.markdown));
  const auto markdown = read(written.markdown);
  const std::regex image_link(R"(!\[[^\]]*\]\(([^)]+\.svg)\))");
  int links = 0;
  for (auto it = std::sregex_iterator(markdown.begin(), markdown.end(), image_link);
       it != std::sregex_iterator(); ++it) {
    const auto file = options.out_dir / (*it)[1].str();
    CAPTURE(file);
    CHECK((*it)[1].str().rfind("figures/", 0) == 0);
    CHECK(fs::exists(file));
    CHECK(read(file).find("<svg") != std::string::npos);
    ++links;
  }
  CHECK(links == 2);
  // figures are numbered from 1 in their study: the first figure (id delta_t) is figure 1
  CHECK(markdown.find("(figures/impact_restitution-figure-1-delta") != std::string::npos);
  CHECK(markdown.find("FAIL") != std::string::npos);
  CHECK(markdown.find("block\\_on\\_slope") != std::string::npos);
}

TEST_CASE("a malformed result.json is reported, not fatal", "[report]") {
  TempDir tmp;
  const auto studies = tmp.path / "studies";
  write(studies / "a_good" / "result.json", failing_study);
  write(studies / "b_broken" / "result.json", "{ \"study\": \"b_broken\", \"checks\": [ }");
  write(studies / "c_not_object" / "result.json", "[1, 2]");

  report::Options options;
  options.studies_dir = studies;
  options.out_dir = tmp.path / "out";
  const auto written = report::write_report(options);
  CHECK(written.studies == 3);
  const auto html = read(written.html);
  CHECK(count(html, "UNREADABLE") >= 2);
  CHECK(html.find("b_broken") != std::string::npos);
  CHECK(html.find("parse error") != std::string::npos);  // the JSON error is shown
  CHECK(html.find("block_on_slope") != std::string::npos);
  CHECK(html.find("2 unreadable or broken") != std::string::npos);
  CHECK(read(written.markdown).find("UNREADABLE") != std::string::npos);
}

TEST_CASE("a study's status is recomputed from its checks, and what does not add up is BROKEN", "[report]") {
  auto status_of = [](const std::string& text) {
    TempDir tmp;
    write(tmp.path / "studies" / "s" / "result.json", text);
    const auto studies = report::read_study_results(tmp.path / "studies");
    REQUIRE(studies.size() == 1);
    return report::study_status(studies.front());
  };
  const std::string good = passing_study, bad = failing_study;
  CHECK(status_of(good) == "PASS");
  CHECK(status_of(bad) == "FAIL");
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
  };
  // "passed": true beside a failed check: the file's verdict is not taken
  CHECK(status_of(replaced(bad, "\"passed\": false,\n  \"checks\"", "\"passed\": true,\n  \"checks\"")) == "BROKEN");
  // checks that are not a list, or none at all
  const auto from = good.find("\"checks\": [");
  const auto to = good.find("\"series\": [");
  CHECK(status_of(good.substr(0, from) + "\"checks\": \"x\",\n  " + good.substr(to)) == "BROKEN");
  CHECK(status_of(good.substr(0, from) + "\"checks\": [],\n  " + good.substr(to)) == "BROKEN");
  CHECK(status_of(replaced(good, "\"passed\": true, \"note\"", "\"passed\": \"yes\", \"note\"")) == "BROKEN");
  // 10^5 levels of nesting: refused, not a stack overflow
  CHECK(status_of("{\"checks\": " + std::string(100000, '[') + std::string(100000, ']') + "}") == "UNREADABLE");
  TempDir tmp;  // a result.json that is a folder is listed as unreadable, not skipped
  fs::create_directories(tmp.path / "studies" / "d" / "result.json");
  const auto studies = report::read_study_results(tmp.path / "studies");
  REQUIRE(studies.size() == 1);
  CHECK(report::study_status(studies.front()) == "UNREADABLE");
  CHECK(studies.front().read_error == "result.json is not a file");
}

TEST_CASE("a study served from the run cache says so beside its wall time", "[report]") {
  TempDir tmp;
  std::string text = passing_study;
  const std::string from = "\"overrides\": [\"numerics.dt=1e-6\"] },";
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), "\"overrides\": [\"numerics.dt=1e-6\"], \"wall_time_s\": 0.04, \"command\": \"dem2d study x\", "
                                "\"runs_run\": 0, \"runs_reused\": 12, \"reused_run_seconds\": 1.3, "
                                "\"reused_code_version\": \"v9-1-gabc\", \"reused_date\": \"2026-11-27T04:58:01Z\" },");
  write(tmp.path / "studies" / "cached" / "result.json", text);
  report::Options options;
  options.studies_dir = tmp.path / "studies";
  options.out_dir = tmp.path / "out";
  const auto written = report::write_report(options);
  const std::string words = "wall time 0.0 s; 12 of 12 runs reused from the cache (their original run time 1.3 s, code v9-1-gabc, 2026-11-27T04:58:01Z)";
  CHECK(read(written.html).find(words) != std::string::npos);
  CHECK(read(written.markdown).find(words) != std::string::npos);
  CHECK(read(written.html).find("0.0 s (12/12 cached, originally 1.3 s)") != std::string::npos);
  // a study that ran everything: the wall time alone
  CHECK(report::wall_time_words(nlohmann::json{{"wall_time_s", 2.25}, {"runs_run", 3}, {"runs_reused", 0}}) == "2.2 s");
}

TEST_CASE("a failing gnuplot is noted in place of the figure", "[report]") {
  TempDir tmp;
  const auto studies = tmp.path / "studies";
  write(studies / "impact_restitution" / "result.json", passing_study);
  report::Options options;
  options.studies_dir = studies;
  options.out_dir = tmp.path / "out";
  const auto written = report::write_report(options, tmp.path / "no_such_gnuplot");
  CHECK(written.figures == 0);
  const auto html = read(written.html);
  CHECK(count(html, "<svg") == 0);
  CHECK(html.find("gnuplot failed") != std::string::npos);
}

TEST_CASE("missing studies folder throws", "[report]") {
  TempDir tmp;
  report::Options options;
  options.studies_dir = tmp.path / "nothing_here";
  options.out_dir = tmp.path / "out";
  CHECK_THROWS_AS(report::write_report(options), std::runtime_error);
}

namespace {

// A study with a direction check (expect = above, tolerance 0), a trend check, a README, wall time,
// a figure with an x range and a series whose check bounds the absolute error.
const char* direction_study = R"json({
  "study": "small_rotation",
  "title": "M-B small rotation",
  "kind": "single",
  "readme": "# small_rotation\n\nPurpose line one\ncontinued.\n\nKnown limit: Hisatake drifts.\n",
  "provenance": { "code_version": "v1", "date": "2024-05-01T10:00:00Z", "wall_time_s": 12.34,
                  "command": "dem2d study verification/small_rotation/study.toml --out x --jobs 2" },
  "passed": true,
  "checks": [
    { "quantity": "overshoot [m]", "reference": 0.0125, "dem": 0.0125019, "error": 1.9e-6,
      "error_kind": "abs", "tolerance": 0, "tolerance_reason": "r", "expect": "above",
      "observed_order": null, "expected_order": null, "order_band": null, "passed": true, "note": "" },
    { "quantity": "peak falls with N", "reference": null, "dem": 2600, "error": 60,
      "error_kind": "abs", "tolerance": 0, "tolerance_reason": "r", "expect": "decreasing",
      "observed_order": null, "expected_order": null, "order_band": null, "passed": true, "note": "values: ..." },
    { "quantity": "e (K18)", "reference": 0.37, "dem": 0.3701, "error": 1e-4,
      "error_kind": "abs", "tolerance": 2e-3, "tolerance_reason": "r", "expect": "within",
      "observed_order": 1.02, "expected_order": 1.0, "order_band": 0.2, "passed": true, "note": "" }
  ],
  "series": [
    { "name": "e (K18)", "parameter": "dt [s]", "h": [1e-5, 5e-6, 2.5e-6],
      "value": [0.36, 0.366, 0.369], "reference": 0.37, "error": [1e-2, 4e-3, 1e-3],
      "observed_order": [null, 1.3, 2.0], "fitted_order": 1.02, "expected_order": 1.0 }
  ],
  "figures": [
    { "id": "tangential", "title": "first ms", "xlabel": "t [ms]", "ylabel": "x [um]", "xrange": [0, 1],
      "curves": [ { "label": "exact", "x": [0, 0.5, 1, 20], "y": [1, 2, 3, 4], "style": "lines" },
                  { "label": "linearised", "x": [0, 0.5, 1, 20], "y": [1, 2, 3, 4], "style": "lines" },
                  { "label": "reference", "x": [0, 1], "y": [0, 0], "style": "reference" } ] }
  ]
})json";

}  // namespace

TEST_CASE("check directions are stated in words, overview and README are shown", "[report]") {
  TempDir tmp;
  write(tmp.path / "studies" / "small_rotation" / "result.json", direction_study);
  report::Options options;
  options.studies_dir = tmp.path / "studies";
  options.out_dir = tmp.path / "report";
  const auto written = report::write_report(options);
  const auto html = read(written.html), md = read(written.markdown);
  for (const auto* page : {&html, &md}) {
    CHECK(std::regex_search(*page, std::regex("DEM (&gt;|\\\\>|>) reference \\+ tol")));
    CHECK(page->find("decreases from variant to variant") != std::string::npos);
    CHECK(page->find("≤ tol") != std::string::npos);
    CHECK(page->find("Purpose line one") != std::string::npos);
    CHECK(page->find("Known limit: Hisatake drifts.") != std::string::npos);
    CHECK(page->find("12.3 s") != std::string::npos);  // wall time in the overview
    CHECK(page->find("dem2d study verification/small_rotation/study.toml") != std::string::npos);
    CHECK(page->find("Observed orders") != std::string::npos);
    CHECK(page->find("1.02 (1)") != std::string::npos);
  }
  CHECK(html.find("id=\"contents\"") != std::string::npos);
  CHECK(html.find("href=\"#study-small_rotation\"") != std::string::npos);
  CHECK(html.find(">CPU<") + html.find(">OS<") != 2 * std::string::npos);
}

TEST_CASE("declared x range, distinct curve styles, key below and the tolerance line reach gnuplot", "[report]") {
  TempDir tmp;
  write(tmp.path / "studies" / "small_rotation" / "result.json", direction_study);
  report::Options options;
  options.studies_dir = tmp.path / "studies";
  options.out_dir = tmp.path / "report";
  report::write_report(options);
  std::string figure, convergence;
  for (const auto& entry : fs::directory_iterator(options.out_dir / "figures")) {
    if (entry.path().extension() != ".gp") continue;
    (entry.path().string().find("convergence") != std::string::npos ? convergence : figure) = read(entry.path());
  }
  REQUIRE(!figure.empty());
  REQUIRE(!convergence.empty());
  CHECK(figure.find("set xrange [0:1]") != std::string::npos);
  CHECK(figure.find("set key below") != std::string::npos);
  CHECK(figure.find("with lines dt 1") != std::string::npos);  // first curve solid
  CHECK(figure.find("with lines dt 2 lw 2.4") != std::string::npos);  // second dashed, thinner
  CHECK(figure.find("lc rgb '#000000'") != std::string::npos);  // the reference in black
  CHECK(convergence.find("title 'tolerance 0.002'") != std::string::npos);
  CHECK(convergence.find("abs. error") != std::string::npos);
}

TEST_CASE("a narrow linear range gets enough tick digits that neighbours differ", "[report]") {
  report::Plot plot;
  report::Curve c;
  c.x = {0, 1, 2};
  c.y = {12500000.0, 12500000.5, 12500001.0};  // e0.y in nm: offset 1.25e7, span 1
  plot.curves.push_back(c);
  const auto script = report::gnuplot_script(plot, "x.svg");
  CHECK(script.find("set format y '%.11g'") != std::string::npos);
  CHECK(script.find("set format x") == std::string::npos);
}

TEST_CASE("several reference curves in one figure get distinct dash patterns, one reference keeps its dashes", "[report]") {
  report::Plot plot;
  plot.title = "Fig. 9";
  report::Curve dem{"DEM", {0.0, 1.0}, {0.0, 1.0}, "lines"};
  report::Curve bg{"Bray and Goodman", {0.0, 1.0}, {0.0, 1.1}, "reference"};
  report::Curve pre{"PRE model", {0.0, 1.0}, {0.0, 1.05}, "reference"};
  plot.curves = {dem, bg};
  const std::string one = report::gnuplot_script(plot, "one.svg");
  CHECK(one.find("with lines dt 2 lw 2.5 lc rgb '#000000' title 'Bray and Goodman'") != std::string::npos);
  plot.curves = {dem, bg, pre};
  const std::string two = report::gnuplot_script(plot, "two.svg");
  CHECK(two.find("with lines dt 2 lw 2.5 lc rgb '#000000' title 'Bray and Goodman'") != std::string::npos);
  CHECK(two.find("with lines dt 4 lw 2.5 lc rgb '#000000' title 'PRE model'") != std::string::npos);
}

TEST_CASE("the speed benchmark's newest table and its plot are shown, an older one is not", "[report][speed]") {
  TempDir tmp;
  write(tmp.path / "studies/small_rotation/result.json", direction_study);
  const fs::path kept = tmp.path / "bench_results";  // as bench/results: tables by date, plots beside them
  write(kept / "suite_2026-01-05.md", "| settle | after 1T / LAMMPS |\n|---|---|\n| 1e4 disks | 2.22 |\n");
  write(kept / "cost_2026-01-05.svg", "<svg width=\"10\" height=\"10\"><text>older plot</text></svg>");
  write(kept / "suite_2026-02-01.md", "Machine: test host.\n\n| settle | after 1T / LAMMPS |\n|---|---|\n| 1e4 disks | 3.76 |\n");
  write(kept / "cost_2026-02-01.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"420\"><text>newer plot</text></svg>");
  write(kept / "notes.md", "| not | a table of the suite |\n");
  report::Options options;
  options.studies_dir = tmp.path / "studies";
  options.out_dir = tmp.path / "out";
  options.bench_dir = kept;
  report::write_report(options);
  const std::string html = read(tmp.path / "out/index.html"), md = read(tmp.path / "out/index.md");
  CHECK(count(html, "<section id=\"speed\">") == 1);
  CHECK(count(html, "href=\"#speed\"") == 1);  // in the contents
  CHECK(html.find("<td>3.76</td>") != std::string::npos);
  CHECK(html.find("2.22") == std::string::npos);
  CHECK(html.find("newer plot") != std::string::npos);
  CHECK(html.find("older plot") == std::string::npos);
  CHECK(html.find("viewBox=\"0 0 640 420\"") != std::string::npos);  // scales without stretching its box
  CHECK(html.find("suite_2026-02-01.md") != std::string::npos);
  CHECK(md.find("| 1e4 disks | 3.76 |") != std::string::npos);
  CHECK(md.find("](figures/speed_cost.svg)") != std::string::npos);
  CHECK(read(tmp.path / "out/figures/speed_cost.svg").find("newer plot") != std::string::npos);

  // a suite's own output folder (table.md, cost.svg) is taken as it is
  const fs::path suite = tmp.path / "suite_out";
  write(suite / "table.md", "| settle | after 1T / LAMMPS |\n|---|---|\n| 1e5 disks | 3.96 |\n");
  options.bench_dir = suite;
  options.out_dir = tmp.path / "out2";
  report::write_report(options);
  const std::string html2 = read(tmp.path / "out2/index.html");
  CHECK(html2.find("<td>3.96</td>") != std::string::npos);
  CHECK(count(html2, "<figure style=\"max-width: 760px\">") == 0);  // no plot there, none shown
  CHECK_FALSE(fs::exists(tmp.path / "out2/figures/speed_cost.svg"));

  // no tables: no section
  options.bench_dir = tmp.path / "studies";
  options.out_dir = tmp.path / "out3";
  report::write_report(options);
  CHECK(read(tmp.path / "out3/index.html").find("id=\"speed\"") == std::string::npos);
}

TEST_CASE("a tic label with a percent sign is drawn as written - gnuplot reads tic labels as formats", "[report]") {
  report::Plot plot;
  report::Curve c;
  c.x = {1, 2};
  c.y = {1.0, 2.0};
  plot.curves.push_back(c);
  plot.xticks = {{1.0, "fill gap (dummy: ±3 %)"}, {2.0, "φ"}};
  const auto script = report::gnuplot_script(plot, "x.svg");
  CHECK(script.find("'fill gap (dummy: ±3 %%)' 1") != std::string::npos);
  TempDir tmp;
  const auto outcome = report::render_svg(plot, tmp.path / "ticks.svg", GNUPLOT_EXECUTABLE);
  CHECK(outcome.error == "");
  CHECK(outcome.ok);
}

TEST_CASE("the header's machine lines: the first CPU model and the processors counted, no line ends", "[report]") {
  const auto cpu = report::cpu_field("processor\t: 0\nvendor_id\t: X\nmodel name\t: Alpha 1\n\nprocessor\t: 1\n"
                                     "model name\t: Beta 2\n");
  REQUIRE(cpu);
  CHECK(cpu->label == "CPU");
  CHECK(cpu->value == "Alpha 1 (2 logical cores)");
  CHECK_FALSE(report::cpu_field("processor\t: 0\nBogoMIPS\t: 50.00\nprocessor\t: 1\n"));  // no model name (ARM)
  for (const auto& f : report::machine_fields()) {  // what the system and gnuplot print, their line ends cut
    CAPTURE(f.label, f.value);
    CHECK_FALSE(f.value.empty());
    CHECK(f.value.find('\n') == std::string::npos);
    CHECK(f.value.find('\r') == std::string::npos);
  }
}
