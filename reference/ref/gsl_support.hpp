#pragma once
// GSL glue shared by the reference solvers: GSL's abort-on-error handler switched off (every status
// is checked instead), RAII for the integration workspace, and C++ callables behind GSL's C
// callbacks. An exception thrown by a callable must not unwind through GSL's C frames: it is caught
// in the callback, the callback returns NaN, and the exception is rethrown once GSL returns.

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>

#include <cstddef>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace ref::detail {

inline void gsl_handler_off() {
  static std::once_flag once;
  std::call_once(once, [] { gsl_set_error_handler_off(); });
}

[[noreturn]] inline void gsl_failure(const std::string& where, int status) {
  throw std::runtime_error(where + ": GSL failed: " + gsl_strerror(status));
}

struct WorkspaceDeleter {
  void operator()(gsl_integration_workspace* w) const { gsl_integration_workspace_free(w); }
};
using Workspace = std::unique_ptr<gsl_integration_workspace, WorkspaceDeleter>;

inline Workspace make_workspace(std::size_t limit) {
  Workspace w(gsl_integration_workspace_alloc(limit));
  if (!w) throw std::runtime_error("ref: GSL workspace allocation failed");
  return w;
}

// A C++ callable seen by GSL as a gsl_function.
class GuardedFunction {
 public:
  explicit GuardedFunction(std::function<double(double)> f) : f_(std::move(f)) {}
  GuardedFunction(const GuardedFunction&) = delete;  // function_ points at this object
  GuardedFunction& operator=(const GuardedFunction&) = delete;
  gsl_function* gsl() { return &function_; }
  // Rethrows a captured exception, else turns a GSL status into std::runtime_error.
  void check(const std::string& where, int status) const {
    if (failure_) std::rethrow_exception(failure_);
    if (status != GSL_SUCCESS) gsl_failure(where, status);
  }

 private:
  static double call(double x, void* self) {
    auto* me = static_cast<GuardedFunction*>(self);
    try {
      return me->f_(x);
    } catch (...) {
      if (!me->failure_) me->failure_ = std::current_exception();
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
  std::function<double(double)> f_;
  std::exception_ptr failure_;
  gsl_function function_{&GuardedFunction::call, this};
};

// The root of f in [lo, hi] (f(lo), f(hi) of opposite signs) by gsl_root_fsolver_brent, to
// |upper - lower| < absolute_tolerance + relative_tolerance · min(|lower|, |upper|)
// (gsl_root_test_interval; min is 0 while the bracket contains 0).
inline double brent_root(const std::string& where, std::function<double(double)> f, double lo,
                         double hi, double relative_tolerance, double absolute_tolerance) {
  gsl_handler_off();
  GuardedFunction function(std::move(f));
  std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), &gsl_root_fsolver_free);
  if (!solver) throw std::runtime_error(where + ": GSL solver allocation failed");
  function.check(where, gsl_root_fsolver_set(solver.get(), function.gsl(), lo, hi));
  for (int iteration = 0; iteration < 500; ++iteration) {
    function.check(where, gsl_root_fsolver_iterate(solver.get()));
    const double a = gsl_root_fsolver_x_lower(solver.get());
    const double b = gsl_root_fsolver_x_upper(solver.get());
    if (gsl_root_test_interval(a, b, absolute_tolerance, relative_tolerance) == GSL_SUCCESS)
      return gsl_root_fsolver_root(solver.get());
  }
  throw std::runtime_error(where + ": Brent did not converge");
}

// ∫_a^b f by gsl_integration_qag with the given Gauss-Kronrod key.
inline double integrate_qag(const std::string& where, std::function<double(double)> f, double a,
                            double b, double epsabs, double epsrel, int key,
                            std::size_t limit = 1000) {
  gsl_handler_off();
  GuardedFunction function(std::move(f));
  Workspace workspace = make_workspace(limit);
  double result = 0.0, error = 0.0;
  const int status = gsl_integration_qag(function.gsl(), a, b, epsabs, epsrel, limit, key,
                                         workspace.get(), &result, &error);
  function.check(where, status);
  return result;
}

}  // namespace ref::detail
