// The sensitivity overview of the report (reports/sensitivity_overview.hpp): one row per sensitivity
// study and output, the strongest measure the study computed, most and least influential parameter.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "report.hpp"
#include "sensitivity_overview.hpp"

namespace {

report::StudyReport study(const std::string& folder, const std::string& json) {
  report::StudyReport s;
  s.source.folder = folder;
  s.source.result = nlohmann::json::parse(json);
  return s;
}

const char* sobol_study = R"json({
  "study": "sens_slope", "title": "Slope", "kind": "sensitivity",
  "setup": { "runs": 1607, "failed runs": 2 },
  "tables": [
    { "title": "Morris elementary effects (unit coordinates)", "columns": ["output", "parameter", "μ*", "μ", "σ", "effects", "exact μ*"],
      "rows": [["x_0.2", "K_n", "9", "1", "1", "10", ""], ["x_0.2", "h_n", "0.5", "1", "1", "10", ""]] },
    { "title": "Sobol' indices (Saltelli sampling, N = 256, 1536 runs; 95 % bootstrap intervals)",
      "columns": ["output", "parameter", "S", "interval", "S_T", "interval", "exact S", "exact S_T", "S (Janon)", "interval"],
      "rows": [["x_0.2", "K_n", "0.21", "[-5.5, 2.2]", "0.98", "[0.12, 3.4]", "", "", "0.1", "[0, 1]"],
               ["x_0.2", "h_n", "0.28", "[-5.3, 2.8]", "1.16", "[0.37, 4]", "", "", "0.1", "[0, 1]"],
               ["x_0.2", "Δt", "-0.013", "[-0.089, 0.008]", "0.0001", "[4.6e-06, 0.00061]", "", "", "0.1", "[0, 1]"],
               ["x_0.2", "dummy (inert: noise floor)", "0", "[0, 0]", "0", "[0, 0]", "", "", "0.02", "[-0.03, 0.05]"],
               ["x_0.1", "K_n", "—", "[—, —]", "—", "[—, —]", "", "", "—", "[—, —]"]] },
    { "title": "Sobol' indices (Saltelli sampling, N = 256, 1536 runs; 95 % bootstrap intervals): indices of the TRANSFORMED output rank(y)",
      "columns": ["output", "parameter", "S", "interval", "S_T", "interval"],
      "rows": [["rank(x_0.2)", "K_n", "0.05", "[0, 0.1]", "0.09", "[0.05, 0.14]"], ["rank(x_0.2)", "h_n", "0.7", "[0.5, 0.8]", "0.97", "[0.67, 1.3]"]] }
  ] })json";

const char* morris_study = R"json({
  "study": "sens_beam", "title": "Beam", "kind": "sensitivity",
  "setup": { "runs": 71, "failed runs": 0 },
  "tables": [
    { "title": "One-at-a-time sweeps: the output at both ends of each range", "columns": ["output", "parameter", "range", "at low", "at high", "max − min", "(max − min) / |base|"],
      "rows": [["peak", "c", "0 … 1", "1", "2", "5", "0.1"]] },
    { "title": "Morris elementary effects (unit coordinates)", "columns": ["output", "parameter", "μ*", "95 % bootstrap interval", "μ*_conf (SALib)", "μ", "σ", "effects", "exact μ*"],
      "rows": [["peak", "c", "0.02", "[0.01, 0.03]", "0.01", "0", "0", "10", ""], ["peak", "k_n", "300", "[250, 350]", "50", "1", "1", "10", ""],
               ["peak", "φ", "1.5", "[1, 2]", "0.5", "1", "1", "10", ""]] }
  ] })json";

}  // namespace

TEST_CASE("sensitivity overview: the strongest measure per output, most and least influential with their intervals", "[report]") {
  report::ReportContent content;
  content.studies.push_back(study("a_convergence", R"({"study": "conv", "kind": "refinement", "tables": []})"));
  content.studies.push_back(study("sensitivity_slope", sobol_study));
  content.studies.push_back(study("sensitivity_beam", morris_study));
  const auto rows = report::sensitivity_overview_rows(content);
  REQUIRE(rows.size() == 4);  // x_0.2, x_0.1, rank(x_0.2) of the slope; peak of the beam; no row for the convergence study
  CHECK(rows[0].output == "x_0.2");
  CHECK(rows[0].measure == "S_T (Jansen)");  // Sobol' outranks Morris, whatever the table order
  CHECK(rows[0].most == "h_n (intervals overlap: K_n)");  // K_n's [0.12, 3.4] reaches into h_n's [0.37, 4]
  CHECK(rows[0].most_value == "1.16");
  CHECK(rows[0].most_interval == "[0.37, 4]");
  CHECK(rows[0].least == "Δt");
  CHECK(rows[0].least_interval == "[4.6e-06, 0.00061]");
  CHECK(rows[0].runs == "1607");
  CHECK(rows[0].failed == "2");
  CHECK(rows[0].anchor == "study-sensitivity_slope");
  CHECK(rows[1].output == "x_0.1");
  CHECK(rows[1].most == "—");  // no finite index: nothing ranked
  CHECK(rows[2].output == "rank(x_0.2)");
  CHECK(rows[2].most == "h_n");           // [0.67, 1.3] clear of K_n's [0.05, 0.14]
  CHECK(rows[2].least == "K_n");
  CHECK(rows[3].study == "sens_beam");
  CHECK(rows[3].measure == "μ* (Morris)");
  CHECK(rows[3].most == "k_n");
  CHECK(rows[3].most_value == "300");
  CHECK(rows[3].least == "c");
  CHECK(rows[3].most_interval == "[250, 350]");  // μ*'s bootstrap interval
  CHECK(rows[0].noise == "—");  // no replicates
  CHECK(rows[3].runs == "71");
}

TEST_CASE("sensitivity overview: a section in both pages linking each study, none without sensitivity studies", "[report]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dem2d_report_test_sens_" + std::to_string(std::random_device{}()));
  for (const auto& [folder, json] : {std::pair{"sensitivity_slope", sobol_study}, std::pair{"sensitivity_beam", morris_study}}) {
    fs::create_directories(dir / "studies" / folder);
    std::ofstream(dir / "studies" / folder / "result.json") << json;
  }
  report::Options options;
  options.studies_dir = dir / "studies";
  options.out_dir = dir / "report";
  const auto written = report::write_report(options);
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  const std::string html = slurp(written.html), md = slurp(written.markdown);
  CHECK(html.find("id=\"sensitivity-overview\"") != std::string::npos);
  CHECK(html.find("href=\"#sensitivity-overview\"") != std::string::npos);  // in the contents
  CHECK(html.find("<td><a href=\"#study-sensitivity_slope\">sens_slope</a></td>") != std::string::npos);
  CHECK(html.find("[0.37, 4]") != std::string::npos);
  CHECK(md.find("## Sensitivity studies: overview") != std::string::npos);
  CHECK(md.find("[sens\\_beam](#study-sensitivity_beam)") != std::string::npos);  // markdown escapes _
  // Without sensitivity studies: no section, no contents entry.
  fs::remove_all(dir / "studies" / "sensitivity_slope");
  fs::remove_all(dir / "studies" / "sensitivity_beam");
  fs::create_directories(dir / "studies" / "conv");
  std::ofstream(dir / "studies" / "conv" / "result.json") << R"({"study": "conv", "kind": "refinement", "checks": []})";
  const auto again = report::write_report(options);
  CHECK(slurp(again.html).find("sensitivity-overview") == std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("sensitivity overview: the noise fraction of a study with replicates", "[report]") {
  report::ReportContent content;
  content.studies.push_back(study("sensitivity_noisy", R"json({
  "study": "noisy", "title": "Noisy", "kind": "sensitivity", "setup": { "runs": 20, "failed runs": 0 },
  "tables": [
    { "title": "Morris elementary effects (unit coordinates)", "columns": ["output", "parameter", "μ*", "95 % bootstrap interval", "μ*_conf (SALib)", "μ", "σ", "effects", "exact μ*"],
      "rows": [["rate", "φ", "30", "[18, 50]", "5", "-30", "24", "6", ""]] },
    { "title": "Run-to-run noise against parameter effect (3 replicates per sample)",
      "columns": ["output", "samples", "n", "R", "σ_noise", "interval", "√V_effect", "noise fraction", "interval", "exact", "noise μ* (Morris)"],
      "rows": [["rate", "Morris points", "30", "3", "12", "[10, 14]", "20", "0.26", "[0.2, 0.33]", "—", "9"]] }
  ] })json"));
  const auto rows = report::sensitivity_overview_rows(content);
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].noise == "0.26 [0.2, 0.33]");
}
