#!/usr/bin/env python3
"""dem2d run --threads against the cores the process may use (lib/dem/core/usable_cores.hpp): bound to one cpu
(taskset), --threads 4 and --threads auto run on one thread, say so in summary.json "threads" and give the
one-thread series bit for bit; --timings writes "timings" whose phases fit in the steps' wall time;
--fixed-threads makes no governor probe.

    check_threads.py DEM2D SOURCE_DIR
"""
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

dem2d, root = sys.argv[1], Path(sys.argv[2])
case = root / "cases/bench/settle_10k.toml"
short = ["--set", "numerics.duration=8e-4 s", "--set", "output.every=50"]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def run(out, *args, cpus=None):
    cmd = ([shutil.which("taskset"), "-c", cpus] if cpus else []) + [dem2d, "run", str(case), "--out", str(out), *short, *args]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{r.stdout}")
    return json.loads((out / "summary.json").read_text()), (out / "series.csv").read_text().split("\n", 1)[1], r.stdout


with tempfile.TemporaryDirectory() as tmp:
    tmp = Path(tmp)
    one, series1, _ = run(tmp / "one", "-q", "--threads", "1")
    check(one["threads"] == {"asked": 1, "used": 1, "usable_cores": one["threads"]["usable_cores"], "governor_probes": 0,
                             "steps_on_fewer_threads": 0}, f"one thread: {one['threads']}")
    if shutil.which("taskset"):
        four, series4, said = run(tmp / "four", "--threads", "4", cpus="0")
        t = four["threads"]
        check(t["usable_cores"] == 1 and t["used"] == 1 and t["asked"] == 4, f"--threads 4 on one cpu runs 1: {t}")
        check("may use 1 cores" in said and "running on 1" in said, "--threads 4 on one cpu says so on the terminal")
        check(series4 == series1, "--threads 4 on one cpu: the one-thread series")
        auto, _, _ = run(tmp / "auto", "-q", "--threads", "auto", cpus="0")
        check(auto["threads"]["used"] == 1 and auto["threads"]["asked"] == 1, f"--threads auto on one cpu: {auto['threads']}")
        two, series2, _ = run(tmp / "two", "-q", "--threads", "2", "--fixed-threads", "--timings", cpus="0,1")
        if two["threads"]["usable_cores"] >= 2:
            check(two["threads"]["used"] == 2 and two["threads"]["governor_probes"] == 0,
                  f"--fixed-threads: two threads, no probe: {two['threads']}")
            check(series2 == series1, "two threads: the one-thread series")
            check(len(two["timings"]["per_thread"]) == 2, "--timings on two threads: two threads' phases")
    else:
        print("(no taskset: the bound runs are not checked)")
    timed, _, _ = run(tmp / "timed", "-q", "--threads", "1", "--timings")
    tm = timed["timings"]
    th = tm["per_thread"][0]
    phases = th["rebuild"] + th["sweep"] + th["integrate"] + th["gather"]
    check(tm["steps"] == timed["steps"] and tm["step_wall"] > 0, f"--timings: {tm['steps']} steps, {tm['step_wall']:.4f} s")
    check(0.5 * tm["step_wall"] < phases <= tm["step_wall"] * 1.0001,
          f"--timings on one thread: the phases ({phases:.4f} s) fill most of the steps' wall time ({tm['step_wall']:.4f} s)")
    check("timings" not in one, "no --timings: no timings")

if failures:
    sys.exit(f"{len(failures)} failure(s)")
