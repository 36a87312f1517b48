#!/usr/bin/env python3
"""Throughput of `dem2d sweep|study` serially and under mpiexec (docs/cluster.md, "Measured").

Runs every configuration once per round, the rounds interleaved (so that a change in the load of a
shared machine hits every configuration alike), each with --fresh; prints the wall time of each run, the
median per configuration, runs per second and the ratio to the first configuration. Finally a rerun of
the last configuration with everything in the cache: rank 0's own work per run (planning, cache
look-ups, analysis, writing), the part that does not shrink with more ranks.

  tests/mpi/throughput.py --dem2d build-mpi/app/dem2d --rounds 3 \
      --study tests/mpi/studies/mpi_sensitivity/sensitivity.toml --command sweep
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import time
from pathlib import Path


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dem2d", required=True)
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--command", default="sweep")
    ap.add_argument("--study", required=True)
    ap.add_argument("--work", default="build-mpi/throughput")
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    mpi = [a.mpiexec, "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    configs = [("serial, --jobs 1", [], 1), ("mpiexec -n 1, --jobs 1", mpi + ["-n", "1"], 1),
               ("mpiexec -n 2, --jobs 1", mpi + ["-n", "2"], 1), ("serial, --jobs 2", [], 2)]
    times = {name: [] for name, _, _ in configs}
    cpu = {name: [] for name, _, _ in configs}  # user + system CPU seconds of all processes of the run
    runs = None
    for r in range(a.rounds):
        for name, prefix, jobs in configs:
            out = Path(a.work) / name.replace(" ", "").replace(",", "_")
            cmd = prefix + [a.dem2d, a.command, a.study, "--out", str(out), "--jobs", str(jobs), "--fresh"]
            u0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            subprocess.run(cmd, stdout=subprocess.DEVNULL, check=True)
            dt = time.perf_counter() - t0
            u1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            times[name].append(dt)
            cpu[name].append(u1.ru_utime + u1.ru_stime - u0.ru_utime - u0.ru_stime)
            runs = json.loads((out / "result.json").read_text())["provenance"]["runs_run"]
            print(f"round {r + 1}: {name:<24} {dt:7.2f} s wall, {cpu[name][-1]:6.2f} s CPU", flush=True)
    base = statistics.median(times[configs[0][0]])
    print(f"\n{runs} runs per study\n| configuration | wall times [s] | median [s] | runs/s | ratio to serial --jobs 1 | CPU [s] (median) |")
    print("|---|---|---|---|---|---|")
    for name, _, _ in configs:
        m = statistics.median(times[name])
        print(f"| {name} | {', '.join(f'{t:.2f}' for t in times[name])} | {m:.2f} | {runs / m:.2f} | {base / m:.2f} | {statistics.median(cpu[name]):.2f} |")
    name, prefix, jobs = configs[2]
    out = Path(a.work) / name.replace(" ", "").replace(",", "_")
    t0 = time.perf_counter()
    subprocess.run(prefix + [a.dem2d, a.command, a.study, "--out", str(out), "--jobs", str(jobs)], stdout=subprocess.DEVNULL, check=True)
    dt = time.perf_counter() - t0
    print(f"\nrerun of '{name}' from the cache: {dt:.2f} s ({1000 * dt / runs:.1f} ms per run, MPI start-up included)")


if __name__ == "__main__":
    main()
