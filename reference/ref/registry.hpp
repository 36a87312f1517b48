#pragma once
// Name-based entry point to the reference solvers, for study files. All arguments and results in
// SI (angles in rad). In 2D, "per unit thickness" quantities keep the same names (refs
// conventions).

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace ref {

struct SolverArgument {
  std::string name;
  std::string unit;
  std::string meaning;
};

struct SolverInfo {
  std::string name;
  std::string description;  // what is returned, with its source section
  std::vector<SolverArgument> arguments;
  std::string result_unit;
};

// Evaluates the named solver. `args` must hold exactly the solver's arguments. Throws
// std::invalid_argument naming the solver for an unknown solver name, a missing or unknown
// argument, or an argument the solver rejects (e.g. a negative mass).
double evaluate(std::string_view name, const std::map<std::string, double>& args);

// Every solver evaluate() knows, in a fixed order.
std::vector<SolverInfo> solvers();

}  // namespace ref
