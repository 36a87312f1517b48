#!/usr/bin/env bash
# The project's main job: install what is missing, build (Release), run the verification suite
# (ctest -L verification), print its summary table, write the report (build/report/index.html and
# index.md) and, when Chromium is installed, check the page in a real browser (ctest -L browser:
# every figure rendered, no repeated tick label, no NaN/inf; tests/browser/check_report.py).
# It builds what each step needs when it needs it: the dem2d command line first (the studies and the
# report need nothing else), then, after the report, the rest of the build (test executables, fuzz
# harnesses, benchmarks, the Python module) for the README's second command, the whole default suite.
# Each step is timed (scripts/phases.sh; .ci/run prints the table).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/phases.sh
jobs=$(nproc 2>/dev/null || echo 2)
phase "setup" bash scripts/setup.sh
build() {  # cmake --build with the output in build.log (its tail shown on a failure)
  cmake --build build -j"$jobs" "$@" >> build.log 2>&1 || { tail -50 build.log; return 1; }
}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
phase "build: dem2d (the command line)" build --target dem2d
status=0
phase "ctest -L verification" ctest --test-dir build -L verification -j"$jobs" --output-on-failure || status=$?
phase "report" build/app/dem2d report --studies build/studies --out build/report --claims verification/paper_claims.toml
echo "verify: report written to build/report/index.html (and index.md)"
if command -v chromium > /dev/null || command -v chromium-browser > /dev/null; then
  phase "ctest -L browser" ctest --test-dir build -L browser --output-on-failure || status=$?
else
  echo "verify: chromium not found, browser check of the report skipped"
fi
phase "build: the rest (tests, fuzz replays, benchmarks, Python module)" build
exit $status
