#!/usr/bin/env bash
# Runs the 16-core benchmark on a machine without Debian packages (bench/README.md, "Sixteen cores"), from
# the repository's root, with the archive that bench/portable/pack.sh made:
#
#   bench/portable/run.sh [ARCHIVE] -- [bench/scaling.py options]
#
# It unpacks the archive into bench/portable/unpacked/, puts its programs and libraries first (env.sh),
# records the machine (lscpu, memory, cgroup, the bundle's versions) and runs bench/scaling.py with the
# bundle's dem2d (and dem2d_base, if packed, as "base"). Results go to $OUT if set (a lent machine's
# output folder), else /tmp/dem2d_scaling.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
ARCHIVE="$ROOT/bench/portable/bundle.tar.xz"
if [ $# -gt 0 ] && [ "$1" != "--" ]; then ARCHIVE=$1; shift; fi
[ "${1:-}" = "--" ] && shift
DEST="${OUT:-/tmp/dem2d_scaling}"
mkdir -p "$DEST"
UNPACK="$ROOT/bench/portable/unpacked"
rm -rf "$UNPACK" && mkdir -p "$UNPACK"
tar -C "$UNPACK" -xJf "$ARCHIVE"
# shellcheck source=/dev/null
source "$UNPACK/dem2d_bundle/env.sh"
{
  echo "date: $(date -u +%FT%TZ)"; uname -a; nproc
  lscpu 2>/dev/null || grep -m1 "model name" /proc/cpuinfo
  grep -E "MemTotal|MemAvailable" /proc/meminfo
  cat /sys/fs/cgroup/cpu.max 2>/dev/null || true
  dem2d --version 2>&1 | head -1
  [ -x "$DEM2D_BUNDLE/bin/dem2d_base" ] && dem2d_base --version 2>&1 | head -1
  lmp -h 2>/dev/null | sed -n 2,3p
  mpirun --version 2>&1 | head -1
} > "$DEST/machine.txt" 2>&1 || true
codes=(--dem2d "dem2d=$DEM2D_BUNDLE/bin/dem2d")
[ -x "$DEM2D_BUNDLE/bin/dem2d_base" ] && codes+=(--dem2d "base=$DEM2D_BUNDLE/bin/dem2d_base")
cd "$ROOT/bench"
PYTHONUNBUFFERED=1 python3 scaling.py "${codes[@]}" --lmp "$DEM2D_BUNDLE/bin/lmp" --out /tmp/dem2d_scaling_runs \
  --results "$DEST" "$@"
