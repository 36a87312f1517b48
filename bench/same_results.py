#!/usr/bin/env python3
"""Behaviour-neutral check of an optimisation (bench/README.md): runs every cases/*/*.toml with two dem2d
builds (`dem2d run CASE --out DIR`, plus any extra arguments of each build) and compares series.csv (without its
`#` provenance lines), every file under vtk/, and summary.json without provenance and timings, byte for byte / value
for value.

    python3 bench/same_results.py BEFORE AFTER [--after-args "--threads 2"] [--out DIR] [--jobs 2]
                                  [--set numerics.duration=...] [CASE ...]

Exit status 0 if every case gives identical outputs. BEFORE and AFTER are dem2d binaries (e.g. a build of
main copied aside, and build/app/dem2d).
"""
import argparse
import json
import shlex
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
VOLATILE = {"provenance", "wall_seconds", "cpu_seconds", "element_steps_per_second", "wall_time", "started", "finished",
            "threads", "timings"}


def strip(j):
    if isinstance(j, dict):
        return {k: strip(v) for k, v in j.items() if k not in VOLATILE}
    if isinstance(j, list):
        return [strip(v) for v in j]
    return j


def run(binary, extra, case, out, sets):
    cmd = [binary, "run", str(case), "--out", str(out), "-q"] + extra
    for s in sets:
        cmd += ["--set", s]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return r.returncode, r.stdout[-500:]


def data(path):
    """The file without its provenance comment lines (`# ...`: the code version)."""
    return [l for l in path.read_bytes().splitlines() if not l.startswith(b"#")]


def compare(a, b):
    diffs = []
    fa, fb = a / "series.csv", b / "series.csv"
    if fa.exists() or fb.exists():
        if not (fa.exists() and fb.exists()) or data(fa) != data(fb):
            diffs.append("series.csv")
    va = sorted(p.relative_to(a) for p in (a / "vtk").rglob("*") if p.is_file()) if (a / "vtk").exists() else []
    vb = sorted(p.relative_to(b) for p in (b / "vtk").rglob("*") if p.is_file()) if (b / "vtk").exists() else []
    if va != vb:
        diffs.append("vtk file list")
    diffs += [str(p) for p in va if p in vb and (a / p).read_bytes() != (b / p).read_bytes()]
    sa, sb = a / "summary.json", b / "summary.json"
    if strip(json.load(open(sa))) != strip(json.load(open(sb))):
        diffs.append("summary.json")
    return diffs, len(va)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--before-args", default="")
    ap.add_argument("--after-args", default="")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("cases", nargs="*")
    a = ap.parse_intermixed_args()
    out = a.out or Path(tempfile.mkdtemp(prefix="dem2d-same."))
    cases = [Path(c) for c in a.cases] or sorted(ROOT.glob("cases/*/*.toml"))

    def one(case):
        name = f"{case.parent.name}_{case.stem}"
        ra = run(a.before, shlex.split(a.before_args), case, out / name / "before", a.set)
        rb = run(a.after, shlex.split(a.after_args), case, out / name / "after", a.set)
        if ra[0] != rb[0]:
            return name, [f"exit status {ra[0]} vs {rb[0]}: {ra[1]} | {rb[1]}"], 0
        if not (out / name / "before" / "summary.json").exists():
            return name, [f"no output (exit {ra[0]}): {ra[1]}"], 0
        d, nv = compare(out / name / "before", out / name / "after")
        return name, d, nv

    bad = 0
    with ThreadPoolExecutor(a.jobs) as ex:
        for name, diffs, nv in ex.map(one, cases):
            print(f"{'SAME' if not diffs else 'DIFFERENT'}  {name}  (series.csv, {nv} vtk files, summary.json)"
                  + ("" if not diffs else ": " + ", ".join(diffs[:10])), flush=True)
            bad += bool(diffs)
    print(f"{len(cases) - bad} of {len(cases)} cases identical; outputs in {out}")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
