#!/usr/bin/env python3
"""The MPI tests (ctest -L mpi, built with -DDEM2D_MPI=ON; docs/cluster.md).

same:   runs a study (dem2d study) or a sensitivity study (dem2d sweep) serially and under
        `mpiexec -n P` for each P given, and asserts that every file the serial run wrote is there and
        identical byte for byte, except for the fields that record the machine and the time (provenance,
        wall times, element-steps per second), which are removed from JSON files before comparing; and
        that the cache holds the same runs with the same results.
resume: starts the study under `mpiexec -n 2`, kills mpiexec and every rank with SIGKILL once a
        quarter of the runs is in the cache (a job or a node killed hard), asserts that no result was
        written and that a cache entry is either complete or absent, reruns it and asserts that the
        finished runs were reused and that the output equals the serial run's.
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

VOLATILE = {"provenance", "wall_seconds", "cpu_seconds", "wall_time_s", "element_steps_per_second",
            "mean element-steps per second", "eps", "seconds_per_step",
            "threads", "timings"}  # the machine's side of a run: usable cores differ under mpiexec's core binding


def strip(j):
    if isinstance(j, dict):
        return {k: strip(v) for k, v in j.items() if k not in VOLATILE}
    if isinstance(j, list):
        return [strip(v) for v in j]
    return j


def files_of(d: Path):
    return sorted(p.relative_to(d) for p in d.rglob("*")
                  if p.is_file() and p.parts[len(d.parts)] != "cache" and p.name != "running.json")


def compare(serial: Path, other: Path, what: str):
    errors = []
    a, b = files_of(serial), files_of(other)
    if a != b:
        errors.append(f"{what}: file sets differ: only serial {sorted(set(a) - set(b))}, only {what} {sorted(set(b) - set(a))}")
    if not a:
        errors.append(f"{what}: the serial run wrote nothing")
    for rel in sorted(set(a) & set(b)):
        x, y = (serial / rel).read_bytes(), (other / rel).read_bytes()
        if rel.suffix == ".json":
            x, y = [json.dumps(strip(json.loads(t)), sort_keys=False).encode() for t in (x, y)]
        if x != y:
            errors.append(f"{what}: {rel} differs from the serial run's")
    # The cache: the same runs with the same results (entry names contain the run folder's path, which
    # differs between the two output folders, so the entries are compared by content).
    def entries(d):
        return sorted(json.dumps(strip({k: v for k, v in json.loads(p.read_text()).items() if k != "code"}), sort_keys=True)
                      for p in (d / "cache").glob("*.json"))
    ca, cb = entries(serial), entries(other)
    if ca != cb:
        errors.append(f"{what}: the cache holds other runs or results ({len(ca)} entries serial, {len(cb)})")
    return errors


def descendants(pid):
    """Every process below pid (from /proc)."""
    children = {}
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                ppid = int((d / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(d.name))
    out, todo = [], [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            out.append(c)
            todo.append(c)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dem2d", required=True)
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--command", choices=["study", "sweep"], required=True)
    ap.add_argument("--study", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--ranks", type=int, nargs="*", default=[1, 2, 3])
    ap.add_argument("--resume", action="store_true")
    a = ap.parse_args()
    work = Path(a.work)
    mpi = [a.mpiexec, "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])

    def dem2d(out, jobs, extra=()):
        return [a.dem2d, a.command, a.study, "--out", str(out), "--jobs", str(jobs), *extra]

    if work.exists():  # nothing of an earlier test run may count
        shutil.rmtree(work)
    serial = work / "serial"
    t0 = time.time()
    subprocess.run(dem2d(serial, 2, ["--fresh"]), check=False, stdout=subprocess.DEVNULL)
    if not (serial / "result.json").exists():
        sys.exit("the serial run wrote no result.json")
    print(f"serial: {time.time() - t0:.1f} s")
    errors = []
    if not a.resume:
        for p in a.ranks:
            out = work / f"mpi{p}"
            t0 = time.time()
            r = subprocess.run(mpi + ["-n", str(p)] + dem2d(out, 1, ["--fresh"]), stdout=subprocess.DEVNULL)
            print(f"mpiexec -n {p}: {time.time() - t0:.1f} s, exit {r.returncode}")
            errors += compare(serial, out, f"mpiexec -n {p}")
    else:
        out = work / "resume"
        total = json.loads((serial / "result.json").read_text())["provenance"]["runs_run"]
        proc = subprocess.Popen(mpi + ["-n", "2"] + dem2d(out, 1, ["--fresh"]), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        cache = out / "cache"
        deadline = time.time() + 300
        while time.time() < deadline and proc.poll() is None:
            if cache.is_dir() and len(list(cache.glob("*.json"))) >= max(2, total // 4):
                break
            time.sleep(0.05)
        if proc.poll() is not None:
            sys.exit(f"the job ended (exit {proc.returncode}) before it could be killed: make the study longer")
        # SIGKILL to every rank and mpiexec (a node or the job killed hard): nothing can finish
        # or clean up after this point; only what was already in the cache may remain.
        for pid in descendants(proc.pid) + [proc.pid]:  # the ranks are not in mpiexec's process group
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        proc.wait(timeout=120)
        kept = len(list(cache.glob("*.json")))
        time.sleep(1.0)
        if len(list(cache.glob("*.json"))) != kept:
            errors.append("a rank outlived the kill (the cache still grows)")
        print(f"killed (exit {proc.returncode}) with {kept} of {total} runs in the cache")
        if (out / "result.json").exists():
            errors.append("the killed job wrote result.json")
        if proc.returncode == 0:
            errors.append("the killed job exited 0")
        if kept >= total:
            errors.append("every run was cached before the kill: make the study longer")
        for e in cache.glob("*.json"):  # atomic writes: no torn entry
            try:
                json.loads(e.read_text())
            except ValueError:
                errors.append(f"a torn cache entry: {e.name}")
        r = subprocess.run(mpi + ["-n", "2"] + dem2d(out, 1), stdout=subprocess.DEVNULL)
        res = json.loads((out / "result.json").read_text()) if (out / "result.json").exists() else {}
        prov = res.get("provenance", {})
        print(f"rerun: exit {r.returncode}, runs reused {prov.get('runs_reused')}, run {prov.get('runs_run')}")
        if prov.get("runs_reused", 0) < kept or prov.get("runs_reused", 0) + prov.get("runs_run", 0) != total:
            errors.append(f"the rerun did not continue: reused {prov.get('runs_reused')}, run {prov.get('runs_run')}, "
                          f"{kept} were cached, {total} in all")
        errors += compare(serial, out, "killed and resumed")
    for e in errors:
        print("FAIL:", e)
    sys.exit(1 if errors else 0)


if __name__ == "__main__":
    main()
