// dem2d — the command line of the 2D DEM verification testbed.
//   dem2d run CASE [--set key=value]... [--out DIR] [--checkpoint-every N] [--checkpoint-at-end]
//             [--restart CHECKPOINT | --start-from CHECKPOINT]
//                                                        run a case, write series.csv, summary.json, vtk/
//   dem2d check CASE [--set key=value]...                check a case and print what it resolves to
//   dem2d study STUDY [--out DIR] [--jobs N] [--fresh] [-v]   run one verification study (verification/*/study.toml)
//   dem2d sweep STUDY [--out DIR] [--jobs N] [--fresh] [-v]   run one sensitivity study (verification/sensitivity_*/sensitivity.toml)
//   dem2d sweep STUDY --design-only [--out DIR]          write its design (design.csv), run nothing
//   dem2d analyse STUDY --outputs FILE [--out DIR]       analyse outputs of that design computed anywhere
//   dem2d report [--studies DIR] [--out DIR] [--claims FILE]   write the verification report from study results
//   dem2d schema                                         print the JSON Schema of the case format
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <thread>
#include <utility>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dem/cases/case_file.hpp"
#include "dem/cases/case_reader.hpp"
#include "dem/cases/case_schema.hpp"
#include "dem/run/interrupt.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/resolved_case.hpp"
#include "dem/run/case_in_words.hpp"
#include "dem/run/run_threads.hpp"
#include "dem/core/usable_cores.hpp"
#include "dem/run/run.hpp"
#include "dem/run/run_threads.hpp"
#include "dem/core/usable_cores.hpp"
#include "dem/core/simulation.hpp"
#include "engine/sensitivity.hpp"
#include "engine/study.hpp"
#include "ref/library_versions.hpp"
#ifdef DEM2D_MPI
#include "engine/mpi/mpi_runs.hpp"
#endif
#include "report.hpp"
#include "study_summary.hpp"

namespace fs = std::filesystem;

#ifndef DEM2D_SOURCE_DIR
#define DEM2D_SOURCE_DIR "."
#endif

namespace {

constexpr const char* kExitCodes =
    "Exit status: 0 done (study, sweep: every check passed); 1 a study or sweep ran and a check failed; "
    "2 a mistake in the command line or an input file (case, study, sensitivity file, checkpoint), named with "
    "file:line: key; 3 a run blew up or its time-step guard, evaluated again (numerics.guard_reach), refused Δt (the message "
    "names the step and the bound); 4 an output could not be written "
    "(full disk, unwritable folder); 128 + the signal when stopped by SIGINT (130) or SIGTERM (143), everything "
    "finished written.";

int cmd_check(const fs::path& file, const std::vector<std::string>& sets) {
  const dem::Case c = dem::read_case(file, sets);
  dem::StabilityBound b;
  const double limit = dem::check_case(c, &b);
  dem::check_outputs(c);
  const dem::Model& m = c.model;
  const nlohmann::json rc = dem::resolved_case_si(c);
  fmt::print("{}: OK — {}\n", file.string(), c.title);
  if (!c.source.empty()) fmt::print("  source: {}\n", c.source);
  fmt::print("  {} elements ({} disks, {} PREs{}), {} walls, {} materials, {} contact laws\n", m.elements.size(),
             rc["elements"]["disks"].get<std::size_t>(), rc["elements"]["pres"].get<std::size_t>(),
             rc["elements"].contains("polygons") ? fmt::format(", {} polygons", rc["elements"]["polygons"].get<std::size_t>()) : "",
             m.walls.size(), m.materials.size(), m.laws.size());
  fmt::print("  total mass {:.6g} kg (thickness {:.6g} m), gravity ({:.6g}, {:.6g}) m/s^2\n", dem::total_mass(m), m.thickness,
             m.gravity.x, m.gravity.y);
  fmt::print("  integrator {} ({}), velocity start {} ({}), dt = {:.6g} s, duration = {:.6g} s ({} steps)\n",
             rc["numerics"]["integrator"].get<std::string>(),
             m.numerics.integrator == dem::Integrator::k18 ? "du = v dt, K18" : "du = (du_prev + v dt)/2, K19",
             rc["numerics"]["velocity_start"].get<std::string>(),
             m.numerics.velocity_start == dem::VelocityStart::plain ? "v_-1 = v(0)" : "v_-1 = v(0) - a(0) dt/2",
             m.numerics.dt, m.numerics.duration, rc["numerics"]["steps"].get<std::int64_t>());
  fmt::print("  neighbour skin {:.6g} m, blow-up: max step {:.3g} of a radius\n", rc["numerics"]["skin"].get<double>(),
             m.numerics.max_step_fraction);
  for (const auto& l : rc["contacts"]) fmt::print("  contact {}\n", dem::law_in_words(l));
  for (const auto& p : rc["probes"])
    fmt::print("  probe {}: {} [{}]\n", p["name"].get<std::string>(), p["kind"].get<std::string>(), p["unit"].get<std::string>());
  fmt::print("  stability limit: {:.6g} s (dt is {:.3g} of it), over every contact the case can form\n", limit,
             m.numerics.dt / limit);
  if (b.element >= 0) fmt::print("    what limits it: {}\n", dem::limit_in_words(m, b, limit));
  if (b.limit_sticking < limit)
    fmt::print("    with every Coulomb shear spring sticking: {:.6g} s (dt is {:.3g} of it; a shear mode above it is "
               "bounded by sliding, |f_s| = mu f_n)\n", b.limit_sticking, m.numerics.dt / b.limit_sticking);
  if (b.eigen)
    fmt::print("    bonded structure: eigenvalue bound {:.6g} s (lambda_max = {:.6g} 1/s^2, c_max = {:.6g} 1/s at the start); "
               "Gershgorin (row-sum) bound {:.6g} s, {:.3g} x smaller\n",
               b.limit, b.lambda_max, b.c_max, b.limit_gershgorin, b.limit / b.limit_gershgorin);
  if (b.eigen && b.limit_block > 0.0)
    fmt::print("    block bound (G5: the bonded block and each unbonded element apart): {:.6g} s\n", b.limit_block);
  if (b.eigen)
    fmt::print("    the start network alone (without the contacts the unbonded elements can still form): {:.6g} s\n",
               b.limit_start);
  else
    fmt::print("    Gershgorin (row-sum) bound {:.6g} s (no bonded structure: no eigenvalue bound)\n", b.limit_gershgorin);
  fmt::print("    assumed: {}\n", b.assumptions);
  return 0;
}

/// The exit status of a command stopped by SIGINT / SIGTERM: 128 + the signal, as a shell reports it.
int interrupted_exit() { return 128 + (dem::interrupt_signal() ? dem::interrupt_signal() : SIGTERM); }

int cmd_run(const fs::path& file, const std::vector<std::string>& sets, fs::path out, bool quiet, dem::RunOptions opt) {
  dem::Case c = dem::read_case(file, sets);
  if (out.empty()) out = fs::path("runs") / file.stem();
  opt.out_dir = out;
  opt.progress = !quiet;
  std::map<std::string, std::string> units;  // each probe's SI unit, printed with its value
  for (const auto& p : c.probes) units[p.name] = dem::probe_unit(p);
  const dem::RunResult r = dem::run_case(std::move(c), opt);  // the model's elements once, in the run
  if (!quiet) {
    fmt::print("{}: {} after {} steps (t = {:.6g} s) in {:.3g} s, {:.3g} element-steps/s\n", file.string(), r.status,
               r.steps, r.time, r.wall_seconds, r.element_steps_per_second);
    for (const auto& [k, v] : r.probes) {
      const std::string unit = units.count(k) && units[k] != "1" ? " " + units[k] : "";
      fmt::print("  {} = {}\n", k, v ? fmt::format("{:.10g}{}", *v, unit) : std::string("(not available)"));
    }
    fmt::print("  written to {}\n", out.string());
  }
  if (r.status == "blow-up" || r.status == "refused") {  // refused: the guard's re-check (docs/model.md G7)
    fmt::print(stderr, "error: {}: {}\n", file.string(), r.message);
    return 3;
  }
  if (r.status == "interrupted") {
    fmt::print(stderr, "interrupted: {}: {}; everything is written, checkpoint {}\n", file.string(), r.message,
               (out / "checkpoint.bin").string());
    return interrupted_exit();
  }
  return 0;
}

/// Every option of every subcommand, as the command line gives it.
struct Cli {
  std::string case_file, study_file;
  std::vector<std::string> sets;
  std::string out_dir;
  bool quiet = false;
  dem::RunOptions run_opt;
  std::string restart, start_from;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  bool fresh = false;
  bool verbose = false;  // study, sweep: a line per finished run
  bool design_only = false;  // sweep: write design.csv only
  std::string outputs_file;  // analyse: the outputs of the design's runs
  std::string studies_dir = "build/studies", report_dir = "build/report";
  std::string docs_dir, bench_dir, claims_file;
  CLI::App *run = nullptr, *check = nullptr, *study = nullptr, *sweep = nullptr, *analyse = nullptr, *report = nullptr,
           *schema = nullptr;
};

void add_run(CLI::App& app, Cli& o) {
  auto* run = o.run = app.add_subcommand("run", "Run a case: writes series.csv, summary.json and vtk/ snapshots");
  run->add_option("case", o.case_file, "Case file (TOML)")->required()->check(CLI::ExistingFile);
  run->add_option("--set", o.sets, "Override a case value: key=value, e.g. numerics.dt=1e-6 or \"contact.0.kn=12 kN/mm\"");
  run->add_option("--out", o.out_dir, "Output folder (default runs/<case name>)");
  run->add_flag("-q,--quiet", o.quiet, "No progress or summary on the terminal");
  // Default 1: every study already runs its runs side by side on one thread each, and on a machine shared
  // with other work a second thread mostly waits for its partner (bench/journal.md, "Threads inside a run").
  o.run_opt.threads = 1;
  const std::string cores = std::to_string(dem::usable_cores());
  run->add_option("--threads", o.run_opt.threads,
                  "Threads inside the run: a number, or auto (the cores this process may use, " + cores +
                      ") (default 1; runs of at least 2048 elements can use 2 or more; never more than the usable "
                      "cores; fewer while the machine is busy with other work); the results are the same bit for "
                      "bit for any number")
      ->transform(CLI::Transformer({{"auto", cores}}))
      ->check(CLI::Range(1, 1024));
  run->add_flag("--restart-any-version", o.run_opt.restart_any_version,
                "Accept a checkpoint written by another dem2d version (refused otherwise: the restart would not "
                "continue bit for bit; summary.json records both versions)");
  run->add_flag("--fixed-threads", [&o](std::int64_t) { o.run_opt.governed = false; },
                "Exactly --threads threads at every step, also on a busy machine (benchmarks)");
  run->add_flag("--timings", o.run_opt.timings,
                "summary.json gets \"timings\": where the steps' time went, per thread and phase");
  run->add_option("--checkpoint-every", o.run_opt.checkpoint_every,
                  "Write <out>/checkpoint.bin every N steps (replaced each time; SIGINT/SIGTERM always write one)")
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--checkpoint-at-end", o.run_opt.checkpoint_at_end, "Write <out>/checkpoint.bin at the end of the run");
  auto* restart_opt = run->add_option("--restart", o.restart,
                                      "Continue from a checkpoint of this case (bit for bit like the uninterrupted run)")
                          ->check(CLI::ExistingFile);
  run->add_option("--start-from", o.start_from,
                  "Start this case from the state of a checkpoint of another case (same elements, walls and dt)")
      ->check(CLI::ExistingFile)
      ->excludes(restart_opt);
}

void add_check(CLI::App& app, Cli& o) {
  o.check = app.add_subcommand("check", "Check a case (keys, units, values, time step) without running it");
  o.check->add_option("case", o.case_file, "Case file (TOML)")->required()->check(CLI::ExistingFile);
  o.check->add_option("--set", o.sets, "Override a case value: key=value");
}

void add_schema(CLI::App& app, Cli& o) {
  o.schema = app.add_subcommand("schema", "Print the JSON Schema (draft-07) of the case format, made from the reader's "
                                          "key table: for editors and TOML language servers (docs/running.md)");
}

void add_study_and_sweep(CLI::App& app, Cli& o) {
  auto* study = o.study =
      app.add_subcommand("study", "Run one verification study and write its result.json; fails if a check fails");
  study->add_option("study", o.study_file, "Study file (verification/<name>/study.toml)")->required()->check(CLI::ExistingFile);
  study->add_option("--out", o.out_dir, "Output folder (default build/studies/<name>)");
  study->add_option("-j,--jobs", o.jobs, "Runs in parallel (1 to 4096)")->check(CLI::Range(1, 4096));
  study->add_flag("--fresh", o.fresh, "Clear the cache of finished runs in the study folder first (run everything again)");
  study->add_flag("-v,--verbose", o.verbose,
                  "A line per finished run on stderr (on a terminal a status line shows runs done, reused, time left)");

  auto* sweep = o.sweep =
      app.add_subcommand("sweep", "Run one sensitivity study (one-at-a-time, Morris, Sobol') and write its result.json");
  sweep->add_option("study", o.study_file, "Sensitivity study file (verification/sensitivity_<name>/sensitivity.toml)")
      ->required()->check(CLI::ExistingFile);
  sweep->add_option("--out", o.out_dir, "Output folder (default build/studies/<name>)");
  sweep->add_option("-j,--jobs", o.jobs, "Runs in parallel (1 to 4096)")->check(CLI::Range(1, 4096));
  sweep->add_flag("--fresh", o.fresh, "Clear the cache of finished runs in the study folder first");
  sweep->add_flag("-v,--verbose", o.verbose,
                  "A line per finished run on stderr (on a terminal a status line shows runs done, reused, time left)");
  sweep->add_flag("--design-only", o.design_only,
                  "Write the design (design.csv: each run's parameter values, SI, ASCII names and units) and run nothing; "
                  "then `dem2d analyse`");
  auto* analyse = o.analyse = app.add_subcommand(
      "analyse", "Analyse a sensitivity study's design from outputs computed anywhere (see sweep --design-only): the same indices.csv and result.json");
  analyse->add_option("study", o.study_file, "Sensitivity study file")->required()->check(CLI::ExistingFile);
  analyse->add_option("--outputs", o.outputs_file, "CSV with a run column (0 … n−1, as design.csv) and one column per output of the study")
      ->required()->check(CLI::ExistingFile);
  analyse->add_option("--out", o.out_dir, "Output folder (default build/studies/<name>)");
}

void add_report(CLI::App& app, Cli& o) {
  auto* rep = o.report =
      app.add_subcommand("report", "Write the verification report (index.html, index.md) from study results");
  rep->add_option("--studies", o.studies_dir, "Folder with one sub-folder per study holding result.json");
  rep->add_option("--out", o.report_dir, "Report folder");
  rep->add_option("--docs", o.docs_dir,
                  "The docs/ folder rendered into the page, every citation linked to it (default: ./docs, else the "
                  "source tree's)");
  rep->add_option("--bench", o.bench_dir,
                  "The speed benchmark shown in the report: a bench/suite.py output folder (table.md, cost.svg) or "
                  "a folder of kept tables, of which the name that sorts last (default: ./bench/results, else the "
                  "source tree's)")
      ->check(CLI::ExistingDirectory);
  rep->add_option("--claims", o.claims_file,
                  "The papers' items (verification/paper_claims.toml): the section \"The papers, item by item\"; a claim "
                  "whose check or figure matches nothing in a present result makes the exit status 2");
}

/// A first word that is no subcommand: says so and returns true (CLI11 would ask for one).
bool unknown_subcommand(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  std::vector<std::string> names;
  for (const auto* sub : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(sub->get_name());
  if (std::find(names.begin(), names.end(), argv[1]) != names.end()) return false;
  const std::string near = dem::nearest_word(argv[1], names);
  fmt::print(stderr, "error: unknown subcommand '{}'{} (dem2d --help lists them: {})\n", argv[1],
             near.empty() ? "" : fmt::format("; did you mean '{}'?", near), fmt::join(names, ", "));
  return true;
}

/// --out must be a folder or not exist yet: the rule, message and exit status (4) of `dem2d run` and `report`.
void check_out_is_folder(const std::string& out) {
  std::error_code ec;
  if (!out.empty() && fs::exists(out, ec) && !fs::is_directory(out, ec))
    throw dem::OutputError(fmt::format("{}: --out: exists and is not a folder", out));
}

int cmd_study(const Cli& o, bool sweep) {
  check_out_is_folder(o.out_dir);
  ver::StudyOptions so;
  so.out_dir = o.out_dir;
  so.jobs = o.jobs;
  so.use_cache = !o.fresh;
  so.verbose = o.verbose;
  if (sweep && o.design_only) {
    ver::write_sensitivity_design(o.study_file, so);
    return 0;
  }
  if (sweep) return ver::run_sensitivity(o.study_file, so).passed ? 0 : 1;
  const ver::StudyResult r = ver::run_study(o.study_file, so);
  return r.passed ? 0 : 1;
}

int cmd_report(const Cli& cli, int argc, char** argv) {
  report::Options o;
  o.studies_dir = cli.studies_dir;
  o.out_dir = cli.report_dir;
  o.title = "dem2d verification report";
  o.provenance = dem::provenance();
  std::string command;  // the exact command that wrote the report
  for (int k = 0; k < argc; ++k) command += (k ? " " : "") + std::string(argv[k]);
  o.provenance["report command"] = command;
  o.provenance["libraries"] = o.provenance["libraries"].get<std::string>() + ", " + ref::library_versions() +
                              ", CLI11 " CLI11_VERSION;
  o.provenance["working directory"] = fs::current_path().string();
  o.docs_dir = !cli.docs_dir.empty() ? fs::path(cli.docs_dir)
               : fs::is_directory("docs") ? fs::path("docs") : fs::path(DEM2D_SOURCE_DIR) / "docs";
  o.bench_dir = !cli.bench_dir.empty() ? fs::path(cli.bench_dir)
                : fs::is_directory("bench/results") ? fs::path("bench/results")
                                                   : fs::path(DEM2D_SOURCE_DIR) / "bench/results";
  o.claims_file = cli.claims_file;
  report::print_study_summary(cli.studies_dir);
  const report::Written w = report::write_report(o);
  fmt::print("report: {} studies, {} figures\n  {}\n  {}\n", w.studies, w.figures, fs::absolute(w.html).string(),
             fs::absolute(w.markdown).string());
  std::fflush(stdout);  // the errors after the summary, not inside it
  for (const auto& e : w.claim_errors) fmt::print(stderr, "error: {}\n", e);
  return w.claim_errors.empty() ? 0 : 2;  // a claim that matches nothing is a mistake in the claims file
}

/// Runs the chosen subcommand; each kind of error is an exit status (kExitCodes).
int dispatch(Cli& o, int argc, char** argv) {
  try {
    if (*o.run) {
      o.run_opt.restart = !o.restart.empty() ? o.restart : o.start_from;
      o.run_opt.restart_other_case = !o.start_from.empty();
      if (const int usable = dem::threads_for_run(o.run_opt.threads); usable < o.run_opt.threads) {
        if (!o.quiet)
          fmt::print(stderr, "dem2d: --threads {}: this process may use {} cores (affinity, cgroup quota); running on {}\n",
                     o.run_opt.threads, usable, usable);
        o.run_opt.threads_asked = o.run_opt.threads;
        o.run_opt.threads = usable;
      }
      return cmd_run(o.case_file, o.sets, o.out_dir, o.quiet, o.run_opt);
    }
    if (*o.check) return cmd_check(o.case_file, o.sets);
    if (*o.schema) {
      fmt::print("{}\n", dem::case_schema().dump(2));
      return 0;
    }
    if (*o.study) return cmd_study(o, false);
    if (*o.sweep) return cmd_study(o, true);
    if (*o.analyse) {
      check_out_is_folder(o.out_dir);
      ver::StudyOptions so;
      so.out_dir = o.out_dir;
      return ver::analyse_sensitivity(o.study_file, o.outputs_file, so).passed ? 0 : 1;
    }
    if (*o.report) return cmd_report(o, argc, argv);
  } catch (const dem::CaseError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const dem::OutputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 4;
  } catch (const ver::StudyInterrupted& e) {
    fmt::print(stderr, "interrupted: {} (finished runs are cached; run the study again to continue)\n", e.what());
    return interrupted_exit();
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef DEM2D_MPI
  ver::mpi::Session mpi(&argc, &argv);  // MPI for the whole program (a single process is a job of one rank)
#endif
  CLI::App app{"dem2d — verification-first 2D distinct element method testbed (Cundall disks, Matsui's "
               "pseudo-rectangle elements)"};
  app.require_subcommand(1);
  {  // dem2d --version: the code version (git describe), build type and compiler
    const nlohmann::json p = dem::provenance();
    app.set_version_flag("--version", fmt::format("dem2d {} ({} build, {})", p["code_version"].get<std::string>(),
                                                  p["build_type"].get<std::string>(), p["compiler"].get<std::string>()));
  }
  Cli o;
  add_run(app, o);
  add_check(app, o);
  add_schema(app, o);
  add_study_and_sweep(app, o);
  add_report(app, o);
  app.footer(kExitCodes);
  for (auto* sub : app.get_subcommands([](CLI::App*) { return true; })) sub->footer(kExitCodes);
  if (unknown_subcommand(app, argc, argv)) return 2;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, the version or the error
    return code == 0 ? 0 : 2;      // every command-line mistake is exit 2, like a mistake in an input file
  }
  // SIGINT / SIGTERM: runs stop at the next step and write everything. `check` writes nothing: it keeps
  // the default action (Ctrl-C ends it at once).
  if (!*o.check) dem::install_interrupt_handlers();
  std::signal(SIGXFSZ, SIG_IGN);      // a file size limit makes writes fail (reported, exit 4) instead of killing
#ifdef DEM2D_MPI
  // Under mpirun: rank 0 does the command; for study and sweep the other ranks run what it hands out
  // (engine/mpi/mpi_runs.hpp, docs/cluster.md), for any other command they do nothing.
  if (mpi.rank() > 0) return (*o.study || *o.sweep) ? ver::mpi::serve(o.jobs) : 0;
  std::optional<ver::mpi::Distributor> distributor;
  if (mpi.size() > 1 && (*o.study || *o.sweep)) distributor.emplace(o.jobs);
#endif
  return dispatch(o, argc, argv);
}
