// Sample and analyse apart: `dem2d sweep --design-only` writes the design (design.csv) and `dem2d
// analyse` reads the outputs of its runs computed anywhere (another code, a cluster). The design is
// the study file's own (plan_runs: deterministic for the file), so analyse rebuilds it and matches
// the outputs by run number.
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/run/output_files.hpp"
#include "engine/sensitivity_study.hpp"

namespace fs = std::filesystem;

namespace ver::sens {

namespace {

/// The fields of one CSV line ("..." may hold commas; "" inside quotes is a quote).
std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted && c == '"' && k + 1 < line.size() && line[k + 1] == '"') out.back() += '"', ++k;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else if (c != '\r') out.back() += c;
  }
  return out;
}

}  // namespace

void write_design_csv(const Sens& s, const std::vector<Run>& runs, const fs::path& file) {
  std::ostringstream csv;
  csv << "run,method";
  for (const auto& p : s.params) csv << "," << p.name << " [" << p.unit << "]";
  csv << "\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    csv << k << "," << runs[k].method;
    for (std::size_t i = 0; i < s.params.size(); ++i)
      csv << "," << (std::isfinite(runs[k].u[i]) ? fmt::format("{:.17g}", value_at(s.params[i], runs[k].u[i])) : std::string());
    csv << "\n";
  }
  dem::write_file_atomic(file, csv.str(), false);
}

void read_outputs_csv(const Sens& s, const fs::path& file, std::vector<Run>& runs) {
  std::ifstream in(file);
  if (!in) throw dem::CaseError(fmt::format("file not found: {}", file.string()));
  auto fail = [&](std::size_t line, const std::string& what) -> void {
    throw dem::CaseError(fmt::format("{}:{}: {}", file.string(), line, what));
  };
  std::string line;
  if (!std::getline(in, line)) fail(1, "empty: expected a header with run and the outputs");
  const std::vector<std::string> header = fields_of(line);
  auto column = [&](const std::string& name) -> std::size_t {
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) return c;
    fail(1, fmt::format("no column \"{}\" (expected run and the study's outputs: {})", name, fmt::join(s.outputs, ", ")));
    return 0;
  };
  const std::size_t run_col = column("run");
  std::vector<std::size_t> out_col;
  for (const std::string& o : s.outputs) out_col.push_back(column(o));
  for (Run& r : runs) {
    r.outputs.assign(s.outputs.size(), std::nan(""));
    r.status = "missing";
    r.message = "no row in " + file.filename().string();
  }
  std::vector<bool> seen(runs.size(), false);
  for (std::size_t n = 2; std::getline(in, line); ++n) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> f = fields_of(line);
    if (f.size() < header.size()) fail(n, fmt::format("{} fields, the header has {}", f.size(), header.size()));
    std::size_t k = 0;
    try {
      std::size_t used = 0;
      const long long v = std::stoll(f[run_col], &used);
      if (used != f[run_col].size() || v < 0 || static_cast<std::size_t>(v) >= runs.size()) throw std::out_of_range("run");
      k = static_cast<std::size_t>(v);
    } catch (const std::exception&) {
      fail(n, fmt::format("run: expected a run number 0 … {}, got \"{}\"", runs.size() - 1, f[run_col]));
    }
    if (seen[k]) fail(n, fmt::format("run {} given twice", k));
    seen[k] = true;
    runs[k].status = "completed";
    runs[k].message.clear();
    for (std::size_t o = 0; o < out_col.size(); ++o) {
      const std::string& x = f[out_col[o]];
      if (x.empty() || x == "nan" || x == "NaN") {
        runs[k].status = "failed";
        continue;
      }
      try {
        std::size_t used = 0;
        runs[k].outputs[o] = std::stod(x, &used);
        if (used != x.size()) throw std::invalid_argument(x);
      } catch (const std::exception&) {
        fail(n, fmt::format("{}: expected a number, got \"{}\"", s.outputs[o], x));
      }
    }
  }
}

}  // namespace ver::sens
