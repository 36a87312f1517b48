// The map of what is verified (reports/feature_matrix.hpp): labels read as the docs write them, a group
// covering its sub-labels and no other, the code-site tables of model.md read row by row, and a study
// counted as checking a row only through its check rows.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "feature_matrix.hpp"

using report::covers;
using report::cited_labels;

TEST_CASE("feature matrix: labels are whole tokens - K1 is not K18 and K-16 is a finding not a label") {
  CHECK(cited_labels("(K19) and K18, M15.1; K-16 M-A F13 GK7 x9M") == std::vector<std::string>{"K19", "K18", "M15.1"});
  CHECK(cited_labels("K1 K1.a K1") == std::vector<std::string>{"K1", "K1.a"});
}

TEST_CASE("feature matrix: a group covers its sub-labels - a sub-label its group - nothing else") {
  CHECK(covers("M15", "M15"));
  CHECK(covers("M15.1", "M15"));
  CHECK(covers("M15", "M15.1"));
  CHECK_FALSE(covers("M15.1", "M15.2"));
  CHECK_FALSE(covers("M1", "M15"));
  CHECK_FALSE(covers("K19", "K1"));
}

TEST_CASE("feature matrix: the code-site tables of model.md - ranges expanded - other tables ignored") {
  const std::string md =
      "Text K99 that is not a table.\n\n"
      "| Equations | What | Code |\n|---|---|---|\n"
      "| K6–K8 | increments | `lib/x.hpp` |\n"
      "| M15.1, M15.2 | linearised increments | `lib/y.hpp` |\n\n"
      "| Symbol | Meaning | Unit |\n|---|---|---|\n| K9 | not a code site | m |\n";
  const auto rows = report::feature_rows(md);
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].labels == std::vector<std::string>{"K6", "K7", "K8"});
  CHECK(rows[0].what == "increments");
  CHECK(rows[1].labels == std::vector<std::string>{"M15.1", "M15.2"});
}

TEST_CASE("feature matrix: a study checks a row through its check rows - shows it through its text - else neither") {
  const std::string md = "| Equations | What | Code |\n|---|---|---|\n| K19 | averaged increment | c |\n"
                         "| K21 | stability | c |\n| M8 | tension cut-off | c |\n";
  auto study = [](const std::string& folder, nlohmann::json result) {
    report::StudyReport s;
    s.source.folder = folder;
    s.source.result = std::move(result);
    return s;
  };
  std::vector<report::StudyReport> studies;
  studies.push_back(study("a", {{"checks", {{{"label", "largest stable dt, K19"}, {"passed", true}}}}, {"readme", "about K21"}}));
  studies.push_back(study("b", {{"checks", {{{"label", "something"}, {"passed", true}}}}, {"title", "K19 and K21 in words"}}));
  const auto rows = report::match_features(report::feature_rows(md), studies);
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].checked_by == std::vector<std::string>{"a"});
  CHECK(rows[0].shown_in == std::vector<std::string>{"b"});
  CHECK(rows[1].checked_by.empty());
  CHECK(rows[1].shown_in == std::vector<std::string>{"a", "b"});
  CHECK(rows[2].checked_by.empty());
  CHECK(rows[2].shown_in.empty());
  const std::string html = report::features_html(rows);
  CHECK(html.find("1 of 3") != std::string::npos);
  CHECK(html.find("class=\"unchecked\"") != std::string::npos);
}

TEST_CASE("feature matrix: a group and a sub-label with rows of their own are cited apart") {
  // M19 (the paper's lever) and M19.r (an alternative) each head a row: a check of one is no check of
  // the other; M15's sub-labels have no row of their own, so M15.1 still covers the row M15.
  const std::string md = "| Equations | What | Code |\n|---|---|---|\n| M19 | wall lever | c |\n"
                         "| M19.r | corner lever | c |\n| M15 | linearised | c |\n";
  auto study = [](const std::string& folder, const std::string& label) {
    report::StudyReport s;
    s.source.folder = folder;
    s.source.result = {{"checks", {{{"label", label}, {"passed", true}}}}};
    return s;
  };
  const std::vector<report::StudyReport> studies{study("wall", "theta (M19, M15.1)"), study("corner", "theta (M19.r)")};
  const auto rows = report::match_features(report::feature_rows(md), studies);
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].checked_by == std::vector<std::string>{"wall"});
  CHECK(rows[1].checked_by == std::vector<std::string>{"corner"});
  CHECK(rows[2].checked_by == std::vector<std::string>{"wall"});
}

TEST_CASE("feature matrix: model.md's why-not table explains an unchecked row - a checked row keeps its studies") {
  const std::string md = "| Equations | What | Code |\n|---|---|---|\n| M14.1, M14.2 | linearised displacements | - |\n"
                         "| K27 | neighbour search | c |\n| M8 | tension cut-off | c |\n\n"
                         "| Equations | Why no study checks it |\n|---|---|\n| M14.1, M14.2 | only their increments are used |\n"
                         "| M8 | a reason that a check overrides |\n| K99 | a row that is not in the code tables |\n";
  report::StudyReport s;
  s.source.folder = "a";
  s.source.result = {{"checks", {{{"label", "cut-off (M8)"}, {"passed", true}}}}};
  const auto rows = report::match_features(report::feature_rows(md), {s});
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].not_checkable == "only their increments are used");
  CHECK(rows[1].not_checkable.empty());
  CHECK(rows[2].checked_by == std::vector<std::string>{"a"});
  const std::string html = report::features_html(rows);
  CHECK(html.find("1 of 3</strong> rows are checked; not checkable") != std::string::npos);
  CHECK(html.find("<tr class=\"not-checkable\"><td>M14.1, M14.2</td>") != std::string::npos);
  CHECK(html.find("<em>not checkable</em>: only their increments are used") != std::string::npos);
  CHECK(html.find("<tr class=\"unchecked\"><td>K27</td>") != std::string::npos);
  CHECK(html.find("a reason that a check overrides") == std::string::npos);
  const std::string md_out = report::features_markdown(rows);
  CHECK(md_out.find("| M14.1, M14.2 | linearised displacements | not checkable: only their increments are used |") != std::string::npos);
  CHECK(md_out.find("| **K27** |") != std::string::npos);
  CHECK(md_out.find("own (a definition or a choice; the reason stands in the row): 1; unchecked, in bold: 1.") != std::string::npos);
}
