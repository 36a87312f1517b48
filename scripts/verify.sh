#!/usr/bin/env bash
# The project's main job: install what is missing, build (Release), run the verification suite
# (ctest -L verification), print its summary table, write the report (build/report/index.html and
# index.md) and, when Chromium is installed, check the page in a real browser (ctest -L browser:
# every figure rendered, no repeated tick label, no NaN/inf; tests/browser/check_report.py).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j"$jobs" >> build.log 2>&1 || { tail -50 build.log; exit 1; }
status=0
ctest --test-dir build -L verification -j"$jobs" --output-on-failure || status=$?
build/app/dem2d report --studies build/studies --out build/report --claims verification/paper_claims.toml
echo "verify: report written to build/report/index.html (and index.md)"
if command -v chromium > /dev/null || command -v chromium-browser > /dev/null; then
  ctest --test-dir build -L browser --output-on-failure || status=$?
else
  echo "verify: chromium not found, browser check of the report skipped"
fi
exit $status
