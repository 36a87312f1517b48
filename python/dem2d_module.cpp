// dem2d._core: the C++ side of the Python module (python/README.md). Thin: every call is a library function
// the command line (app/main.cpp) calls too — read_case, check_case, run_case, run_study, run_sensitivity —
// so the module reads, checks and runs a case exactly as `dem2d` does. JSON crosses as text (the Python
// side, dem2d/__init__.py, turns it into dicts and DataFrames and the errors into dem2d.CaseError).
#include <csignal>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "dem/cases/case_file.hpp"
#include "dem/cases/case_schema.hpp"
#include "dem/run/case_in_words.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/resolved_case.hpp"
#include "dem/run/run.hpp"
#include "dem/run/run_threads.hpp"
#include "engine/sensitivity.hpp"
#include "engine/study.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace {

/// `dem2d check`'s content as JSON text: the resolved case (SI), the stability limit and what sets it.
std::string check_json(const dem::Case& c) {
  dem::StabilityBound b;
  const double limit = dem::check_case(c, &b);
  dem::check_outputs(c);
  nlohmann::json j = dem::resolved_case_si(c);
  nlohmann::json s = {{"limit", limit},
                      {"dt", c.model.numerics.dt},
                      {"dt_over_limit", c.model.numerics.dt / limit},
                      {"limit_sticking", b.limit_sticking},
                      {"limit_gershgorin", b.limit_gershgorin},
                      {"eigen", b.eigen},
                      {"assumptions", b.assumptions},
                      {"units", {{"limit", "s"}, {"dt", "s"}, {"limit_sticking", "s"}, {"limit_gershgorin", "s"}}}};
  if (b.element >= 0) s["what_limits_it"] = dem::limit_in_words(c.model, b, limit);
  j["stability"] = s;
  j["title"] = c.title;
  j["source"] = c.source;
  j["path"] = c.path.string();
  j["overrides"] = c.overrides;
  return j.dump();
}

/// SIGINT during a run: recorded for the run's loop, which stops at the next step with status
/// "interrupted" and writes everything (as `dem2d run` does). Python's own handler is put back after the run.
extern "C" void on_sigint(int sig) { dem::set_interrupt_signal(sig); }

struct SigintDuringRun {
  bool active;
  struct sigaction before {};
  explicit SigintDuringRun(bool install) : active(install) {
    dem::set_interrupt_signal(0);
    if (!active) return;
    struct sigaction sa {};
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &before);
  }
  ~SigintDuringRun() {
    if (active) sigaction(SIGINT, &before, nullptr);
    dem::set_interrupt_signal(0);
  }
};

py::dict run(const dem::Case& c, const fs::path& out, long long threads, bool handle_sigint) {
  // As `dem2d run --threads`: 1 to 1024, and never more than this process may use (the number asked is
  // recorded in summary.json's "threads" beside the number used).
  if (threads < 1 || threads > 1024)
    throw py::value_error("threads=" + std::to_string(threads) + ": expected a whole number from 1 to 1024 (as dem2d run --threads)");
  dem::RunOptions opt;
  opt.out_dir = out;
  opt.threads = static_cast<int>(threads);
  if (const int usable = dem::threads_for_run(opt.threads); usable < opt.threads) {
    opt.threads_asked = opt.threads;
    opt.threads = usable;
  }
  dem::RunResult r;
  {
    SigintDuringRun guard(handle_sigint);
    py::gil_scoped_release nogil;  // other Python threads run meanwhile
    r = dem::run_case(c, opt);     // a copy of the case: the Python Case stays usable
  }
  py::dict probes;
  for (const auto& [k, v] : r.probes) probes[py::str(k)] = v ? py::object(py::float_(*v)) : py::object(py::none());
  py::dict d;
  d["status"] = r.status, d["message"] = r.message, d["steps"] = r.steps, d["time"] = r.time;
  d["wall_seconds"] = r.wall_seconds, d["stability_limit"] = r.stability_limit;
  d["probes"] = probes, d["summary"] = r.summary.dump();
  return d;
}

/// A study or sensitivity study (result.json as JSON text, passed), as `dem2d study|sweep` runs it.
py::tuple study(const fs::path& file, const fs::path& out, int jobs, bool fresh, bool sweep, bool handle_sigint) {
  ver::StudyOptions so;
  so.out_dir = out;
  so.jobs = jobs;
  so.use_cache = !fresh;
  so.print = false;
  ver::StudyResult r;
  {
    SigintDuringRun guard(handle_sigint);
    py::gil_scoped_release nogil;
    r = sweep ? ver::run_sensitivity(file, so) : ver::run_study(file, so);
  }
  return py::make_tuple(r.passed, r.json.dump());
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "dem2d's C++ core (use the package dem2d, not this module)";
  auto case_error = py::register_exception<dem::CaseError>(m, "CaseError", PyExc_ValueError);
  py::register_exception<dem::OutputError>(m, "OutputError", PyExc_OSError);
  py::register_exception<ver::StudyInterrupted>(m, "StudyInterrupted", PyExc_KeyboardInterrupt);
  (void)case_error;
  py::class_<dem::Case>(m, "Case")
      .def_property_readonly("path", [](const dem::Case& c) { return c.path.string(); })
      .def_property_readonly("title", [](const dem::Case& c) { return c.title; })
      .def_property_readonly("source", [](const dem::Case& c) { return c.source; })
      .def_property_readonly("overrides", [](const dem::Case& c) { return c.overrides; })
      .def_property_readonly("series_names", [](const dem::Case& c) { return c.output.series; })
      .def_property_readonly("dt", [](const dem::Case& c) { return c.model.numerics.dt; })
      .def_property_readonly("duration", [](const dem::Case& c) { return c.model.numerics.duration; })
      .def_property_readonly("elements", [](const dem::Case& c) { return c.model.elements.size(); })
      .def_property_readonly("as_read", [](const dem::Case& c) { return c.resolved.dump(); });
  m.def("read_case", &dem::read_case, py::arg("path"), py::arg("overrides"));
  m.def("check", &check_json, py::arg("case"));
  m.def("run", &run, py::arg("case"), py::arg("out"), py::arg("threads"), py::arg("handle_sigint"));
  m.def("study", &study, py::arg("file"), py::arg("out"), py::arg("jobs"), py::arg("fresh"), py::arg("sweep"),
        py::arg("handle_sigint"));
  m.def("version", [] { return dem::provenance().dump(); });
  m.def("schema", [] { return dem::case_schema().dump(2); });  // the text `dem2d schema` prints (without its newline)
}
