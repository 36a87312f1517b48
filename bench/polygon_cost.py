#!/usr/bin/env python3
"""The cost of a polygon block against PRE blocks (Matsui & Nishimura §3(1) and conclusions), measured in one run.

Matsui and Nishimura write that their PRE block on the slope (Table 1) ran in about 1/10 of UDEC's time,
because a PRE's contact detection is simpler than a polygon's, and that the advantage holds only up to about
10 PREs per polygon. This script measures both on this code, one thread, the same time step for every run:
  * the slope (Table 1, case 1, Δt = 1 μs): one PRE block (cases/pre/block_on_slope.toml) against one polygon
    block (cases/polygon/block_on_slope.toml), the whole 0.5 s;
  * a block b × h on the slope (the mode-map cases, α = 40°, φ = 38°: it slides) made of n = 1 … 30 PREs of
    r = 12.5 mm (a bonded 1 × n or c × r lattice, cases/pre/block_mode.toml) against the same block as ONE
    polygon (cases/polygon/block_mode.toml), each over --duration of simulated time at Δt = 2 μs.
It repeats the grid --reps times interleaved, takes the least CPU time of each run (interference only adds
time) and writes DIR/table.md, DIR/results.json and, with gnuplot, DIR/polygon_cost.svg. A benchmark, not a
test: timings depend on the machine.

    python3 bench/polygon_cost.py [--dem2d build/app/dem2d] [--reps 3] [--duration "0.05 s"] [--out DIR]
"""
import argparse
import datetime
import json
import platform
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from machine import cpu_model

ROOT = Path(__file__).resolve().parent.parent
# n PREs as (columns, rows): a block one or more PREs wide
BLOCKS = [(1, 1), (1, 2), (1, 3), (2, 2), (1, 5), (2, 3), (2, 4), (3, 3), (2, 5), (3, 4), (4, 4), (4, 5), (5, 5), (5, 6)]


def run(dem2d, case, sets, work):
    out = Path(work) / "run"
    cmd = [str(dem2d), "run", str(case), "--out", str(out), "--threads", "1", "--fixed-threads"]
    for s in sets:
        cmd += ["--set", s]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stdout[-2000:]}")
    s = json.loads((out / "summary.json").read_text())
    shutil.rmtree(out)
    return s["cpu_seconds"], s["steps"]


def grid(a):
    g = [("slope", "PRE", 1, ROOT / "cases/pre/block_on_slope.toml", []),
         ("slope", "polygon", 1, ROOT / "cases/polygon/block_on_slope.toml", [])]
    common = ["physics.gravity.direction=-50 deg", f"numerics.duration={a.duration}", "numerics.dt=2e-6 s"]
    for c, r in BLOCKS:
        b, h = 0.025 * c, 0.025 * r
        g.append((f"{c}x{r}", "PREs", c * r, ROOT / "cases/pre/block_mode.toml",
                  common + [f"lattice.0.columns={c}", f"lattice.0.rows={r}", "contact.1.friction_angle=38 deg"]))
        g.append((f"{c}x{r}", "polygon", c * r, ROOT / "cases/polygon/block_mode.toml",
                  common + [f"element.0.size=[{b!r}, {h!r}]", f"element.0.position=[{b / 2!r}, {h / 2!r}]",
                            "contact.0.friction_angle=38 deg"]))
    return g


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--dem2d", type=Path, default=ROOT / "build" / "app" / "dem2d")
    p.add_argument("--reps", type=int, default=3)
    p.add_argument("--duration", default="0.05 s")
    p.add_argument("--out", type=Path, default=None)
    a = p.parse_args()
    if a.reps < 1:
        p.error("--reps: expected at least 1")
    g = grid(a)
    times = {k: [] for k in range(len(g))}
    steps = {}
    with tempfile.TemporaryDirectory() as work:
        for rep in range(a.reps):
            for k, (block, model, n, case, sets) in enumerate(g):
                cpu, st = run(a.dem2d, case, sets, work)
                times[k].append(cpu)
                steps[k] = st
            print(f"rep {rep + 1}/{a.reps} done", file=sys.stderr)
    rows = [{"block": b, "model": m, "pres": n, "case": str(c.relative_to(ROOT)), "sets": s, "steps": steps[k],
             "cpu_seconds": times[k], "best_cpu": min(times[k]), "us_per_step": 1e6 * min(times[k]) / steps[k]}
            for k, (b, m, n, c, s) in enumerate(g)]
    by = {(r["block"], r["model"]): r for r in rows}
    slope_ratio = by[("slope", "polygon")]["best_cpu"] / by[("slope", "PRE")]["best_cpu"]
    ratios = [{"block": f"{c}x{r}", "pres": c * r,
               "ratio": by[(f"{c}x{r}", "PREs")]["best_cpu"] / by[(f"{c}x{r}", "polygon")]["best_cpu"]} for c, r in BLOCKS]
    breakeven = next((x["pres"] for x in ratios if x["ratio"] >= 1.0), None)
    out = a.out or ROOT / "bench" / "results" / f"polygon_cost_{datetime.date.today().isoformat()}"
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"# A polygon block against PRE blocks: {datetime.date.today().isoformat()}", "",
             f"Machine: {cpu_model()} ({platform.machine()}), one thread. dem2d: `{a.dem2d}`. Least CPU time of "
             f"{a.reps} interleaved repetitions.", "",
             "## The slope of Table 1 (case 1, Δt = 1 μs, 0.5 s)", "",
             "| model | CPU [s] | μs per step |", "|---|---|---|"]
    for m in ("PRE", "polygon"):
        r = by[("slope", m)]
        lines.append(f"| one {m} block | {r['best_cpu']:.3f} | {r['us_per_step']:.3f} |")
    lines += ["", f"Polygon / PRE: **{slope_ratio:.2f}** (Matsui and Nishimura: UDEC / PRE ≈ 10).", "",
              f"## A block of n PREs against one polygon (α = 40°, φ = 38°, Δt = 2 μs, {a.duration})", "",
              "| block (PREs) | n PREs: μs per step | one polygon: μs per step | n PREs / polygon |", "|---|---|---|---|"]
    for x in ratios:
        pr, po = by[(x["block"], "PREs")], by[(x["block"], "polygon")]
        lines.append(f"| {x['block']} ({x['pres']}) | {pr['us_per_step']:.3f} | {po['us_per_step']:.3f} | {x['ratio']:.2f} |")
    lines += ["", "Break-even (the first n at which the PREs cost at least the polygon): "
              + (f"**n = {breakeven}**" if breakeven else "not reached up to 30") + " (Matsui and Nishimura: about 10)."]
    text = "\n".join(lines) + "\n"
    (out / "table.md").write_text(text)
    (out / "results.json").write_text(json.dumps({"date": datetime.datetime.now().isoformat(timespec="seconds"),
                                                   "machine": cpu_model(), "dem2d": str(a.dem2d), "reps": a.reps,
                                                   "duration": a.duration, "slope_polygon_over_pre": slope_ratio,
                                                   "breakeven_pres": breakeven, "ratios": ratios, "rows": rows},
                                                  indent=1) + "\n")
    gp = shutil.which("gnuplot")
    if gp:
        (out / "polygon_cost.dat").write_text("".join(f"{x['pres']} {x['ratio']}\n" for x in ratios))
        script = ("set terminal svg size 640,420 font 'sans,12'; set output 'polygon_cost.svg'; set logscale xy; set xrange [0.8:40]; "
                  "set xlabel 'n (PREs in the block)'; set ylabel 'CPU time of n PREs / one polygon'; set grid; "
                  "set key left top; set title 'A block of n PREs against one polygon (one thread)'; "
                  "plot 'polygon_cost.dat' using 1:2 with linespoints title 'measured', 1 with lines dt 2 title 'break-even'")
        subprocess.run([gp, "-e", script], cwd=out, check=True)
    print(text)
    print(f"written: {out}/table.md, results.json" + (", polygon_cost.svg" if gp else " (no gnuplot: no figure)"))


if __name__ == "__main__":
    main()
