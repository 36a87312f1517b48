#pragma once
// What a study or sweep tells the user while it runs (issue: a 1 572-run sweep printed nothing for
// ~400 s). On a terminal (stderr a TTY) one status line, rewritten as runs finish:
//   study beam_peak_load: 7/12 runs (5 reused), 0:41 elapsed, ~0:35 left, slowest 9.8 s
// With `verbose` one line per finished run (status, seconds, its overrides), TTY or not. Not a TTY and
// not verbose: nothing. The engines announce the runs they plan (planned) and those the cache served
// (reused); run_all reports each finished run (finished). Totals grow as batches are planned (a
// stability study's bisection plans one run at a time: no estimate of the time left then).
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

namespace ver {

class Progress {
 public:
  /// `out`: where to write (stderr); `tty`: rewrite one status line; `verbose`: a line per run.
  Progress(std::string name, std::FILE* out, bool tty, bool verbose);
  ~Progress() { close(); }
  /// Ends the status line (prints it once more with a newline); later reports print nothing more.
  void close();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void planned(std::size_t runs);   // runs to do (not in the cache)
  void reused(std::size_t runs);    // runs the cache served
  void finished(const std::string& status, double seconds, const std::vector<std::string>& sets);

  /// The status line as it stands (for tests and the last print).
  std::string line() const;

 private:
  void print_line();
  std::string name_;
  std::FILE* out_;
  bool tty_, verbose_, closed_ = false;
  std::chrono::steady_clock::time_point start_;
  std::size_t planned_ = 0, reused_ = 0, done_ = 0;
  double slowest_ = 0.0;
  mutable std::mutex mutex_;
};

/// The progress of the study being run (installed by run_study / run_sensitivity for their duration),
/// or nullptr. run_all reports to it.
Progress* current_progress();
/// Installs `p` while alive, restores the previous one after (RAII).
struct ProgressScope {
  explicit ProgressScope(Progress* p);
  ~ProgressScope();
  Progress* previous;
};

/// "m:ss" (or "h:mm:ss").
std::string clock_text(double seconds);

}  // namespace ver
