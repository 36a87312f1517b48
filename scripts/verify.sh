#!/usr/bin/env bash
# The project's main job: install what is missing, build (Release), run the verification suite
# (ctest -L verification), print its summary table and write the report (build/report/index.html).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j"$jobs" >> build.log 2>&1 || { tail -50 build.log; exit 1; }
status=0
ctest --test-dir build -L verification -j"$jobs" --output-on-failure || status=$?
build/app/dem2d report --studies build/studies --out build/report
exit $status
