// The papers, item by item (reports/paper_claims*.hpp): the strict reader of verification/paper_claims.toml
// (mistakes planted one at a time, each refused with file:line), the table in the report (a failed check
// shows FAIL, a study without a result shows "no result", a selector that matches nothing in a present
// result is an error) and the project's own claims file (every study and finding it names exists).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "dem/cases/case_file.hpp"
#include "paper_claims_file.hpp"
#include "report.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

struct TempDir : test::TempDir {
  TempDir() : test::TempDir("dem2d_claims_test_") {}
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

/// A claims file that reads, beside two study folders (alpha with a study.toml, beta with a sensitivity.toml).
/// `from` is replaced by `to` (the planted mistake) so that each test differs from a good file in one place.
std::string good_claims() {
  return "[[claim]]\n"                                   // line 1
         "paper = \"Kiyama & Fujimura 1983\"\n"          // 2
         "item = \"Fig. 7\"\n"                           // 3
         "says = \"wall pressure levels off with depth\"\n"  // 4
         "study = \"alpha\"\n"                           // 5
         "check = \"bottom band\"\n"                     // 6
         "status = \"checked\"\n"                        // 7
         "note = \"holds below 0.6 of Janssen\"\n"       // 8
         "\n"                                            // 9
         "[[claim]]\n"                                   // 10
         "paper = \"Matsui & Nishimura 1999\"\n"         // 11
         "item = \"Table 2\"\n"                          // 12
         "says = \"other law choices change little\"\n"  // 13
         "study = \"beta\"\n"                            // 14
         "status = \"finding\"\n"                        // 15
         "finding = \"M-12\"\n"                          // 16
         "note = \"measured over a range\"\n";           // 17
}

fs::path claims_dir(const TempDir& tmp, const std::string& text) {
  write(tmp.path / "alpha" / "study.toml", "# a study\n");
  write(tmp.path / "beta" / "sensitivity.toml", "# a sweep\n");
  write(tmp.path / "claims.toml", text);
  return tmp.path / "claims.toml";
}

std::string planted(const std::string& from, const std::string& to) {
  std::string text = good_claims();
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

/// The error of reading the claims file with one mistake planted, or "" if it reads.
std::string error_of(const std::string& from, const std::string& to) {
  TempDir tmp;
  const auto file = claims_dir(tmp, planted(from, to));
  try {
    report::read_paper_claims(file);
  } catch (const dem::CaseError& e) {
    // the temp folder differs per run: keep "claims.toml:LINE: …"
    const std::string what = e.what();
    const auto at = what.find("claims.toml:");
    return at == std::string::npos ? what : what.substr(at);
  }
  return "";
}

}  // namespace

TEST_CASE("claims: a good file reads with every field", "[claims]") {
  TempDir tmp;
  const auto claims = report::read_paper_claims(claims_dir(tmp, good_claims()));
  REQUIRE(claims.size() == 2);
  CHECK(claims[0].paper == "Kiyama & Fujimura 1983");
  CHECK(claims[0].check == "bottom band");
  CHECK_THAT(claims[0].where, Contains("claims.toml:1"));
  CHECK(claims[1].finding == "M-12");
  CHECK_THAT(claims[1].where, Contains("claims.toml:10"));
}

TEST_CASE("claims: planted mistakes are refused with file:line", "[claims]") {
  CHECK_THAT(error_of("study = \"alpha\"", "stdy = \"alpha\""),
             StartsWith("claims.toml:5: claim.stdy: unknown key; did you mean 'study'?"));
  CHECK_THAT(error_of("status = \"checked\"", "status = \"chekced\""),
             StartsWith("claims.toml:7: claim.status: expected one of") && Contains("did you mean \"checked\"?"));
  CHECK_THAT(error_of("paper = \"Kiyama & Fujimura 1983\"", "paper = \"Kiyama 1983\""),
             StartsWith("claims.toml:2: claim.paper: expected one of"));
  CHECK_THAT(error_of("study = \"alpha\"", "study = \"alhpa\""),
             StartsWith("claims.toml:5: claim.study: no study folder") && Contains("did you mean \"alpha\"?"));
  CHECK_THAT(error_of("check = \"bottom band\"\n", ""),
             StartsWith("claims.toml:1: claim.check: missing: status \"checked\" needs the check rows"));
  CHECK_THAT(error_of("finding = \"M-12\"\n", ""), StartsWith("claims.toml:10: claim.finding: missing"));
  CHECK_THAT(error_of("finding = \"M-12\"", "finding = \"M12\""),
             StartsWith("claims.toml:16: claim.finding: expected a docs/findings.md entry"));
  CHECK_THAT(error_of("status = \"finding\"", "status = \"absent\"\ncheck = \"x\""),
             StartsWith("claims.toml:16: claim.check: an absent claim has no check"));
  CHECK_THAT(error_of("study = \"beta\"\n", "check = \"x\"\n"),
             StartsWith("claims.toml:14: claim.check: names a row of a study's result: give the study too"));
  CHECK_THAT(error_of("note = \"holds below 0.6 of Janssen\"\n", ""), StartsWith("claims.toml:1: claim.note: missing"));
  CHECK_THAT(error_of("says = \"wall pressure levels off with depth\"", "says = \"\""),
             StartsWith("claims.toml:4: claim.says: expected a text"));
  CHECK_THAT(error_of("[[claim]]\npaper = \"Matsui", "title = \"x\"\n[[claim]]\npaper = \"Matsui"),
             Contains("title: unknown key"));
  // an absent claim may name the study that is still to be written
  CHECK(error_of("study = \"beta\"\nstatus = \"finding\"", "study = \"gamma\"\nstatus = \"absent\"") == "");
}

namespace {

const char* alpha_result = R"json({
  "study": "alpha", "title": "Alpha", "passed": false,
  "checks": [
    { "quantity": "bottom band, K19", "reference": 168.0, "dem": 80.6, "error": -87.4, "tolerance": 0,
      "expect": "below", "passed": true },
    { "quantity": "bottom band, K18", "reference": 168.0, "dem": 190.5, "error": 22.5, "tolerance": 0,
      "expect": "below", "passed": false },
    { "quantity": "total force", "reference": 1.0, "dem": 1.0, "error": 0, "tolerance": 1e-6, "passed": true,
      "ci_low": 0.98, "ci_high": 1.02, "members": 8 }
  ],
  "figures": [
    { "id": "depth", "title": "Wall force against depth", "xlabel": "z", "ylabel": "f",
      "curves": [ { "label": "DEM", "x": [0, 1, 2], "y": [1, 2, 1.5], "style": "linespoints" } ] }
  ],
  "snapshots": [
    { "id": "network", "title": "Force network at the end", "variant": "v", "at": "end", "time": null, "step": null,
      "file": null, "note": "no picture: not drawn" }
  ]
})json";

/// Writes the claims (alpha's check rows, beta without result) and alpha's result, then the report.
report::Written report_with_claims(const TempDir& tmp, const std::string& claims) {
  write(tmp.path / "verification" / "alpha" / "study.toml", "#\n");
  write(tmp.path / "verification" / "beta" / "study.toml", "#\n");
  write(tmp.path / "verification" / "claims.toml", claims);
  write(tmp.path / "studies" / "alpha" / "result.json", alpha_result);
  report::Options options;
  options.studies_dir = tmp.path / "studies";
  options.out_dir = tmp.path / "report";
  options.claims_file = tmp.path / "verification" / "claims.toml";
  return report::write_report(options);
}

std::string claims_section(const fs::path& html) {
  const std::string page = read(html);
  const auto from = page.find("<section id=\"paper-claims\">");
  REQUIRE(from != std::string::npos);
  return page.substr(from, page.find("</section>", from) - from);
}

std::string claim(const std::string& item, const std::string& study, const std::string& extra, const std::string& status) {
  return "[[claim]]\npaper = \"Kiyama & Fujimura 1983\"\nitem = \"" + item + "\"\nsays = \"s\"\nstudy = \"" + study +
         "\"\n" + extra + "status = \"" + status + "\"\nnote = \"n\"\n\n";
}

}  // namespace

TEST_CASE("claims table: a failed check row shows FAIL and a study without result shows no result", "[claims]") {
  TempDir tmp;
  const auto written = report_with_claims(
      tmp, claim("Fig. 7", "alpha", "check = \"bottom band\"\nfigure = \"depth\"\n", "checked") +
               claim("Fig. 8", "beta", "check = \"anything\"\n", "checked") +
               claim("Conclusion 1", "alpha", "check = \"total force\"\n", "checked") +
               claim("Fig. 6", "alpha", "figure = \"network\"\n", "shown"));
  CHECK(written.claim_errors.empty());
  const std::string section = claims_section(written.html);
  // both rows of the selector, the failed one first, in red, and the claim marked FAIL
  CHECK_THAT(section, Contains("<span class=\"small\">bottom band:</span><br>"));  // the shared label once
  CHECK_THAT(section, Contains("K18</span>: DEM 190.5 &middot; ref. 168 <span class=\"badge fail\">FAIL</span>"));
  CHECK_THAT(section, Contains("K19</span>: DEM 80.6 &middot; ref. 168 <span class=\"badge pass\">PASS</span>"));
  CHECK_THAT(section, Contains("<span class=\"badge claim-checked\">checked</span> <span class=\"badge fail\">FAIL</span>"));
  CHECK(section.find("K18</span>") < section.find("K19</span>"));
  // the claim whose checks all passed carries no FAIL
  const auto conclusion = section.substr(section.find("Conclusion 1"));
  CHECK_THAT(conclusion.substr(0, conclusion.find("</tr>")), !Contains("badge fail"));
  CHECK_THAT(section, Contains("<span class=\"badge na\">no result</span>"));
  // an ensemble check shows the 95 % interval of its mean
  CHECK_THAT(section, Contains("DEM 1 <span class=\"small\">95 % CI [0.98, 1.02]</span> &middot; ref. 1"));
  // the counterpart links the study's section and the figure, which carries that id
  CHECK_THAT(section, Contains("href=\"#study-alpha\""));
  CHECK_THAT(section, Contains("href=\"#figure-alpha-depth\">Wall force against depth</a>"));
  const std::string page = read(written.html);
  CHECK_THAT(page, Contains("<figure id=\"figure-alpha-depth\">"));
  // a snapshot id links the heading of its gallery
  CHECK_THAT(section, Contains("href=\"#snapshot-alpha-network\">Force network at the end</a>"));
  CHECK_THAT(page, Contains("<h4 id=\"snapshot-alpha-network\">Force network at the end</h4>"));
  CHECK_THAT(page, Contains("<li><a href=\"#paper-claims\">The papers, item by item</a></li>"));
  CHECK_THAT(section, Contains("4 items: 3 checked, 1 shown, 0 finding, 0 absent; 1 with a failed check, 1 without a result."));
  const std::string markdown = read(written.markdown);
  CHECK_THAT(markdown, Contains("## The papers, item by item"));
  CHECK_THAT(markdown, Contains("bottom band, K18: DEM 190.5, ref. 168 **FAIL**"));
  CHECK_THAT(markdown, Contains("no result (study not run for this report)"));
}

TEST_CASE("claims table: a selector or figure that matches nothing in a present result is an error", "[claims]") {
  TempDir tmp;
  const auto written = report_with_claims(
      tmp, claim("Fig. 7", "alpha", "check = \"botom band\"\n", "checked") +
               claim("Fig. 6", "alpha", "figure = \"dpeth\"\n", "shown") +
               claim("Fig. 8", "beta", "check = \"botom band\"\n", "checked"));  // no result: not an error
  REQUIRE(written.claim_errors.size() == 2);
  CHECK_THAT(written.claim_errors[0], Contains("claims.toml:1: claim (Kiyama & Fujimura 1983, Fig. 7): check \"botom band\" "
                                               "matches none of the 3 check rows of"));
  CHECK_THAT(written.claim_errors[1], Contains("claims.toml:10: claim (Kiyama & Fujimura 1983, Fig. 6): figure \"dpeth\" is "
                                               "not among the 1 figures and 1 snapshots of"));
  const std::string section = claims_section(written.html);
  CHECK_THAT(section, Contains("<span class=\"badge fail\">error</span>"));
  CHECK_THAT(section, Contains("with a selector that matches nothing"));
}

TEST_CASE("claims table: a claims file that does not read stops the report before anything is written", "[claims]") {
  TempDir tmp;
  CHECK_THROWS_AS(report_with_claims(tmp, claim("Fig. 7", "alpha", "chek = \"x\"\n", "shown")), dem::CaseError);
  CHECK_FALSE(fs::exists(tmp.path / "report" / "index.html"));
}

TEST_CASE("claims: the project's paper_claims.toml reads and names existing studies and findings", "[claims]") {
  const fs::path source(DEM2D_SOURCE_DIR);
  const auto claims = report::read_paper_claims(source / "verification" / "paper_claims.toml");
  const std::string findings = read(source / "docs" / "findings.md");
  std::set<std::string> papers;
  for (const auto& c : claims) {
    INFO(c.where << ": " << c.paper << ", " << c.item);
    papers.insert(c.paper);
    // every study a claim names is a folder of verification/ (a renamed study breaks this); an absent claim
    // may name the study that is still to be written
    if (!c.study.empty() && c.status != "absent") CHECK(fs::is_directory(source / "verification" / c.study));
    // every finding is an entry of docs/findings.md ("**K-9. …", "**F8 (M-C). …")
    if (!c.finding.empty())
      CHECK((findings.find("\n**" + c.finding + ".") != std::string::npos ||
             findings.find("\n**" + c.finding + " (") != std::string::npos));
  }
  CHECK(papers.size() == 2);
  CHECK(claims.size() >= 50);
}
