#pragma once
// What the study engine and the sensitivity engine share for their runs: a cache of finished runs
// (resumable studies) and a small thread pool with a fixed assignment of results to slots.
#include <atomic>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/study.hpp"

namespace ver {

/// FNV-1a 64.
std::uint64_t fnv1a(std::string_view text, std::uint64_t h = 1469598103934665603ull);

/// The code version as a cache key: the recorded version (git describe) and a hash of this executable,
/// so that a rebuilt, uncommitted change never reuses results of the old code.
const std::string& code_identity();

/// A finished run as the cache keeps it.
struct CachedRun {
  std::string status, message;
  double eps = 0.0;  // element-steps per second
  std::map<std::string, std::optional<double>> probes;
  std::string code_version, date;  // of the run that wrote the entry (read back only)
  double seconds_per_step = 0.0;   // wall clock per step of that run (0: not recorded)
};

/// The cache file of a run, in `dir`: keyed by the code identity, the resolved case (its content after
/// the overrides), the run folder (`out`, empty if none) and the overrides.
std::filesystem::path cache_entry(const std::filesystem::path& dir, const nlohmann::json& resolved_case,
                                  const std::vector<std::string>& sets, const std::filesystem::path& out = {});

/// The cached run, or nothing if there is none or it cannot be read (then run again).
std::optional<CachedRun> read_cached(const std::filesystem::path& entry);

/// Writes a finished run (atomically) with the case path, the overrides and the code identity.
void write_cached(const std::filesystem::path& entry, const CachedRun& run, const std::string& case_path,
                  const std::vector<std::string>& sets);

/// <out>/running.json while a study or sweep is under way ("running": also what a study killed by
/// SIGKILL leaves); `end` records how it ended otherwise — "failed" or "interrupted" with the message —
/// and `remove` takes it away once result.json is in place.
void mark_running(const std::filesystem::path& out, const std::string& study);
void mark_ended(const std::filesystem::path& out, const std::string& study, const std::string& status,
                const std::string& message);

/// The folder of a study or sweep (opt.out_dir, or build/studies/<name>) made ready: the old result.json
/// removed first (never a stale result) and running.json written.
std::filesystem::path open_study_folder(const std::string& study, const StudyOptions& opt);

/// Calls f(); if it throws, records in running.json how the study ended ("interrupted" or "failed",
/// with the message) and rethrows.
template <class F>
auto marking_failure(const std::filesystem::path& out, const std::string& study, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const StudyInterrupted& e) {
    mark_ended(out, study, "interrupted", e.what());
    throw;
  } catch (const std::exception& e) {
    mark_ended(out, study, "failed", e.what());
    throw;
  }
}

/// Runs f(0) … f(n−1) on `jobs` threads; rethrows the first exception after all have finished.
template <class F>
void parallel_for(std::size_t n, int jobs, F&& f) {
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  std::mutex err_m;
  std::exception_ptr err;
  for (int t = 0; t < std::max(1, jobs); ++t)
    pool.emplace_back([&] {
      for (std::size_t k; (k = next++) < n;) {
        try {
          f(k);
        } catch (...) {
          std::lock_guard<std::mutex> l(err_m);
          if (!err) err = std::current_exception();
        }
      }
    });
  for (auto& th : pool) th.join();
  if (err) std::rethrow_exception(err);
}

}  // namespace ver
