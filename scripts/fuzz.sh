#!/usr/bin/env bash
# Fuzzes the input boundary with libFuzzer (fuzz/README.md): fuzz_case (whole case text → read_case +
# check_case), fuzz_case_read (the same text → the reader alone, fast), fuzz_override (--set strings on a fixed case), fuzz_checkpoint (crafted checkpoints restarted),
# fuzz_study and fuzz_sensitivity (study and sensitivity files) and fuzz_result (result.json → the report),
# built in build-san/ with ASan + UBSan.
#   scripts/fuzz.sh --minutes 30        30 minutes in all, split over the targets by their weights (the long run)
#   scripts/fuzz.sh --seconds 45        45 s for case and override, 3/8 of it (16 s) for each of the five
#                                       others: 170 s of fuzzing, two targets at a time on 2 cores (CI)
#   scripts/fuzz.sh --runs 20000        a fixed number of inputs per target (repeatable)
#   --target NAME                       one target only (case, case_read, override, checkpoint, study, sensitivity, result)
# The seeds are cases/, tests/lib/fixtures/ and fuzz/corpus/<target>/ (read only); what libFuzzer learns goes
# to build-san/fuzz-work/<target>/. A finding (crash, sanitizer report, unlocated error) is written to
# build-san/fuzz-findings/<target>/ and the script fails: fix it, then copy the input into
# fuzz/regression/<target>/ so that ctest replays it.
set -euo pipefail
cd "$(dirname "$0")/.."
per_target_seconds=60; runs=""; targets=(case case_read override checkpoint study sensitivity result)
while [ $# -gt 0 ]; do
  case "$1" in
    --minutes) total=$(( $2 * 60 )); shift 2; per_target_seconds=-1 ;;
    --seconds) per_target_seconds=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --target) targets=("$2"); shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "fuzz.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
# Weights in eighths: the case reader and --set get 8, the newer targets 3 (small inputs, shallow readers).
weight() { case "$1" in case|override) echo 8 ;; *) echo 3 ;; esac; }
if [ "$per_target_seconds" -lt 0 ]; then
  sum=0; for t in "${targets[@]}"; do sum=$(( sum + $(weight "$t") )); done
  unit_seconds=$(( total * 8 / sum ))  # the seconds of a weight-8 target
else
  unit_seconds=$per_target_seconds
fi

bash scripts/setup.sh
if [ ! -f build-san/CMakeCache.txt ]; then
  cmake -S . -B build-san -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1" -DDEM2D_SANITIZE=ON -DDEM2D_FUZZ=ON > build-san.log 2>&1 \
    || { cat build-san.log; exit 1; }
fi
cmake --build build-san -j"$(nproc 2>/dev/null || echo 2)" --target "${targets[@]/#/fuzz_}" >> build-san.log 2>&1 \
  || { tail -50 build-san.log; exit 1; }

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# One libFuzzer process per target, as many at a time as there are cores (each is single-threaded; the
# 2 cores of CI run two targets side by side). Each writes its own log; the results print in target order.
parallel=${DEM2D_FUZZ_JOBS:-$(nproc 2>/dev/null || echo 2)}
fuzz_one() {  # target: runs it, leaves its exit status in build-san/fuzz-<target>.status
  local t=$1 seeds dict seconds limit work findings log
  work=build-san/fuzz-work/$t; findings=build-san/fuzz-findings/$t
  mkdir -p "$work" "$findings"
  if [ "$t" = case ] || [ "$t" = case_read ]; then seeds=(cases tests/lib/fixtures fuzz/regression/case)
  else seeds=(fuzz/corpus/"$t"); [ -d fuzz/regression/"$t" ] && seeds+=(fuzz/regression/"$t"); fi
  dict=(); case "$t" in case|case_read|override|study|sensitivity) dict=(-dict=fuzz/case.dict) ;; esac
  seconds=$(( unit_seconds * $(weight "$t") / 8 )); [ "$seconds" -lt 1 ] && seconds=1
  limit=(-max_total_time="$seconds")
  [ -n "$runs" ] && limit=(-runs="$runs")
  # -timeout: one input may take at most 10 s; -rss_limit_mb: 2 GB (a machine shared by many)
  log=build-san/fuzz-$t.log
  echo "fuzz: $t (${limit[*]})"
  local status=0
  build-san/fuzz/fuzz_"$t" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=16384 \
    "${dict[@]}" -print_final_stats=1 -artifact_prefix="$findings/" \
    "$work" "${seeds[@]}" > "$log" 2>&1 || status=$?
  echo $status > build-san/fuzz-$t.status
}
rm -f build-san/fuzz-*.status
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do wait -n || true; done
  fuzz_one "$t" &
done
wait
status=0
for t in "${targets[@]}"; do
  log=build-san/fuzz-$t.log; findings=build-san/fuzz-findings/$t
  if [ "$(cat build-san/fuzz-$t.status 2>/dev/null || echo 1)" = 0 ]; then
    runs_done=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    secs=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
    echo "fuzz: $t: $runs_done inputs, $secs inputs/s, $cov, no finding"
  else
    status=1
    echo "fuzz: $t: FINDING (log $log, input in $findings/):"
    grep -E "FUZZ FINDING|ERROR:|runtime error|SUMMARY|^    #[0-9] " "$log" | head -30
  fi
done
exit $status
