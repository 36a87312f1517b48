#pragma once
// The versions of the numerical libraries the reference solvers are built with (report provenance).
#include <string>

namespace ref {

/// "GSL 2.7.1, Boost 1.74, Eigen 3.4.0".
std::string library_versions();

}  // namespace ref
