#pragma once
// The levels of a refinement study (verification/README.md, "The study file"), coarse → fine.
//
// Two ways to declare them in study.toml:
//   [refinement] parameter = "numerics.dt", values = [...] (or base, ratio, levels), h = "value" | "inverse":
//       one --set path takes one value per level; h = the value (Δt) or 1/value (N).
//   [refinement] label = "r [m]" and [[level]] tables, each with its own length h (or count n: h = 1/n),
//       several overrides `set = [...]` and its own reference arguments `args = {...}`: a level that is a
//       whole model (e.g. an n × 3n block of PREs: radius, mass, origin, columns, rows).
// Either way every level ends up as overrides + h, and the study engine analyses the probe values over
// h with convergence.hpp (observed orders, Richardson, GCI) exactly alike.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <optional>

#include <toml++/toml.h>

#include "engine/convergence.hpp"

namespace ver {

struct RefinementLevel {
  std::string label;               // "" in the values form
  double value = 0.0;              // the declared number: h, n or the parameter's value
  double h = 0.0;                  // the length the analysis uses: value, or 1/value (inverse)
  std::vector<std::string> set;    // overrides of this level (values form: "parameter=value")
  std::map<std::string, double> args;  // reference arguments of this level (over the variant's)
};

struct Refinement {
  std::string parameter;           // the --set path (values form); "" with [[level]] tables
  std::string label;               // the h axis, e.g. "dt [s]"
  bool inverse = false;            // h = 1/value
  bool declared_levels = false;    // true: [[level]] tables
  std::vector<RefinementLevel> levels;  // coarse → fine, h strictly decreasing ([[level]] form)
};

/// Reads [refinement] (and [[level]]) of a study file for kind = "refinement". Throws
/// std::runtime_error "file:line: key: what was expected" for malformed input.
Refinement read_refinement(const toml::table& root, const std::string& file);

/// The convergence series of one probe over the levels (value k of level k; a level without a value
/// is left out, and so is its label). `labels` receives the labels of the levels used.
Series analyse_levels(const Refinement& refinement, const std::vector<std::optional<double>>& values,
                      const ConvergenceOptions& options, const std::string& name,
                      std::vector<std::string>* labels = nullptr);

/// Throws "file:line: level: [[level]] tables need kind = \"refinement\"" if the file has [[level]]
/// tables (used for the other kinds).
void refuse_levels(const toml::table& root, const std::string& file);

}  // namespace ver
