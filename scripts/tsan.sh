#!/usr/bin/env bash
# The thread-sanitizer job: a clang build in build-tsan/ with ThreadSanitizer (-fsanitize=thread), then the
# unit tests that step runs on several threads (Catch2 tags [threads] and [spatial_order]) and the study
# engine's tests (a study runs its runs on several threads). Any data race TSan sees fails the job (exit
# 66), and so does a hang (a time limit per run).
#
# Why: the bit-for-bit tests compare results on 1, 2 and 3 threads, but a race may give the same bits on
# most runs and hang or differ on one. One did: the rebuild test at the start of a step shared its flags
# with the integration at the end of it, so that a thread descheduled between the two could read the next
# step's flag, enter the rebuild alone and wait for ever at its barrier (lib/dem/core/simulation.hpp,
# displaced_now_; bench/journal.md, "A hang in CI").
# TSan reports such an unordered read and write on every run, whatever the timing. Its first run over the
# engine's tests found another: the runs of a study each formatted their date with std::gmtime, whose one
# static buffer they shared (run.cpp now uses gmtime_r).
#
# Usage: scripts/tsan.sh [Catch2 test spec for unit_lib, default "[threads],[spatial_order]"]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
source scripts/phases.sh
# The default spec runs on unit_lib_threads, only the test files that carry those tags (tests/CMakeLists.txt);
# another spec needs the whole unit_lib.
spec=${1:-"[threads],[spatial_order]"}
lib_tests=unit_lib_threads
[ "$spec" = "[threads],[spatial_order]" ] || lib_tests=unit_lib
log=build-tsan.log
# clang (its precompiled headers take a third off the test files' compile time; g++ took 30 % longer than
# clang on the same files, docs/toolchain.md "Build time"); -gline-tables-only: file:line in every frame of a
# race report without the full debug info.
if [ ! -f build-tsan/CMakeCache.txt ]; then
  cmake -S . -B build-tsan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
        -DCMAKE_CXX_FLAGS="-fsanitize=thread" -DDEM2D_PYTHON=OFF \
        -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" > $log 2>&1 || { cat $log; exit 1; }
fi
build() { cmake --build build-tsan -j"$jobs" --target $lib_tests unit_engine >> $log 2>&1 || { tail -50 $log; return 1; }; }
start=$(date +%s)
phase "build-tsan" build
echo "tsan: build-tsan built in $(( $(date +%s) - start )) s"
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}
# TSan's shadow memory needs the address layout of vm.mmap_rnd_bits <= 28 on some kernels (it crashes
# at start otherwise); setarch -R turns address randomisation off for this run only.
start=$(date +%s)
status=0
phase "tests: $lib_tests $spec" timeout 1800 setarch "$(uname -m)" -R build-tsan/tests/$lib_tests "$spec" --warn NoTests \
  || status=$?
if [ $status -eq 0 ]; then
  phase "tests: unit_engine" timeout 1200 setarch "$(uname -m)" -R build-tsan/tests/unit_engine --warn NoTests || status=$?
fi
echo "tsan: the tests ran in $(( $(date +%s) - start )) s, exit status $status"
if [ $status -eq 124 ]; then echo "tsan: the tests did not finish in time (a hang?)" >&2; fi
exit $status
