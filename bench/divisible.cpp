// dem2d_divisible: the 2-thread / 1-thread speed ratio of a step that divides perfectly, on dem2d's own pool,
// measured as dem2d_alternate measures dem2d's; run next to it, a reference for what two threads gave a step
// in the same minutes (bench/journal.md, "A perfectly divisible step beside dem2d's ratios").
//
//   dem2d_divisible [--elements 100000] [--read 1] [--write 1] [--flops 40 | --step-us T] [--steps 4000]
//                   [--block 50] [--threads 2] [--json FILE]
//
// A step here is a dem2d step without anything that could keep two threads from twice one: no serial part,
// no uneven shares, no data that two threads share, no rebuild. It is not an upper bound for dem2d: the
// pool's cost per step weighs more in a step that is cheaper, and the host treats two different programs
// differently (the section named at the top). Each element has `read` arrays that the step only reads
// and `write` arrays that it reads and writes (doubles, one array per field, as dem2d's elements); the step
// sums the element's read fields, applies `flops` dependent multiply-adds to the sum, and adds a small
// multiple of it to each written field (no fixed point: an element updated twice, or not at all, stays
// different). The default is arithmetic on little memory (1.6 MB at 10^5 elements); --step-us T instead
// picks the number of multiply-adds that makes a one-thread step last T microseconds (measured at the
// start), e.g. as long as a dem2d step. Larger --read/--write make the step a memory stream.
// Two sides, each with its own arrays, run interleaved block by block in one process: A on one thread, B on
// `threads` threads of dem2d's pool (dem::WorkerThreads, one job per step, as Simulation::step). Printed:
// the speed ratio B / A per pair of blocks (median, quartiles) and of the totals.
// Exit status: 0; 1 (the two sides' arrays differ); 2 (the JSON file could not be written, or the arrays do
// not fit in memory); CLI11's own codes for a wrong option.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "block_ratios.hpp"
#include "dem/core/worker_threads.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"

namespace {

struct Side {
  int threads = 1;
  std::vector<double> data;  // (read + write) arrays of n doubles, one after the other
  double seconds = 0.0;
  std::vector<double> block_seconds;
};

struct Shape {
  std::size_t n = 0, read = 0, write = 0, flops = 0;
};

// The step over elements [b, e): each element reads its fields, and writes its written ones; in tiles of
// 512 elements, field by field within a tile (loops the compiler vectorises, as dem2d's integration).
// Not inlined: both sides must run the same machine code. Inlined into its two call sites, g++ compiled them
// differently, and the ratio of the default step read 2.7-3.0 (measured), which no arithmetic step can reach.
[[gnu::noinline]] void step_range(const Shape& s, double* __restrict d, std::size_t b, std::size_t e) {
  constexpr std::size_t kTile = 512;
  double sum[kTile];
  const std::size_t n = s.n;
  for (std::size_t t0 = b; t0 < e; t0 += kTile) {
    const std::size_t m = std::min(kTile, e - t0);
    for (std::size_t i = 0; i < m; ++i) sum[i] = 0.0;
    for (std::size_t a = 0; a < s.read; ++a) {
      const double* __restrict f = d + a * n + t0;
      for (std::size_t i = 0; i < m; ++i) sum[i] += f[i];
    }
    for (std::size_t k = 0; k < s.flops; ++k)
      for (std::size_t i = 0; i < m; ++i) sum[i] = sum[i] * 0.999999 + 1e-9;
    for (std::size_t a = s.read; a < s.read + s.write; ++a) {
      double* __restrict f = d + a * n + t0;
      for (std::size_t i = 0; i < m; ++i) f[i] += 1e-7 * sum[i];
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dem2d_divisible: the 2-thread / 1-thread speed ratio of a perfectly divisible step on this machine"};
  long elements = 100000, read = 1, write = 1, flops = 40, steps = 4000, block = 50;
  int threads = 2;
  double step_us = 0.0;
  std::string json_path;
  app.add_option("--elements", elements, "elements (default 100000)")->check(CLI::Range(1L, 100000000L));
  app.add_option("--read", read, "arrays a step only reads (default 1)")->check(CLI::Range(0L, 1000L));
  app.add_option("--write", write, "arrays a step reads and writes (default 1)")->check(CLI::Range(1L, 1000L));
  CLI::Option* flops_opt = app.add_option("--flops", flops, "dependent multiply-adds per element and step (default 40)")
      ->check(CLI::Range(0L, 100000L));
  app.add_option("--step-us", step_us,
                 "instead of --flops: the multiply-adds that make a one-thread step last this many microseconds")
      ->check(CLI::Range(1.0, 1e9))
      ->excludes(flops_opt);
  app.add_option("--steps", steps, "steps of each side (default 4000)")->check(CLI::Range(1L, 1000000000L));
  app.add_option("--block", block, "steps per block (default 50)")->check(CLI::Range(1L, 1000000L));
  app.add_option("--threads", threads, "threads of side B (default 2; 1: both sides alike, a check of the method)")->check(CLI::Range(1, 1024));
  app.add_option("--json", json_path, "also write the result as JSON to this file");
  CLI11_PARSE(app, argc, argv);
  std::error_code ec_old;
  if (!json_path.empty()) std::filesystem::remove(json_path, ec_old);  // never a stale result if this run fails

  Shape shape{static_cast<std::size_t>(elements), static_cast<std::size_t>(read), static_cast<std::size_t>(write),
              static_cast<std::size_t>(flops)};
  const std::size_t arrays = shape.read + shape.write;
  Side side[2];
  side[1].threads = threads;
  using clock = std::chrono::steady_clock;
  try {
    for (Side& s : side) {
      s.data.resize(arrays * shape.n);
      for (std::size_t k = 0; k < s.data.size(); ++k) s.data[k] = 1.0 + 1e-6 * static_cast<double>(k % 9973);
    }
    if (step_us > 0.0) {  // a one-thread step of f multiply-adds lasts about t0 + c f: measured on a copy, twice
      std::vector<double> probe = side[0].data;
      auto per_step = [&](std::size_t f) {
        Shape p = shape;
        p.flops = f;
        std::vector<double> t(7);
        for (double& ti : t) {  // the median of 7 (a step as the run will see it, not its best)
          const auto t0 = clock::now();
          for (int i = 0; i < 3; ++i) step_range(p, probe.data(), 0, p.n);
          ti = std::chrono::duration<double>(clock::now() - t0).count() / 3.0;
        }
        return 1e6 * bench::quantile(t, 0.5);
      };
      per_step(0);  // warm-up
      const double t0 = per_step(0);
      auto solve = [&](std::size_t f, double tf) {  // the f for step_us on the line through (0, t0) and (f, tf)
        const double c = (tf - t0) / static_cast<double>(f);
        return c > 0.0 ? static_cast<std::size_t>(std::clamp(std::round((step_us - t0) / c), 1.0, 100000.0)) : f;
      };
      const std::size_t f1 = solve(40, per_step(40));
      shape.flops = solve(f1, per_step(f1));  // again from the first guess: a longer lever against the noise
    }
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "dem2d_divisible: {} elements x {} arrays x 2 sides do not fit in memory\n", shape.n, arrays);
    return 2;
  }
  dem::WorkerThreads pool(threads);

  for (long done = 0; done < steps;) {
    const long n = std::min(block, steps - done);
    const int first = static_cast<int>((done / block) % 2);  // which side starts alternates from pair to pair
    for (int q = 0; q < 2; ++q) {
      Side& s = side[(first + q) % 2];
      double* d = s.data.data();
      const auto t0 = clock::now();
      for (long i = 0; i < n; ++i) {
        if (s.threads == 1) {
          step_range(shape, d, 0, shape.n);
        } else {
          auto body = [&](int t) {
            const std::size_t nt = static_cast<std::size_t>(s.threads), k = static_cast<std::size_t>(t);
            step_range(shape, d, shape.n * k / nt, shape.n * (k + 1) / nt);
          };
          pool.run(body);
        }
      }
      const double secs = std::chrono::duration<double>(clock::now() - t0).count();
      s.seconds += secs;
      s.block_seconds.push_back(secs);
    }
    done += n;
  }

  const bench::BlockRatios br = bench::block_ratios(side[0].block_seconds, side[1].block_seconds);
  const double total_ratio = side[0].seconds / side[1].seconds;
  const double us_a = 1e6 * side[0].seconds / static_cast<double>(steps);  // per step
  const double us_b = 1e6 * side[1].seconds / static_cast<double>(steps);
  const double mb = 8.0 * static_cast<double>(arrays * shape.n) / 1e6;
  const bool same = std::memcmp(side[0].data.data(), side[1].data.data(), side[0].data.size() * sizeof(double)) == 0;
  fmt::print("{} elements x {} arrays ({:.1f} MB per side, {} read, {} written), {} flops per element{}, {} steps\n",
             shape.n, arrays, mb, shape.read, shape.write, shape.flops,
             step_us > 0.0 ? fmt::format(" (for a one-thread step of {:.0f} us)", step_us) : "", steps);
  fmt::print("A  1 thread : {:.1f} us per step\n", us_a);
  fmt::print("B  {} threads: {:.1f} us per step\n", threads, us_b);
  fmt::print("speed B / A over {} pairs of {}-step blocks: median {:.3f} (quartiles {:.3f} … {:.3f}); of the totals {:.3f}\n",
             br.pairs, block, br.median, br.q1, br.q3, total_ratio);
  fmt::print("final arrays {}\n", same ? "identical bit for bit" : "DIFFER");
  if (!json_path.empty()) {
    nlohmann::json j;
    j["elements"] = shape.n;
    j["read"] = shape.read;
    j["write"] = shape.write;
    j["flops"] = shape.flops;
    if (step_us > 0.0) j["step_us_asked"] = step_us;
    j["megabytes_per_side"] = mb;
    j["steps"] = steps;
    j["block"] = block;
    j["threads"] = threads;
    j["pairs"] = br.pairs;
    j["us_per_step"] = {{"a", us_a}, {"b", us_b}};
    j["speed_ratio_b_over_a"] = {{"median", br.median}, {"q1", br.q1}, {"q3", br.q3}, {"of_totals", total_ratio}};
    j["final_arrays_identical"] = same;
    j["provenance"] = dem::provenance();
    try {
      dem::write_file_atomic(json_path, j.dump(2) + "\n");  // whole or not at all
    } catch (const std::exception& e) {
      fmt::print(stderr, "dem2d_divisible: {}\n", e.what());
      return same ? 2 : 1;
    }
  }
  return same ? 0 : 1;
}
