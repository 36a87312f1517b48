#!/usr/bin/env python3
"""Reads a run's outputs as a user's tools would (issue 12): series.csv with pandas.read_csv defaults
(one header line, each column "quantity [unit]", numbers only) and summary.json (every probe with its
unit, the resolved case in SI). Usage: read_series_pandas.py DEM2D_EXECUTABLE SOURCE_DIR WORK_DIR.
Fails (never skips) when pandas is missing: scripts/setup.sh installs python3-pandas."""
import json
import math
import pathlib
import shutil
import subprocess
import sys

try:
    import pandas as pd
except ImportError as e:  # a missing tool is a failure, not a skip
    sys.exit(f"FAIL: pandas is not installed ({e}); run scripts/setup.sh (Debian package python3-pandas)")

exe, src, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
out = work / "pandas_disk_wall"
shutil.rmtree(out, ignore_errors=True)
subprocess.run([exe, "run", str(src / "cases/impact/disk_wall.toml"), "--out", str(out), "--quiet"], check=True)

df = pd.read_csv(out / "series.csv")  # the defaults: nothing to skip, no comment character
expected = ["t [s]", "e0.y [m]", "e0.vy [m/s]", "e0.fn.floor [N]"]
fails = []
if list(df.columns) != expected:
    fails.append(f"columns {list(df.columns)}, expected {expected}")
if len(df) != 201:
    fails.append(f"{len(df)} rows, expected 201 (2000 steps, every 10th, plus t = 0)")
for col in df.columns:
    if df[col].dtype.kind != "f":
        fails.append(f"column {col!r} is {df[col].dtype}, expected float (a non-numeric line in the file?)")
if not fails:
    if df["t [s]"].iloc[0] != 0.0 or not math.isclose(df["t [s]"].iloc[-1], 0.02, rel_tol=1e-9):
        fails.append(f"t runs {df['t [s]'].iloc[0]} .. {df['t [s]'].iloc[-1]} s, expected 0 .. 0.02 s")
    if df["e0.fn.floor [N]"].max() <= 0:
        fails.append("the floor contact force is never positive")

s = json.loads((out / "summary.json").read_text())
for name, p in s["probes"].items():
    if not isinstance(p, dict) or "unit" not in p or "value" not in p:
        fails.append(f"probe {name}: {p!r}, expected {{value, unit}}")
if s["probes"].get("tc", {}).get("unit") != "s":
    fails.append(f"probe tc: unit {s['probes'].get('tc')}, expected s")
rc = s["resolved_case"]["numerics"]
if not (isinstance(rc["dt"], float) and rc["integrator"] in ("K18", "K19") and rc["velocity_start"]):
    fails.append(f"resolved_case.numerics {rc}: expected SI numbers and every default")

if fails:
    sys.exit("FAIL:\n  " + "\n  ".join(fails))
print(f"OK: pandas {pd.__version__} read {len(df)} rows x {len(df.columns)} columns: {', '.join(df.columns)}")
