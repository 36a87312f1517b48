#!/usr/bin/env python3
"""The cost of the PRE face law (Matsui's Fig. 10(c)), measured in one run (bench/README.md, "The cost of N").

Matsui and Nishimura ran the mortar beam on the 2 × 8, 6 × 24 and 10 × 40 lattices with N = 1 … 5 face
segments, all at ONE time step, and drew each run's CPU time over that of the 16-element ordinary DEM
(2 × 8, N = 1). Their claims: the time grows with the element count in proportion or faster; it grows only
gently with N; "N = 5 costs a little under twice the ordinary DEM".

This script runs the same grid (plus N = 2 at the face ends, M13.2) with `dem2d run --threads 1
--fixed-threads`, every run over the same simulated time:
  * at one Δt for every lattice (the paper's way; default the finest lattice's case Δt), and
  * at each lattice's own case Δt (what the time-step limit asks: smaller elements, smaller Δt),
repeats the whole grid --reps times interleaved (so drifts of the machine fall on every run alike), takes
the least CPU time of each run (the best of the repetitions, as bench/scaling.py does: interference
only ever adds time), and divides by that of 2 × 8, N = 1 at the one Δt. It checks the
claim "N = 5 costs less than 2 × N = 1" on every lattice and writes DIR/results.json, DIR/table.md and,
where gnuplot is found, DIR/fig10c.svg. A benchmark, not a test: timings depend on the machine.

    python3 bench/pre_cost.py [--dem2d build/app/dem2d] [--reps 5] [--duration "8 ms"]
                              [--dt "2.5e-7 s"] [--lattices 2x8,6x24,10x40] [--out DIR] [--check]

--check: exit status 1 when the claim fails on a lattice.
"""
import argparse
import datetime
import json
import platform
import shutil
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

from machine import cpu_model

ROOT = Path(__file__).resolve().parent.parent
VARIANTS = [("N=1", 1, "centres"), ("N=2", 2, "centres"), ("N=3", 3, "centres"), ("N=4", 4, "centres"),
            ("N=5", 5, "centres"), ("ends", 2, "ends")]


def case_file(lattice):
    return ROOT / "cases" / "beam" / f"mortar_{lattice}.toml"


def case_dt(lattice):
    """The case's own Δt [s] (numerics.dt, "5e-7 s")."""
    text = tomllib.loads(case_file(lattice).read_text())["numerics"]["dt"]
    value, unit = text.split()
    if unit != "s":
        raise SystemExit(f"{case_file(lattice)}: numerics.dt: expected seconds, got {text!r}")
    return float(value)


def elements(lattice):
    rows, cols = (int(x) for x in lattice.split("x"))
    return rows * cols


def run_once(dem2d, lattice, segments, positions, dt, duration, work):
    out = Path(work) / "run"
    cmd = [str(dem2d), "run", str(case_file(lattice)), "--out", str(out), "--threads", "1", "--fixed-threads",
           "--set", f"contact.0.segments={segments}", "--set", f'contact.0.positions="{positions}"',
           "--set", f'numerics.dt="{dt!r} s"', "--set", f'numerics.duration="{duration}"',
           "--set", "stop.after_peak.drop=0.99"]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stdout[-2000:]}")
    s = json.loads((out / "summary.json").read_text())
    shutil.rmtree(out)
    return {"cpu": s["cpu_seconds"], "wall": s["wall_seconds"], "steps": s["steps"], "status": s["status"]}


def measure(a):
    grid = []  # (lattice, label, segments, positions, mode, dt)
    for lattice in a.lattices:
        for label, n, pos in VARIANTS:
            grid.append((lattice, label, n, pos, "one dt", a.dt))
        grid.append((lattice, "N=1", 1, "centres", "own dt", case_dt(lattice)))
        grid.append((lattice, "N=5", 5, "centres", "own dt", case_dt(lattice)))
    times = {g: [] for g in grid}
    with tempfile.TemporaryDirectory() as work:
        for rep in range(a.reps):
            for g in grid:
                lattice, label, n, pos, mode, dt = g
                r = run_once(a.dem2d, lattice, n, pos, dt, a.duration, work)
                times[g].append(r)
            print(f"rep {rep + 1}/{a.reps} done", file=sys.stderr)
    rows = []
    for g, rs in times.items():
        lattice, label, n, pos, mode, dt = g
        rows.append({"lattice": lattice, "elements": elements(lattice), "variant": label, "segments": n,
                     "positions": pos, "mode": mode, "dt": dt, "steps": rs[0]["steps"], "status": rs[0]["status"],
                     "cpu_seconds": [r["cpu"] for r in rs], "best_cpu": min(r["cpu"] for r in rs)})
    base = next(r["best_cpu"] for r in rows if r["lattice"] == a.lattices[0] and r["variant"] == "N=1" and r["mode"] == "one dt")
    for r in rows:
        r["relative"] = r["best_cpu"] / base
        spread = [c / base for c in r["cpu_seconds"]]
        r["relative_range"] = [min(spread), max(spread)]
    return rows


def claims(rows, lattices):
    """N = 5 over N = 1 per lattice at the one Δt: the paper's "a little under 2×"."""
    out = []
    for lattice in lattices:
        one = {r["variant"]: r for r in rows if r["lattice"] == lattice and r["mode"] == "one dt"}
        ratio = one["N=5"]["best_cpu"] / one["N=1"]["best_cpu"]
        out.append({"lattice": lattice, "claim": "N = 5 costs less than 2 × N = 1 (one Δt)", "value": ratio,
                    "limit": 2.0, "passed": ratio < 2.0})
    return out


def table_md(a, rows, checks):
    lines = [f"# The cost of N (Matsui Fig. 10(c)): {datetime.date.today().isoformat()}", "",
             f"Machine: {cpu_model()} ({platform.machine()}), one thread. dem2d: `{a.dem2d}`. Every run "
             f"{a.duration} of simulated loading; least CPU time of {a.reps} interleaved repetitions, over that of "
             f"{a.lattices[0]}, N = 1 at the one Δt ({a.dt:g} s). In brackets: the range over the repetitions.", "",
             "| lattice (elements) | " + " | ".join(v[0] for v in VARIANTS) + " | N=5 / N=1 |", "|---|" + "---|" * (len(VARIANTS) + 1)]
    for lattice in a.lattices:
        one = {r["variant"]: r for r in rows if r["lattice"] == lattice and r["mode"] == "one dt"}
        cells = [f"{one[v[0]]['relative']:.2f} ({one[v[0]]['relative_range'][0]:.2f}–{one[v[0]]['relative_range'][1]:.2f})" for v in VARIANTS]
        lines.append(f"| {lattice} ({elements(lattice)}) | " + " | ".join(cells) + f" | {one['N=5']['best_cpu'] / one['N=1']['best_cpu']:.2f} |")
    lines += ["", "At each lattice's own case Δt (the same simulated time, so finer lattices take more steps):", "",
              "| lattice | Δt [s] | steps | N=1 | N=5 |", "|---|---|---|---|---|"]
    for lattice in a.lattices:
        own = {r["variant"]: r for r in rows if r["lattice"] == lattice and r["mode"] == "own dt"}
        lines.append(f"| {lattice} | {own['N=1']['dt']:g} | {own['N=1']['steps']} | {own['N=1']['relative']:.2f} | {own['N=5']['relative']:.2f} |")
    lines += ["", "| claim | lattice | measured | verdict |", "|---|---|---|---|"]
    for c in checks:
        lines.append(f"| {c['claim']} | {c['lattice']} | {c['value']:.3f} | {'PASS' if c['passed'] else 'FAIL'} |")
    return "\n".join(lines) + "\n"


def figure(a, rows, out):
    gp = shutil.which("gnuplot")
    if not gp:
        return False
    data = out / "fig10c.dat"
    with data.open("w") as f:
        for lattice in a.lattices:
            f.write(f"# {lattice}\n")
            for r in rows:
                if r["lattice"] == lattice and r["mode"] == "one dt" and r["positions"] == "centres":
                    f.write(f"{r['segments']} {r['relative']} {r['relative_range'][0]} {r['relative_range'][1]}\n")
            f.write("\n\n")
    plots = ", ".join(f"'{data.name}' index {i} using 1:2:3:4 with yerrorlines title '{lat} ({elements(lat)} PREs)'"
                      for i, lat in enumerate(a.lattices))
    script = (f"set terminal svg size 640,420 font 'sans,12'; set output 'fig10c.svg'; set logscale y; "
              f"set xlabel 'N (segments per face, M13.1)'; set ylabel 'CPU time / that of 2 x 8, N = 1'; "
              f"set xrange [0.5:5.5]; set key left top; set grid; "
              f"set title 'Matsui Fig. 10(c): cost at one dt = {a.dt:g} s, {a.duration}'; plot {plots}")
    subprocess.run([gp, "-e", script], cwd=out, check=True)
    return True


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--dem2d", type=Path, default=ROOT / "build" / "app" / "dem2d")
    p.add_argument("--reps", type=int, default=5)
    p.add_argument("--duration", default="8 ms")
    p.add_argument("--dt", type=float, default=None, help="the one Δt [s] (default: the finest lattice's case Δt)")
    p.add_argument("--lattices", default="2x8,6x24,10x40")
    p.add_argument("--out", type=Path, default=None)
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    a.lattices = a.lattices.split(",")
    if a.reps < 1:
        p.error("--reps: expected at least 1")
    for lattice in a.lattices:
        if not case_file(lattice).exists():
            p.error(f"--lattices: no case {case_file(lattice)}")
    if a.dt is None:
        a.dt = min(case_dt(x) for x in a.lattices)
    out = a.out or ROOT / "bench" / "results" / f"pre_cost_{datetime.date.today().isoformat()}"
    out.mkdir(parents=True, exist_ok=True)
    rows = measure(a)
    checks = claims(rows, a.lattices)
    text = table_md(a, rows, checks)
    (out / "table.md").write_text(text)
    (out / "results.json").write_text(json.dumps({"date": datetime.datetime.now().isoformat(timespec="seconds"),
                                                   "machine": cpu_model(), "dem2d": str(a.dem2d), "reps": a.reps,
                                                   "duration": a.duration, "dt": a.dt, "rows": rows, "claims": checks},
                                                  indent=1) + "\n")
    drawn = figure(a, rows, out)
    print(text)
    print(f"written: {out}/table.md, results.json" + (", fig10c.svg" if drawn else " (no gnuplot: no figure)"))
    if a.check and not all(c["passed"] for c in checks):
        sys.exit(1)


if __name__ == "__main__":
    main()
