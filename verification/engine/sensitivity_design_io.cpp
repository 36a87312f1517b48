// Sample and analyse apart: `dem2d sweep --design-only` writes the design (design.csv) and `dem2d
// analyse` reads the outputs of its runs computed anywhere (another code, a cluster). The design is
// the study file's own (plan_runs: deterministic for the file), so analyse rebuilds it and matches
// the outputs by run number.
#include <cctype>
#include <cmath>
#include <cstdlib>
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
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 byte-order mark (spreadsheets write one)
  const std::vector<std::string> header = fields_of(line);
  for (std::size_t c = 0; c < header.size(); ++c)
    for (std::size_t e = c + 1; e < header.size(); ++e)
      if (header[c] == header[e])
        fail(1, fmt::format("{}: the header names this column twice (columns {} and {})", header[c], c + 1, e + 1));
  auto column = [&](const std::string& name) -> std::size_t {
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) return c;
    std::string near;  // "overlap [m]" for "overlap": the column is there, with something after its name
    for (const std::string& h : header)
      if (h.size() > name.size() && h.rfind(name, 0) == 0 && (h[name.size()] == ' ' || h[name.size()] == '['))
        near = fmt::format(": column \"{}\" is there, name it exactly \"{}\" (no unit)", h, name);
    fail(1, fmt::format("{}: no such column (expected run and the study's outputs: {}){}", name, fmt::join(s.outputs, ", "), near));
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
    // Exactly the header's fields: more would be a decimal comma or a stray separator, read as other columns.
    if (f.size() != header.size()) fail(n, fmt::format("{} fields, the header has {}", f.size(), header.size()));
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
      // One rule for a value that is not a finite number (empty, nan, NaN, inf, Infinity, nan(…), 1e400, which
      // overflows): the run failed, and it is counted as failed (max_failed_runs), with the value in its message.
      const std::string& x = f[out_col[o]];
      double y = std::nan("");
      bool number = !x.empty() && !std::isspace(static_cast<unsigned char>(x.front()));
      if (number) {
        char* end = nullptr;
        y = std::strtod(x.c_str(), &end);  // an overflow gives ±HUGE_VAL (not finite: a failed run), an underflow its value
        number = end == x.c_str() + x.size();
      }
      if (!number && !x.empty()) fail(n, fmt::format("{}: expected a number, got \"{}\"", s.outputs[o], x));
      if (!std::isfinite(y)) {
        runs[k].status = "failed";
        runs[k].message += fmt::format("{}{}: not a finite number (\"{}\")", runs[k].message.empty() ? "" : "; ", s.outputs[o], x);
        continue;
      }
      runs[k].outputs[o] = y;
    }
  }
}

}  // namespace ver::sens
