#!/usr/bin/env bash
# Speed benchmark (bench/README.md): dem2d and LAMMPS on the same 2D settle of 10^4 disks with linear
# contacts, one core each, in one run; prints both speeds in disk-steps/s and their ratio.
# Not part of ctest: speed is measured here, never in tests.
#
#   bench/run.sh [--reps N] [--granular] [--out DIR]
#
#   --reps N      runs of each code, interleaved; the best of each counts (default 3)
#   --granular    also run LAMMPS' pair_style granular (slower than gran/hooke/history)
#   --out DIR     keep the outputs there (default: a fresh directory under /tmp)
# Environment: BUILD (dem2d build directory, default build/), LMP (LAMMPS binary, default lmp),
# CASE (default cases/bench/settle_10k.toml).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
CASE=${CASE:-$ROOT/cases/bench/settle_10k.toml}
BUILD=${BUILD:-$ROOT/build}
LMP=${LMP:-lmp}
REPS=3
GRANULAR=0
OUT=""
while [ $# -gt 0 ]; do
  case "$1" in
    --reps) REPS=$2; shift 2 ;;
    --granular) GRANULAR=1; shift ;;
    --out) OUT=$2; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "bench/run.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ -n "$OUT" ] || OUT=$(mktemp -d /tmp/dem2d-bench.XXXXXX)
mkdir -p "$OUT"

DEM2D=$BUILD/app/dem2d
[ -x "$DEM2D" ] || { echo "bench/run.sh: $DEM2D not found: cmake --build build -j2" >&2; exit 1; }
command -v "$LMP" > /dev/null || { echo "bench/run.sh: LAMMPS ($LMP) not found: scripts/setup.sh --bench (Debian lammps)" >&2; exit 1; }
command -v python3 > /dev/null || { echo "bench/run.sh: python3 (3.11+, tomllib) is needed" >&2; exit 1; }

# One core, one thread each: no MPI launcher, no OpenMP threads, no accelerator suffix.
export OMP_NUM_THREADS=1

styles=(gran)
[ "$GRANULAR" = 1 ] && styles+=(granular)
for st in "${styles[@]}"; do
  python3 "$ROOT/bench/lammps_input.py" "$CASE" "$OUT/lammps_$st" --style "$st" > /dev/null
done

run_dem2d() {  # $1: run number
  local dir=$OUT/dem2d_$1
  "$DEM2D" run "$CASE" --out "$dir" > "$dir.log" 2>&1 || { cat "$dir.log" >&2; exit 1; }
}
run_lammps() {  # $1: style, $2: run number
  local dir=$OUT/lammps_$1
  (cd "$dir" && "$LMP" -in in.settle -log "log.$2" -screen none -nocite) || { tail -5 "$dir/log.$2" >&2; exit 1; }
}

echo "dem2d vs LAMMPS: $(basename "$CASE"), $REPS runs each (interleaved), outputs in $OUT"
for r in $(seq "$REPS"); do
  run_dem2d "$r"
  for st in "${styles[@]}"; do run_lammps "$st" "$r"; done
done

ROOT="$ROOT" python3 - "$OUT" "$REPS" "${styles[@]}" <<'PY'
import json, re, sys, os
sys.path.insert(0, os.path.join(os.environ["ROOT"], "bench"))
from machine import cpu_model
out, reps, styles = sys.argv[1], int(sys.argv[2]), sys.argv[3:]

dem = []
for r in range(1, reps + 1):
    s = json.load(open(f"{out}/dem2d_{r}/summary.json"))
    dem.append(s)
best_dem = max(dem, key=lambda s: s["element_steps_per_second"])
result = {"cpu": cpu_model(), "load_average": os.getloadavg()[0], "dem2d": {
    "disk_steps_per_second": best_dem["element_steps_per_second"],
    "all_runs": [s["element_steps_per_second"] for s in dem],
    "steps": best_dem["steps"], "disks": best_dem["elements"], "contacts_at_end": best_dem["contacts"],
    "rebuilds": best_dem["rebuilds"], "build_type": best_dem["provenance"]["build_type"],
    "code_version": best_dem["provenance"]["code_version"]}}
loop = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
for st in styles:
    runs = []
    for r in range(1, reps + 1):
        text = open(f"{out}/lammps_{st}/log.{r}").read()
        m = loop.search(text)
        secs, procs, steps, atoms = float(m[1]), int(m[2]), int(m[3]), int(m[4])
        assert procs == 1, "LAMMPS must run on one process"
        contacts = re.findall(r"^\s+%d\s+%d\s+\S+\s+(\S+)" % (steps, atoms), text, re.M)
        runs.append({"rate": steps * atoms / secs, "seconds": secs, "steps": steps, "atoms": atoms,
                     "pair_contacts_at_end": float(contacts[-1]) if contacts else None})
    best = max(runs, key=lambda x: x["rate"])
    result[f"lammps_{st}"] = {"disk_steps_per_second": best["rate"], "all_runs": [x["rate"] for x in runs],
                              "steps": best["steps"], "disks": best["atoms"],
                              "pair_contacts_at_end": best["pair_contacts_at_end"]}
json.dump(result, open(f"{out}/results.json", "w"), indent=2)

d = result["dem2d"]
print(f"machine: {result['cpu']}, load average {result['load_average']:.2f} (other load slows both codes)")
if d["build_type"] != "Release":
    print(f"WARNING: dem2d was built as {d['build_type']}, not Release")
print(f"dem2d ({d['code_version']}):  {d['disk_steps_per_second']:.3g} disk-steps/s  "
      f"({d['disks']} disks x {d['steps']} steps; {d['contacts_at_end']} contacts (with walls) at the end, {d['rebuilds']} rebuilds; "
      f"runs {', '.join('%.3g' % x for x in d['all_runs'])})")
names = {"gran": "pair_style gran/hooke/history", "granular": "pair_style granular"}
for st in styles:
    l = result[f"lammps_{st}"]
    print(f"LAMMPS {names[st]}:  {l['disk_steps_per_second']:.3g} disk-steps/s  "
          f"({l['disks']} disks x {l['steps']} steps; {l['pair_contacts_at_end']:.0f} disk-disk contacts at the end; "
          f"runs {', '.join('%.3g' % x for x in l['all_runs'])})")
    print(f"ratio dem2d / LAMMPS {names[st]}: {d['disk_steps_per_second'] / l['disk_steps_per_second']:.2f}")
print(f"results: {out}/results.json")
PY
