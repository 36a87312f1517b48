#!/usr/bin/env python3
"""Locality benchmark (bench/journal.md, "Locality"): the settle case with its disks numbered in row order
and at random (make_settle_case.py --shuffle), run with spatial reordering off and on
(numerics.reorder_every), all runs interleaved, the best of --reps counting. Prints a table of speeds
(disk-steps/s of the time loop, from summary.json), the load average before and after, and the final
packing statistics of each variant (contacts, kinetic energy) to compare results with and without
reordering.

    python3 bench/locality.py --dem2d build/app/dem2d --sizes 100x100x2000 200x500x1000 --reps 3
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dem2d", default=str(ROOT / "build/app/dem2d"))
    ap.add_argument("--sizes", nargs="+", default=["100x100x2000", "200x500x1000"], help="ROWSxCOLSxSTEPS")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--every", type=int, default=10, help="reorder_every of the 'on' runs")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    out = Path(a.out or tempfile.mkdtemp(prefix="dem2d_locality_"))
    out.mkdir(parents=True, exist_ok=True)
    load0 = os.getloadavg()
    variants = [("rows", False, 0), ("rows", False, a.every), ("shuffled", True, 0), ("shuffled", True, a.every)]
    results = {}
    for size in a.sizes:
        rows, cols, steps = size.split("x")
        cases = {}
        for order, shuffle in (("rows", False), ("shuffled", True)):
            case = out / f"settle_{rows}x{cols}_{order}.toml"
            cmd = [sys.executable, str(ROOT / "bench/make_settle_case.py"), rows, cols, steps] + (["--shuffle"] if shuffle else [])
            case.write_text(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
            cases[order] = case
        for rep in range(a.reps):
            for order, _, every in variants:
                run_dir = out / f"{size}_{order}_r{every}_{rep}"
                subprocess.run([a.dem2d, "run", str(cases[order]), "--quiet", "--out", str(run_dir), "--set",
                                f"numerics.reorder_every={every}"], check=True)
                s = json.loads((run_dir / "summary.json").read_text())
                rate = s["element_steps_per_second"]
                key = (size, order, every)
                r = results.setdefault(key, {"rates": [], "final": None})
                r["rates"].append(rate)
                rows_csv = [l for l in (run_dir / "series.csv").read_text().splitlines() if l and not l.startswith("#")]
                r["final"] = rows_csv[-1]
                print(f"{size} {order:8s} reorder_every={every:3d} rep {rep}: {rate:.3e} disk-steps/s "
                      f"(load {os.getloadavg()[0]:.1f})", flush=True)
    load1 = os.getloadavg()
    print(f"\nload average (1, 5, 15 min) before: {load0[0]:.1f} {load0[1]:.1f} {load0[2]:.1f}; "
          f"after: {load1[0]:.1f} {load1[1]:.1f} {load1[2]:.1f}")
    print("\n| disks x steps | numbering | reorder_every | best [disk-steps/s] | all runs | final row (t, contacts, E_kin) |")
    print("|---|---|---|---|---|---|")
    for (size, order, every), r in results.items():
        rows, cols, steps = (int(v) for v in size.split("x"))
        print(f"| {rows * cols} x {steps} | {order} | {every} | {max(r['rates']):.3e} | "
              f"{' '.join(f'{x:.2e}' for x in r['rates'])} | {r['final']} |")
    (out / "locality.json").write_text(json.dumps({f"{k[0]} {k[1]} {k[2]}": v for k, v in results.items()}, indent=1))
    print(f"\n{out / 'locality.json'}")


if __name__ == "__main__":
    main()
