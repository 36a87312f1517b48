#include "engine/progress.hpp"

#include <cmath>

#include <fmt/format.h>

namespace ver {

namespace {
Progress* g_progress = nullptr;
}

Progress* current_progress() { return g_progress; }
ProgressScope::ProgressScope(Progress* p) : previous(g_progress) { g_progress = p; }
ProgressScope::~ProgressScope() { g_progress = previous; }

std::string clock_text(double seconds) {
  const auto s = static_cast<long long>(std::llround(std::max(0.0, seconds)));
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

Progress::Progress(std::string name, std::FILE* out, bool tty, bool verbose)
    : name_(std::move(name)), out_(out), tty_(tty), verbose_(verbose), start_(std::chrono::steady_clock::now()) {}

void Progress::close() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!closed_ && tty_ && out_ && (done_ > 0 || reused_ > 0)) {
    fmt::print(out_, "\r{}\x1b[K\n", line());
    std::fflush(out_);
  }
  closed_ = true;
}

void Progress::planned(std::size_t runs) {
  std::lock_guard<std::mutex> lock(mutex_);
  planned_ += runs;
  print_line();
}

void Progress::reused(std::size_t runs) {
  std::lock_guard<std::mutex> lock(mutex_);
  reused_ += runs;
  print_line();
}

void Progress::finished(const std::string& status, double seconds, const std::vector<std::string>& sets) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
  if (std::isfinite(seconds)) slowest_ = std::max(slowest_, seconds);
  if (verbose_ && out_ && !closed_) {
    std::string what;
    for (const auto& s : sets) what += (what.empty() ? "" : " ") + s;
    fmt::print(out_, "{}run {}/{}: {} in {:.3g} s{}{}\n", tty_ ? "\r\x1b[K" : "", done_ + reused_, planned_ + reused_, status,
               seconds, what.empty() ? "" : ": ", what);
  }
  print_line();
}

std::string Progress::line() const {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::size_t total = planned_ + reused_, finished = done_ + reused_;
  std::string s = fmt::format("{}: {}/{} runs ({} reused), {} elapsed", name_, finished, total, reused_, clock_text(elapsed));
  if (done_ > 0 && planned_ > done_) s += fmt::format(", ~{} left", clock_text(elapsed / static_cast<double>(done_) * static_cast<double>(planned_ - done_)));
  if (done_ > 0) s += fmt::format(", slowest {:.3g} s", slowest_);
  return s;
}

void Progress::print_line() {
  if (!tty_ || !out_ || closed_) return;
  fmt::print(out_, "\r{}\x1b[K", line());
  std::fflush(out_);
}

}  // namespace ver
