#!/usr/bin/env python3
"""The speed suite (bench/README.md): dem2d side by side with LAMMPS (Debian `lammps`, binary `lmp`) in one
interleaved run. Not part of ctest: speed is measured here, never in tests.

    python3 bench/suite.py [--quick] [--big] [--reps N] [--out DIR] [--dem2d LABEL=PATH ...] [--lmp lmp] [--only-pre]

Cases (written into the output folder):
  settle  bench/make_settle_case.py scaled: 10^3 disks x 10^4 steps, 10^4 x 10^4 (the bench case),
          10^5 x 4000, and with --big 10^6 x 1000; dem2d on 1 and 2 threads, LAMMPS
          pair_style gran/hooke/history on one process (bench/lammps_input.py);
  pre     bench/make_pre_lattice_case.py: a bonded 100 x 100 PRE lattice, faces of N = 1 ... 5 segments,
          2000 steps, dem2d on 1 thread (LAMMPS has no such element);
  shuffled the 10^4 settle with its disks numbered at random (make_settle_case.py --shuffle), reordering off
          and on (numerics.reorder_every = 10), dem2d on 1 thread (bench/journal.md, "Locality");
  silo    the silo discharge of 3x10^4 disks, cases/silo/discharge_30k.toml (bench/make_silo_case.py; --quick:
          8000 steps), dem2d on 1 thread and LAMMPS (bench/lammps_input.py: region walls for the floor and
          the gate); its rate counts the disks at the start (both codes lose disks through the slit).
--quick: fewer steps (a smoke run of the whole suite in about a minute; the ratios are noisier).

Every run repeats --reps times (default 3), all codes interleaved, in an order rotated from rep to rep; the best
run of each counts (other load only slows a run down); peak memory is the smallest maximum resident set size of
the runs (/usr/bin/time). The ratios within dem2d (2 threads / 1 thread from 10^4 disks, PRE N = 2 ... 5 / N = 1)
are also measured interleaved block by block in one process (build/bench/dem2d_alternate, --alternate PATH),
and each 2-thread ratio right after it for a step that divides perfectly, of as many elements and as long as
dem2d's one-thread step (build/bench/dem2d_divisible, --divisible PATH): a reference for the same minutes.
--dem2d LABEL=PATH (repeatable) compares several dem2d builds, e.g. before=/tmp/dem2d_main after=build/app/dem2d;
a build without --threads is run without it (one thread).

Writes DIR/results.json, DIR/table.md (markdown) and DIR/cost.svg (cost per element-step against size,
log-log), and prints the table.
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

from machine import cpu_model
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

SETTLE = [  # (label, rows, cols, steps, quick steps)
    ("1e3", 20, 50, 10000, 2000),
    ("1e4", 50, 200, 10000, 2000),
    ("1e5", 200, 500, 4000, 500),
]
SETTLE_BIG = ("1e6", 500, 2000, 1000, 100)
SHUFFLED = (50, 200, 10000, 2000)  # the 10^4 settle numbered at random (make_settle_case.py --shuffle): locality
REORDER_EVERY = 10                 # numerics.reorder_every of its reordered run
PRE = (100, 100, 2000, 400)  # rows, cols, steps, quick steps
SILO_CASE = ROOT / "cases/silo/discharge_30k.toml"  # bench/make_silo_case.py's output
SILO_QUICK = (150, 200, 8000)  # --quick: the same silo, 8000 steps (the gate opens after 6000)


def timed(cmd, cwd=None, env=None):
    """Runs cmd under /usr/bin/time; returns the peak resident set size [bytes]."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as tf:
        full = ["/usr/bin/time", "-f", "%M", "-o", tf.name] + cmd
        r = subprocess.run(full, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0:
            sys.exit(f"bench/suite.py: {' '.join(cmd)} failed:\n{r.stdout[-2000:]}")
        return int(tf.read().strip().splitlines()[-1]) * 1024


def has_threads(binary):
    r = subprocess.run([binary, "run", "--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return "--threads" in r.stdout


def run_dem2d(binary, case, out, threads, threads_ok):
    cmd = [binary, "run", str(case), "--out", str(out), "-q"]
    if threads_ok:
        cmd += ["--threads", str(threads)]
    elif threads != 1:
        return None
    mem = timed(cmd)
    s = json.load(open(out / "summary.json"))
    n0 = s["resolved_case"]["elements"]["count"]  # at the start (a discharge removes disks)
    return {"rate": s["element_steps_per_second"], "memory": mem, "elements": s["elements"], "steps": s["steps"],
            "contacts": s["contacts"], "elements0": n0, "rate0": n0 * s["steps"] / s["wall_seconds"],
            "discharged": s.get("discharge", {}).get("discharged")}


LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")


def run_lammps(lmp, folder, rep, script="in.settle"):
    """One LAMMPS run; a script of several `run`s (the silo: before and after the gate opens) sums their Loop
    times; rate0 counts the atoms of the first part (the start), rate those at the end."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    mem = timed([lmp, "-in", script, "-log", f"log.{rep}", "-screen", "none", "-nocite"], cwd=folder, env=env)
    loops = LOOP.findall((folder / f"log.{rep}").read_text())
    assert loops and all(int(m[1]) == 1 for m in loops)
    secs, steps = sum(float(m[0]) for m in loops), sum(int(m[2]) for m in loops)
    atoms0, atoms = int(loops[0][3]), int(loops[-1][3])
    return {"rate": steps * atoms / secs, "memory": mem, "elements": atoms, "steps": steps, "elements0": atoms0,
            "rate0": steps * atoms0 / secs, "discharged": atoms0 - atoms}


def best(runs):
    runs = [r for r in runs if r]
    if not runs:
        return None
    b = dict(max(runs, key=lambda r: r["rate"]))
    b["memory"] = min(r["memory"] for r in runs)
    b["all_rates"] = [r["rate"] for r in runs]
    for key in ("rate", "rate0"):
        b[f"median_{key}"] = statistics.median(r[key] for r in runs)
    return b


def slope(points):
    """points: [(elements, cost per element-step)]. Least-squares slope of log(time per step) = log(elements x
    cost) against log(elements): 1 + that of the cost per element-step (1: flat)."""
    if len(points) < 2:
        return None
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(n * cost) for n, cost in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


# The slope's meaning, checked at every run (until 22 Nov 2026 it was fed costs as if they were rates and
# printed 2 - slope): a flat cost gives 1, a cost growing 10x over 10^3 -> 10^6 gives 4/3.
assert abs(slope([(1e3, 20.0), (1e6, 20.0)]) - 1.0) < 1e-12
assert abs(slope([(1e3, 10.0), (1e4, 10.0 * 10 ** (1 / 3)), (1e6, 100.0)]) - 4.0 / 3.0) < 1e-12


def svg_plot(series, path):
    """series: {name: [(elements, ns per element-step)]} -> a log-log plot as SVG (no dependencies)."""
    W, H, L, B, T, R = 640, 420, 70, 50, 20, 170
    pts = [p for s in series.values() for p in s]
    if not pts:
        return
    x0, x1 = math.floor(math.log10(min(p[0] for p in pts))), math.ceil(math.log10(max(p[0] for p in pts)))
    y0 = math.floor(math.log10(min(p[1] for p in pts)) * 2) / 2
    y1 = math.ceil(math.log10(max(p[1] for p in pts)) * 2) / 2
    x1, y1 = max(x1, x0 + 1), max(y1, y0 + 0.5)
    px = lambda n: L + (math.log10(n) - x0) / (x1 - x0) * (W - L - R)
    py = lambda c: H - B - (math.log10(c) - y0) / (y1 - y0) * (H - B - T)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<line x1="{L}" y1="{H - B}" x2="{W - R}" y2="{H - B}" stroke="black"/>',
           f'<line x1="{L}" y1="{T}" x2="{L}" y2="{H - B}" stroke="black"/>']
    for e in range(x0, x1 + 1):
        x = px(10 ** e)
        out.append(f'<line x1="{x:.1f}" y1="{H - B}" x2="{x:.1f}" y2="{T}" stroke="#ddd"/>')
        out.append(f'<text x="{x:.1f}" y="{H - B + 16}" text-anchor="middle">10^{e}</text>')
    v = y0
    while v <= y1 + 1e-9:
        y = py(10 ** v)
        out.append(f'<line x1="{L}" y1="{y:.1f}" x2="{W - R}" y2="{y:.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{L - 6}" y="{y + 4:.1f}" text-anchor="end">{10 ** v:.3g}</text>')
        v += 0.5
    out.append(f'<text x="{(L + W - R) / 2}" y="{H - 12}" text-anchor="middle">elements (disks)</text>')
    out.append(f'<text x="16" y="{(T + H - B) / 2}" text-anchor="middle" transform="rotate(-90 16 {(T + H - B) / 2})">'
               'wall-clock ns per element-step</text>')
    colours = ["#1f77b4", "#2ca02c", "#d62728", "#9467bd", "#ff7f0e", "#8c564b"]
    for k, (name, s) in enumerate(series.items()):
        c = colours[k % len(colours)]
        s = sorted(s)
        out.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>'
                   % (c, " ".join(f"{px(n):.1f},{py(v):.1f}" for n, v in s)))
        for n, v in s:
            out.append(f'<circle cx="{px(n):.1f}" cy="{py(v):.1f}" r="3.5" fill="{c}"/>')
        out.append(f'<line x1="{W - R + 12}" y1="{T + 14 + 18 * k}" x2="{W - R + 32}" y2="{T + 14 + 18 * k}" stroke="{c}" stroke-width="2"/>')
        out.append(f'<text x="{W - R + 38}" y="{T + 18 + 18 * k}">{name}</text>')
    out.append("</svg>")
    path.write_text("\n".join(out) + "\n")


def run_alternated(a, cases, out, sizes):
    """The ratios within dem2d (2 threads against 1 on the settles from 10^4 disks; the PRE lattice at N = 2 ... 5
    against N = 1), each --reps times with dem2d_alternate: both runs of a ratio in one process, 50-step blocks
    in turn, so that they meet the same moments of the machine. [] without the tool."""
    tool = Path(a.alternate)
    if not os.access(tool, os.X_OK):
        print(f"bench/suite.py: {tool} not found (cmake --build build --target dem2d_alternate): no interleaved ratios",
              file=sys.stderr)
        return []
    pairs = [(f"{c}@1", f"{c}@2", f"settle {label}: 1 thread", f"2 threads") for kind, label, c, _ in cases
             if kind == "settle" and label != "1e3"]  # 10^3: one thread whatever --threads says (under 4096 per thread)
    pre = {label: c for kind, label, c, _ in cases if kind == "pre"}
    if "N1" in pre:
        pairs += [(str(pre["N1"]), str(pre[f"N{n}"]), "PRE lattice N = 1", f"N = {n}") for n in range(2, 6)
                  if f"N{n}" in pre]
    # Next to each 2-thread ratio, in the same minutes: dem2d_divisible's, for a step that divides perfectly
    # (arithmetic on little memory), of as many elements and as long as that run's one-thread step.
    divisible = Path(a.divisible)
    if not os.access(divisible, os.X_OK):
        print(f"bench/suite.py: {divisible} not found (cmake --build build --target dem2d_divisible): no reference "
              "step", file=sys.stderr)
    result = []
    for ra, rb, la, lb in pairs:
        runs, divs = [], []
        for rep in range(a.reps):
            j = out / f"alternate_{len(result)}_{rep}.json"
            r = subprocess.run([str(tool), ra, rb, "--json", str(j)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True)
            if r.returncode != 0:
                sys.exit(f"bench/suite.py: dem2d_alternate {ra} {rb} failed:\n{r.stdout[-2000:]}")
            ja = json.load(open(j))
            runs.append(ja["speed_ratio_b_over_a"])
            if ra in sizes and os.access(divisible, os.X_OK):
                jd = out / f"divisible_{len(result)}_{rep}.json"
                n, st = sizes[ra]
                step_us = 1e6 * ja["a"]["seconds"] / ja["steps"]  # dem2d's one-thread step in this run
                r = subprocess.run([str(divisible), "--elements", str(n), "--steps", str(st), "--step-us",
                                    f"{step_us:.3f}", "--json", str(jd)],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
                if r.returncode != 0:
                    sys.exit(f"bench/suite.py: dem2d_divisible failed:\n{r.stdout[-2000:]}")
                divs.append(json.load(open(jd))["speed_ratio_b_over_a"])
        result.append({"a": la, "b": lb, "runs": runs, "divisible": divs})
        print(f"alternated: {la} / {lb} done", file=sys.stderr, flush=True)
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--big", action="store_true", help="also 10^6 disks")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--out", type=Path)
    ap.add_argument("--dem2d", action="append", default=[], help="LABEL=PATH (default dem2d=build/app/dem2d)")
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--alternate", default=str(ROOT / "build/bench/dem2d_alternate"),
                    help="dem2d_alternate, for the ratios within dem2d interleaved block by block")
    ap.add_argument("--divisible", default=str(ROOT / "build/bench/dem2d_divisible"),
                    help="dem2d_divisible, the 2-thread / 1-thread ratio of a perfectly divisible step, next to dem2d's")
    ap.add_argument("--no-pre", action="store_true")
    ap.add_argument("--only-pre", action="store_true", help="only the PRE lattice N = 1 ... 5 (no settle, shuffled, silo)")
    a = ap.parse_args()
    out = a.out or Path(tempfile.mkdtemp(prefix="dem2d-suite."))
    out.mkdir(parents=True, exist_ok=True)
    if not os.access("/usr/bin/time", os.X_OK):  # GNU time: the peak memory of every run
        sys.exit("bench/suite.py: /usr/bin/time not found (GNU time, for peak memory): scripts/setup.sh --bench")
    builds = [tuple(s.split("=", 1)) for s in a.dem2d] or [("dem2d", str(ROOT / "build/app/dem2d"))]
    for _, b in builds:
        if not os.access(b, os.X_OK):
            sys.exit(f"bench/suite.py: {b} not found: cmake --build build -j2")
    lmp = shutil.which(a.lmp)
    if not lmp:
        print(f"bench/suite.py: LAMMPS ({a.lmp}) not found (scripts/setup.sh --bench installs it): dem2d only", file=sys.stderr)
    threads_ok = {label: has_threads(b) for label, b in builds}

    settle = [] if a.only_pre else SETTLE + ([SETTLE_BIG] if a.big else [])
    cases = []  # (kind, label, case path, lammps folder)
    sizes = {}  # "settle case@1": (elements, steps), for dem2d_divisible
    for label, rows, cols, steps, quick in settle:
        st = quick if a.quick else steps
        case = out / f"settle_{label}.toml"
        case.write_text(subprocess.run([sys.executable, str(ROOT / "bench/make_settle_case.py"), str(rows), str(cols),
                                        str(st)], check=True, stdout=subprocess.PIPE, text=True).stdout)
        lf = out / f"lammps_{label}"
        if lmp:
            subprocess.run([sys.executable, str(ROOT / "bench/lammps_input.py"), str(case), str(lf)], check=True,
                           stdout=subprocess.DEVNULL)
        cases.append(("settle", label, case, lf))
        sizes[f"{case}@1"] = (rows * cols, st)
    if not a.no_pre:
        rows, cols, steps, quick = PRE
        for n in range(1, 6):
            case = out / f"pre_N{n}.toml"
            case.write_text(subprocess.run([sys.executable, str(ROOT / "bench/make_pre_lattice_case.py"), str(rows),
                                            str(cols), str(quick if a.quick else steps), str(n)],
                                           check=True, stdout=subprocess.PIPE, text=True).stdout)
            cases.append(("pre", f"N{n}", case, None))
    # locality (bench/journal.md, "Locality"): the 10^4 settle with its disks numbered at random, reordering
    # off and on
    rows, cols, steps, quick = SHUFFLED
    text = "" if a.only_pre else subprocess.run([sys.executable, str(ROOT / "bench/make_settle_case.py"), str(rows), str(cols),
                           str(quick if a.quick else steps), "--shuffle"], check=True, stdout=subprocess.PIPE, text=True).stdout
    for every in (() if a.only_pre else (0, REORDER_EVERY)):
        case = out / f"shuffled_reorder{every}.toml"
        case.write_text(text.replace('integrator = "K18"\n', f'integrator = "K18"\nreorder_every = {every}\n', 1))
        cases.append(("shuffled", f"reorder_every={every}", case, None))
    if SILO_CASE.exists() and not a.only_pre:
        case = SILO_CASE
        if a.quick:
            case = out / "silo_quick.toml"
            case.write_text(subprocess.run([sys.executable, str(ROOT / "bench/make_silo_case.py")] +
                                           [str(v) for v in SILO_QUICK], check=True, stdout=subprocess.PIPE,
                                           text=True).stdout)
        lf = out / "lammps_silo"
        if lmp:
            subprocess.run([sys.executable, str(ROOT / "bench/lammps_input.py"), str(case), str(lf)], check=True,
                           stdout=subprocess.DEVNULL)
        cases.append(("silo", "3e4", case, lf))

    runs = {}  # (kind, label, code) -> [run]
    for rep in range(1, a.reps + 1):
        for kind, label, case, lf in cases:
            # the codes of a case, in an order rotated by one from rep to rep: a code that always ran first
            # would always meet the machine as the previous case left it (measured:
            # bench/journal.md, "Ratios interleaved block by block")
            jobs = [(bl, b, th) for bl, b in builds for th in ((1, 2) if kind == "settle" else (1,))]
            if lmp and kind in ("settle", "silo"):
                jobs.append(("LAMMPS", None, 1))
            shift = (rep - 1) % len(jobs)
            for blabel, b, th in jobs[shift:] + jobs[:shift]:
                if blabel == "LAMMPS":
                    r = run_lammps(lmp, lf, rep, "in.silo" if kind == "silo" else "in.settle")
                    runs.setdefault((kind, label, "LAMMPS"), []).append(r)
                else:
                    r = run_dem2d(b, case, out / f"run_{kind}_{label}_{blabel}_t{th}_{rep}", th, threads_ok[blabel])
                    runs.setdefault((kind, label, f"{blabel} {th}T"), []).append(r)
            print(f"rep {rep}: {kind} {label} done", file=sys.stderr, flush=True)
    alternated = run_alternated(a, cases, out, sizes)

    res = {"cpu": cpu_model(), "cores": os.cpu_count(), "load_average": os.getloadavg(), "reps": a.reps,
           "quick": a.quick, "builds": dict(builds), "best": {}}
    for (kind, label, code), rs in runs.items():
        b = best(rs)
        if b:
            res["best"][f"{kind} {label} {code}"] = b
    B = res["best"]
    lines = [f"Machine: {res['cpu']}, {res['cores']} cores, load average {res['load_average'][0]:.1f} at the end; "
             f"best of {a.reps} interleaved runs{' (--quick)' if a.quick else ''}.", ""]
    codes = [f"{bl} {t}T" for bl, _ in builds for t in (1, 2)]
    head = "| settle | " + " | ".join(f"{c} [Mdisk-steps/s]" for c in codes)
    if lmp:
        head += " | LAMMPS [Mdisk-steps/s] | " + " | ".join(f"{c} / LAMMPS" for c in codes)
    head += " | " + " | ".join(f"{bl} 1T peak memory [B/disk]" for bl, _ in builds)
    if lmp:
        head += " | LAMMPS peak memory [B/disk] | " + " | ".join(f"{bl} / LAMMPS memory" for bl, _ in builds)
    head += " | " + " | ".join(f"{bl} 2T / 1T" for bl, _ in builds) + " |"
    lines += [head, "|" + "---|" * (head.count("|") - 1)]
    plot = {}
    for label, *_ in settle:
        row = [f"{label} disks"]
        get = lambda c: B.get(f"settle {label} {c}")
        lam = get("LAMMPS")
        row += [f"{get(c)['rate'] / 1e6:.1f}" if get(c) else "-" for c in codes]
        if lmp:
            row.append(f"{lam['rate'] / 1e6:.1f}")
            row += [f"{get(c)['rate'] / lam['rate']:.2f}" if get(c) else "-" for c in codes]
        for bl, _ in builds:
            g = get(f"{bl} 1T")
            row.append(f"{g['memory'] / g['elements']:.0f}" if g else "-")
        if lmp:
            row.append(f"{lam['memory'] / lam['elements']:.0f}")
            for bl, _ in builds:
                g = get(f"{bl} 1T")
                row.append(f"{g['memory'] / lam['memory']:.2f}" if g else "-")
        for bl, _ in builds:
            g1, g2 = get(f"{bl} 1T"), get(f"{bl} 2T")
            row.append(f"{g2['rate'] / g1['rate']:.2f}" if g1 and g2 else "-")
        lines.append("| " + " | ".join(row) + " |")
        for c in codes + (["LAMMPS"] if lmp else []):
            if get(c):
                plot.setdefault(c, []).append((get(c)["elements"], 1e9 / get(c)["rate"]))
    if lmp:  # the same ratios from the medians of the reps: the best run favours whichever code met a fast moment
        lines += ["", "The same from the medians of the reps (M disk-steps/s; 1T / LAMMPS):", ""]
        for label, *_ in settle:
            get = lambda c: B.get(f"settle {label} {c}")
            lam = get("LAMMPS")
            if not lam:
                continue
            parts = [f"{c} {get(c)['median_rate'] / 1e6:.1f} ({get(c)['median_rate'] / lam['median_rate']:.2f})"
                     for c in codes if get(c) and c.endswith("1T")]
            lines.append(f"- {label} disks: LAMMPS {lam['median_rate'] / 1e6:.1f}; " + "; ".join(parts))
    lines.append("")
    lines.append("Slope of log(time per step) against log(disks), least squares over the sizes (1 = flat cost "
                 "per disk-step):")
    res["slopes"] = {}
    for c, pts in plot.items():
        s = slope(pts)
        res["slopes"][c] = s
        lines.append(f"- {c}: {s:.3f}" if s is not None else f"- {c}: -")
    pre = [k for k in B if k.startswith("pre ")]
    if pre:
        lines += ["", "| PRE lattice 100 x 100 | " + " | ".join(f"{bl} 1T [M element-steps/s]" for bl, _ in builds)
                  + " | " + " | ".join(f"{bl} cost / cost at N = 1" for bl, _ in builds) + " |",
                  "|---|" + "---|" * (2 * len(builds))]
        for n in range(1, 6):
            row = [f"N = {n}"]
            for bl, _ in builds:
                g = B.get(f"pre N{n} {bl} 1T")
                row.append(f"{g['rate'] / 1e6:.2f}" if g else "-")
            for bl, _ in builds:
                g, g1 = B.get(f"pre N{n} {bl} 1T"), B.get(f"pre N1 {bl} 1T")
                row.append(f"{g1['rate'] / g['rate']:.2f}" if g and g1 else "-")
            lines.append("| " + " | ".join(row) + " |")
    for k in sorted(k for k in B if k.startswith("shuffled ")):
        lines.append(f"\n10^4 settle, disks numbered at random ({k}): {B[k]['rate'] / 1e6:.2f} M disk-steps/s")
    silo = {k[len("silo 3e4 "):]: B[k] for k in B if k.startswith("silo ")}
    if silo:
        lines += ["", "| silo discharge, 3x10^4 disks | M disk-steps/s (disks at the start) | / LAMMPS | "
                  "peak memory [B/disk] | / LAMMPS memory | disks out | / LAMMPS, medians of the reps |",
                  "|---|---|---|---|---|---|---|"]
        lam = silo.get("LAMMPS")
        for code, g in silo.items():
            ratio = f"{g['rate0'] / lam['rate0']:.2f}" if lam else "-"
            mem = f"{g['memory'] / lam['memory']:.2f}" if lam else "-"
            med = f"{g['median_rate0'] / lam['median_rate0']:.2f}" if lam else "-"
            lines.append(f"| {code} | {g['rate0'] / 1e6:.2f} | {ratio} | {g['memory'] / g['elements0']:.0f} | {mem} | "
                         f"{g['discharged']} | {med} |")
    if alternated:
        res["alternated"] = alternated
        lines += ["", "Interleaved block by block in one process (`dem2d_alternate`, 50-step blocks; " + str(a.reps) +
                  " runs each): the speed ratio B / A of each pair of blocks; the median of the runs' medians, and the "
                  "ratio of the total times of each run, smallest and largest. Divisible step: the same for "
                  "`dem2d_divisible` (a step that divides perfectly, of as many elements and as long as the run's "
                  "one-thread step), run right after each 2-thread run.", "",
                  "| A | B | speed B / A, median | B / A of the totals, per run | cost B / A (median) | "
                  "divisible step, median | divisible step, totals per run |",
                  "|---|---|---|---|---|---|---|"]
        for r in alternated:
            med = statistics.median(x["median"] for x in r["runs"])
            tot = [x["of_totals"] for x in r["runs"]]
            cost = f"{1 / med:.3f}" if r["a"].startswith("PRE") else "-"
            c = r.get("divisible") or []
            cmed = f"{statistics.median(x['median'] for x in c):.3f}" if c else "-"
            ctot = f"{min(x['of_totals'] for x in c):.3f} … {max(x['of_totals'] for x in c):.3f}" if c else "-"
            lines.append(f"| {r['a']} | {r['b']} | {med:.3f} | {min(tot):.3f} … {max(tot):.3f} | {cost} | {cmed} | "
                         f"{ctot} |")
    table = "\n".join(lines) + "\n"
    (out / "table.md").write_text(table)
    json.dump(res, open(out / "results.json", "w"), indent=2)
    svg_plot(plot, out / "cost.svg")
    print(table)
    print(f"outputs: {out}/table.md, results.json, cost.svg")


if __name__ == "__main__":
    main()
