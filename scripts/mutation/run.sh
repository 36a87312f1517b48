#!/usr/bin/env bash
# Mutation testing: plants the bugs of mutants.txt ONE AT A TIME in a throw-away copy of the tree
# (never in the working tree), rebuilds incrementally, runs `ctest -L unit` and, if the mutant survived
# that, `ctest -L verification` (both --stop-on-failure, with a timeout), and prints per mutant
# killed/survived and the score. See scripts/README.md.
#
#   scripts/mutation/run.sh [options] [ID ...]
#     --rev REV        test the tree of commit REV (default: the tracked files as they are now)
#     --tests-rev REV  take tests/ (and tests/CMakeLists.txt) from commit REV, the rest as above:
#                      "the score before the new tests" on an unchanged core
#     --from N         start at the N-th mutant of the list (1-based); --count M: run M of them
#     --unit-only      skip the verification suite (a lower bound on the score)
#     --work DIR       copy, build and results here (default /tmp/dem2d_mutation); reused if present
#     --unit-timeout S, --verification-timeout S   per ctest test (default 120 s, 900 s)
#     --check          only check that every mutant applies exactly once, then exit
#     --mutants FILE   the list to run (default mutants.txt; generate.py writes others)
#     --skip-unlinked  for a mutant in reports/ or verification/, leave out the unit tests whose executables
#                      do not link that code (unit_lib "lib: ", unit_reference "reference: ", the dem2d_alternate
#                      and dem2d_divisible benches: they link dem2d_core or dem2d_reference only, so they
#                      cannot see the mutant); the score is the same, the run about twice as fast there
#     --ccache         build through ccache (with CCACHE_BASEDIR above --work, the first build of the
#                      copy reuses the objects of a checkout's build/: the copy builds in <work>/src/build)
#   IDs: run only these mutants.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
mutants="$here/mutants.txt" ccache=0 skip_unlinked=0
tool="$here/mutants.py"
work=/tmp/dem2d_mutation
rev="" tests_rev="" from=1 count=100000 unit_only=0 unit_timeout=120 ver_timeout=900 check=0
ids=()
while (($#)); do
  case "$1" in
    --rev) rev=$2; shift ;;
    --tests-rev) tests_rev=$2; shift ;;
    --from) from=$2; shift ;;
    --count) count=$2; shift ;;
    --unit-only) unit_only=1 ;;
    --work) work=$2; shift ;;
    --unit-timeout) unit_timeout=$2; shift ;;
    --verification-timeout) ver_timeout=$2; shift ;;
    --check) check=1 ;;
    --mutants) mutants=$(realpath "$2"); shift ;;
    --ccache) ccache=1 ;;
    --skip-unlinked) skip_unlinked=1 ;;
    -h|--help) sed -n 2,27p "$0"; exit 0 ;;
    -*) echo "unknown option $1" >&2; exit 2 ;;
    *) ids+=("$1") ;;
  esac
  shift
done

if ((check)); then exec python3 "$tool" check "$mutants" "$repo"; fi

src="$work/src" build="$work/src/build" orig="$work/orig"
mkdir -p "$work" "$orig"
if [[ ! -d "$src" ]]; then
  mkdir -p "$src"
  if [[ -n "$rev" ]]; then
    git -C "$repo" archive "$rev" | tar -x -C "$src"
  else
    (cd "$repo" && git ls-files -z | tar --null --ignore-failed-read -T - -cf -) | tar -x -C "$src"
  fi
  if [[ -n "$tests_rev" ]]; then
    rm -rf "$src/tests"
    git -C "$repo" archive "$tests_rev" tests | tar -x -C "$src"
  fi
  echo "copy: $src (rev: ${rev:-working tree}, tests: ${tests_rev:-same})"
fi
python3 "$tool" check "$mutants" "$src" >/dev/null || { python3 "$tool" check "$mutants" "$src"; exit 1; }

# every target: the unit label also runs the fuzz replays and the dem2d_alternate checks (a list of targets
# here fell behind the tests once: their executables were missing and the baseline failed)
build_all() { nice -n 15 cmake --build "$build" -j2 >"$work/build.log" 2>&1; }
exclude=()  # set per mutant by --skip-unlinked (see tests/CMakeLists.txt and bench/CMakeLists.txt: what links what)
run_ctest() {  # label timeout
  nice -n 15 ctest --test-dir "$build" -L "$1" "${exclude[@]}" --stop-on-failure --timeout "$2" -j2 >"$work/ctest.log" 2>&1
}

if [[ ! -f "$build/CMakeCache.txt" ]]; then
  launcher=()
  ((ccache)) && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  nice -n 15 cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >"$work/configure.log" 2>&1
fi
# ctest's --timeout does not override a test's own TIMEOUT property: the unit tests take theirs from this
# cache variable (a mutant that leaves a thread at a barrier fails in --unit-timeout, not in 600 s)
nice -n 15 cmake -S "$src" -B "$build" -DDEM2D_UNIT_TIMEOUT="$unit_timeout" >>"$work/configure.log" 2>&1
# The unmutated suite must pass, or every mutant would count as killed.
if [[ ! -f "$work/baseline.unit.ok" ]]; then
  echo "baseline: building and running the unmutated unit tests ..."
  build_all || { echo "baseline build failed: $work/build.log"; exit 1; }
  run_ctest unit "$unit_timeout" || { echo "baseline unit tests fail: $work/ctest.log"; exit 1; }
  touch "$work/baseline.unit.ok"
fi
if ((!unit_only)) && [[ ! -f "$work/baseline.verification.ok" ]]; then
  echo "baseline: running the unmutated verification suite ..."
  run_ctest verification "$ver_timeout" || { echo "baseline verification fails: $work/ctest.log"; exit 1; }
  touch "$work/baseline.verification.ok"
fi

mapfile -t all < <(python3 "$tool" list "$mutants")
if ((${#ids[@]} == 0)); then ids=("${all[@]:$((from - 1)):$count}"); fi
results="$work/results.tsv"
[[ -f "$results" ]] || printf 'id\tstatus\tseconds\tfile\tbreaks\n' >"$results"

current=""
# Restore the original text with a new time stamp, so that the next build recompiles it.
restore() { if [[ -n "$current" ]]; then cp "$orig/saved" "$src/$current"; touch "$src/$current"; current=""; fi; }
trap restore EXIT
trap 'restore; exit 130' INT TERM  # stop, with the file restored

for id in "${ids[@]}"; do
  IFS=$'\t' read -r file breaks < <(python3 "$tool" show "$mutants" "$id")
  start=$(date +%s)
  cp -p "$src/$file" "$orig/saved"
  current=$file
  python3 "$tool" apply "$mutants" "$src" "$id"
  exclude=()
  if ((skip_unlinked)); then
    case "$file" in reports/*|verification/*) exclude=(-E '^(lib|reference): |^bench: dem2d_(alternate|divisible)') ;; esac
  fi
  if ! build_all; then
    status="build-error"
  elif ! run_ctest unit "$unit_timeout"; then
    status="killed(unit)"
    cp "$work/ctest.log" "$work/log.$id"
  elif ((unit_only)); then
    status="survived(unit)"
  elif ! run_ctest verification "$ver_timeout"; then
    status="killed(verification)"
    cp "$work/ctest.log" "$work/log.$id"
  else
    status="SURVIVED"
  fi
  restore
  secs=$(($(date +%s) - start))
  printf '%s\t%s\t%s\t%s\t%s\n' "$id" "$status" "$secs" "$file" "$breaks" >>"$results"
  printf '%-28s %-22s %5ss  %s\n' "$id" "$status" "$secs" "$breaks"
done

# Score over every mutant recorded in this work folder (build errors are not counted).
awk -F'\t' 'NR > 1 && $2 != "build-error" { n++; if ($2 ~ /^killed/) k++ }
            END { if (n) printf "score: %d of %d killed (%.1f %%)\n", k, n, 100 * k / n }' "$results"
awk -F'\t' 'NR > 1 && $2 !~ /^killed/ { print "  not killed: " $1 " (" $2 "): " $5 }' "$results"
