#!/usr/bin/env bash
# The sanitizer job: a clang build in build-san/ with AddressSanitizer + UndefinedBehaviorSanitizer
# (any report fatal) and libFuzzer coverage (-DDEM2D_SANITIZE=ON -DDEM2D_FUZZ=ON), then the unit tests
# under the sanitizers: ctest -L unit (Catch2 tests, the fuzz regression replays, the toml++ check).
# The verification studies are not run here (too slow instrumented). Usage: scripts/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/phases.sh
bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
log=build-san.log
if [ ! -f build-san/CMakeCache.txt ]; then
  cmake -S . -B build-san -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1" -DDEM2D_SANITIZE=ON -DDEM2D_FUZZ=ON > $log 2>&1 \
    || { cat $log; exit 1; }
fi
build() {
  cmake --build build-san -j"$jobs" --target unit_lib unit_reference unit_engine fuzz_case fuzz_case_read fuzz_override \
    fuzz_checkpoint fuzz_study fuzz_sensitivity fuzz_result dem2d dem2d_alternate dem2d_divisible \
    >> $log 2>&1 || { tail -50 $log; return 1; }
}
start=$(date +%s)
phase "build-san" build
echo "sanitize: build-san built in $(( $(date +%s) - start )) s"
phase "ctest -L unit (sanitized)" ctest --test-dir build-san -L unit -j"$jobs" --output-on-failure
