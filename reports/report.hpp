// Report generator: reads every <studies_dir>/*/result.json (format: verification/RESULT_FORMAT.md)
// and writes one self-contained HTML page (<out_dir>/index.html, figures inlined as SVG) and its
// Markdown twin (<out_dir>/index.md, linking <out_dir>/figures/*.svg). Plots are made by gnuplot.
// The report never reruns a study; it is generated, never hand-edited.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace report {

struct Options {
  std::filesystem::path studies_dir;  // holds one folder per study, each with a result.json
  std::filesystem::path out_dir;      // created if missing; figures/ inside is regenerated
  std::string title;                  // page title ("" -> "DEM verification report")
  nlohmann::json provenance;          // optional: code_version, build_type, machine, date, ...
  std::filesystem::path docs_dir;     // the repository's docs/: rendered into the page, citations linked
                                      // to it (cited_docs.hpp); empty or missing: citations stay text
  std::filesystem::path bench_dir;    // the speed benchmark's table and plot (speed_table.hpp: a bench/suite.py
                                      // output folder, or bench/results); empty or holding none: no section
  std::filesystem::path claims_file;  // the papers' items (verification/paper_claims.toml, paper_claims_file.hpp),
                                      // read before anything is written; empty: no section
};

struct Written {
  std::filesystem::path html, markdown;
  int studies;  // result.json files found (readable or not)
  int figures;  // SVG figures written
  std::vector<std::string> claim_errors;  // claims whose selector or figure matches nothing in a present result
};

// Throws std::runtime_error if studies_dir is not a directory, dem::OutputError (exit status 4) if the outputs
// cannot be written (each file goes through a temporary name: the previous one stays whole), and
// dem::CaseError for a claims file that does not read (nothing is written then). A claim that does not
// match a present result is shown in its row and listed in Written::claim_errors, not thrown.
// Malformed result files and failed gnuplot calls are reported in the page (and on stderr), not
// thrown.
Written write_report(const Options& options);

// The same with another gnuplot executable than the one found by CMake (a bare name is looked up
// on PATH).
Written write_report(const Options& options, const std::filesystem::path& gnuplot);

}  // namespace report
