#!/usr/bin/env python3
"""Speed against core count (bench/README.md, "Sixteen cores"): dem2d on 1, 2, 4, ... threads beside LAMMPS on
as many MPI ranks bound to cores, the same cases in one run, with where dem2d's step time goes per thread
count (`dem2d run --timings`), the silo discharge on 1 and on the most threads, and the oversubscription
benchmark (two busy processes on two cores beside dem2d). Not part of ctest: speed is measured here.

    python3 bench/scaling.py [--threads 1,2,4,8,16] [--sizes 1e5,1e6] [--steps 1e5=2000,1e6=500]
                             [--dem2d LABEL=PATH ...] [--lmp lmp] [--mpirun mpirun] [--no-lammps]
                             [--silo STEPS] [--oversubscribe STEPS] [--reps N] [--out DIR]

Every dem2d run is `--fixed-threads` (exactly the threads asked for) except the ones labelled "governed".
A dem2d without --timings or --fixed-threads (an older build) is run without them. The rates are disk-steps
per second of the time loop (dem2d: summary.json; LAMMPS: its Loop time); the best of --reps runs counts.
Writes DIR/results.json and DIR/table.md (with the machine) and prints the table.
On a machine without Debian packages: bench/portable/pack.sh here, bench/portable/run.sh there.
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

from machine import cpu_model
from suite import LOOP  # LAMMPS' "Loop time of …" line

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT / "bench"
SETTLE = {"1e4": (50, 200), "1e5": (200, 500), "1e6": (500, 2000)}  # rows, cols (make_settle_case.py)


def sh(cmd, **kw):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed ({r.returncode}):\n{r.stdout[-3000:]}")
    return r.stdout


def options(binary):
    h = subprocess.run([binary, "run", "--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    return {o for o in ("--threads", "--fixed-threads", "--timings") if o in h}


def run_dem2d(binary, opts, case, out, threads, governed=False, prefix=(), env=None):
    cmd = list(prefix) + [binary, "run", str(case), "--out", str(out), "-q"]
    if "--threads" in opts:
        cmd += ["--threads", str(threads)]
    elif threads != 1:
        return None
    if not governed and "--fixed-threads" in opts:
        cmd.append("--fixed-threads")
    if "--timings" in opts:
        cmd.append("--timings")
    sh(cmd, env=env)
    s = json.load(open(Path(out) / "summary.json"))
    n0 = s["resolved_case"]["elements"]["count"]
    r = {"rate": n0 * s["steps"] / s["wall_seconds"], "wall": s["wall_seconds"], "cpu": s["cpu_seconds"],
         "steps": s["steps"], "elements": n0, "threads": s.get("threads"), "timings": s.get("timings")}
    if "discharge" in s:
        r["discharged"] = s["discharge"].get("discharged")
    return r


def run_lammps(a, folder, ranks, tag, script):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    log = f"log.{tag}"
    sh([a.mpirun, "-np", str(ranks), "--bind-to", "core", a.lmp, "-in", script, "-log", log, "-screen", "none",
        "-nocite"], cwd=folder, env=env)
    loops = LOOP.findall((Path(folder) / log).read_text())
    secs, steps = sum(float(m[0]) for m in loops), sum(int(m[2]) for m in loops)
    atoms0 = int(loops[0][3])
    return {"rate": steps * atoms0 / secs, "wall": secs, "steps": steps, "elements": atoms0, "ranks": ranks}


def best(runs):
    runs = [r for r in runs if r]
    return max(runs, key=lambda r: r["rate"]) if runs else None


def phase_line(t):
    """One run's timings as shares of its step wall time: thread 0's phases, the mean wait of the threads."""
    if not t:
        return ""
    wall = t["step_wall"]
    th = t["per_thread"]
    n = len(th)
    mean = lambda k: sum(x[k] for x in th) / n
    return (f"sweep {th[0]['sweep'] / wall:.0%} · integrate {th[0]['integrate'] / wall:.0%} · rebuild "
            f"{th[0]['rebuild'] / wall:.0%} (cells {t['rebuild_cells'] / wall:.1%}) · gather {th[0]['gather'] / wall:.1%} · "
            f"serial {t['step_serial'] / wall:.1%} · wait mean {mean('wait') / wall:.0%} · wake mean "
            f"{mean('wake') / wall:.1%} · sleeps {sum(x['sleeps'] for x in th) / max(1, t['steps']):.2f}/step")


def busy_loops(cpus):
    """Busy processes, one pinned to each of cpus (what another user's work looks like to dem2d)."""
    return [subprocess.Popen(["taskset", "-c", str(c), sys.executable, "-c", "while True: pass"]) for c in cpus]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--threads", default="1,2,4,8,16")
    ap.add_argument("--ranks", default=None, help="LAMMPS ranks (default: the thread counts)")
    ap.add_argument("--sizes", default="1e5,1e6")
    ap.add_argument("--steps", default="1e4=4000,1e5=2000,1e6=500")
    ap.add_argument("--dem2d", action="append", default=[])
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--no-lammps", action="store_true")
    ap.add_argument("--silo", type=int, default=0, help="steps of the 3x10^4 silo discharge (0: none)")
    ap.add_argument("--oversubscribe", type=int, default=0, help="steps of the 10^5 settle beside busy loops (0: none)")
    ap.add_argument("--reps", type=int, default=1)
    ap.add_argument("--cores", action="append", default=[], help="SIZE=LIST: other thread and rank counts for a size")
    ap.add_argument("--size-reps", action="append", default=[], help="SIZE=N: other --reps for a size")
    ap.add_argument("--codes", action="append", default=[], help="SIZE=LABEL,LABEL: only these dem2d builds for a size")
    ap.add_argument("--spin-us", default="", help="also run the most threads with DEM2D_SPIN_US = each of these")
    ap.add_argument("--out", type=Path, default=Path("/tmp/dem2d_scaling"))
    ap.add_argument("--results", type=Path, default=None, help="also keep results.json and table.md here (updated as it goes)")
    a = ap.parse_args()
    out = a.out
    out.mkdir(parents=True, exist_ok=True)
    threads = [int(t) for t in a.threads.split(",")]
    ranks = [int(t) for t in (a.ranks or a.threads).split(",")]
    steps = dict(kv.split("=") for kv in a.steps.split(","))
    codes = [tuple(d.split("=", 1)) for d in a.dem2d] or [("dem2d", str(ROOT / "build/app/dem2d"))]
    opts = {label: options(path) for label, path in codes}
    results = {"machine": {"cpu": cpu_model(), "cores": os.cpu_count(), "usable": len(os.sched_getaffinity(0)),
                           "kernel": platform.release(), "python": platform.python_version()},
               "started": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "codes": dict(codes),
               "settle": {}, "silo": None, "oversubscribed": None}
    t_start = time.time()

    def save():
        for d in filter(None, (out, a.results)):
            d.mkdir(parents=True, exist_ok=True)
            (d / "results.json").write_text(json.dumps(results, indent=1))
            (d / "table.md").write_text(make_table(results))

    def attempt(what, fn):
        try:
            return fn()
        except (RuntimeError, OSError, KeyError, ValueError) as e:
            print(f"{what} failed: {e}", file=sys.stderr)
            return None

    size_cores = dict(kv.split("=", 1) for kv in a.cores)
    size_reps = {k: int(v) for k, v in (kv.split("=", 1) for kv in a.size_reps)}
    size_codes = {k: v.split(",") for k, v in (kv.split("=", 1) for kv in a.codes)}
    all_threads, all_ranks, all_codes = threads, ranks, codes
    for size in a.sizes.split(","):
        threads = [int(t) for t in size_cores[size].split(",")] if size in size_cores else all_threads
        ranks = threads if size in size_cores else all_ranks
        codes = [c for c in all_codes if c[0] in size_codes[size]] if size in size_codes else all_codes
        reps = size_reps.get(size, a.reps)
        rows, cols = SETTLE[size]
        st = int(steps[size])
        case = out / f"settle_{size}.toml"
        case.write_text(sh([sys.executable, str(BENCH / "make_settle_case.py"), str(rows), str(cols), str(st)]))
        lfolder = out / f"lammps_{size}"
        if not a.no_lammps:
            sh([sys.executable, str(BENCH / "lammps_input.py"), str(case), str(lfolder)])
        entry = results["settle"][size] = {"steps": st, "elements": rows * cols, "dem2d": {}, "lammps": {}}
        for t in sorted(set(threads) | set(ranks)):
            for label, path in codes:
                if t in threads:
                    runs = [attempt(f"{label} on {t} threads", lambda: run_dem2d(path, opts[label], case, out / f"run_{size}_{label}_{t}", t))
                            for _ in range(reps)]
                    entry["dem2d"].setdefault(label, {})[t] = best(runs)
            if not a.no_lammps and t in ranks:
                try:
                    entry["lammps"][t] = best([run_lammps(a, lfolder, t, f"{t}.{k}", "in.settle") for k in range(reps)])
                except RuntimeError as e:
                    entry["lammps"][t] = None
                    print(f"LAMMPS on {t} ranks failed: {e}", file=sys.stderr)
            print(f"[{time.time() - t_start:.0f} s] settle {size}, {t} cores done", file=sys.stderr, flush=True)
            save()
        most = max(threads)
        label, path = codes[0]
        if "--fixed-threads" in opts[label]:
            entry["governed"] = attempt("governed", lambda: run_dem2d(path, opts[label], case, out / f"run_{size}_governed", most,
                                                                      governed=True))
        for us in filter(None, a.spin_us.split(",")):
            env = dict(os.environ, DEM2D_SPIN_US=us)
            entry.setdefault("spin", {})[us] = attempt(f"spin {us}", lambda: run_dem2d(
                path, opts[label], case, out / f"run_{size}_spin{us}", most, env=env))
        save()

    threads, codes = all_threads, all_codes
    for name, wanted, part in (("silo", a.silo, lambda: silo(a, codes, opts, threads, out, results)),
                               ("oversubscription", a.oversubscribe, lambda: oversubscribed(a, codes, opts, out, results, save))):
        if wanted:
            attempt(name, part)
            print(f"[{time.time() - t_start:.0f} s] {name} done", file=sys.stderr, flush=True)
            save()
    results["seconds"] = time.time() - t_start
    save()
    table = make_table(results)
    (out / "table.md").write_text(table)
    print(table)


def silo(a, codes, opts, threads, out, results):
    """The silo discharge of 3x10^4 disks (bench/make_silo_case.py) on 1 and on the most threads."""
    case = out / "silo.toml"
    case.write_text(sh([sys.executable, str(BENCH / "make_silo_case.py"), "150", "200", str(a.silo)]))
    most = max(threads)
    results["silo"] = {"steps": a.silo, "dem2d": {
        label: {t: run_dem2d(path, opts[label], case, out / f"silo_{label}_{t}", t) for t in (1, most)}
        for label, path in codes}}


def oversubscribed(a, codes, opts, out, results, save):
    """The 10^5 settle pinned to cpus 0 and 1 beside two busy loops pinned there too: 1 thread, 2 threads
    (governed) and 2 threads fixed; an older build runs 1 and 2 threads as it can."""
    rows, cols = SETTLE["1e5"]
    case = out / "settle_oversub.toml"
    case.write_text(sh([sys.executable, str(BENCH / "make_settle_case.py"), str(rows), str(cols), str(a.oversubscribe)]))
    pin = ["taskset", "-c", "0,1"]
    over = results["oversubscribed"] = {"steps": a.oversubscribe, "cpus": "0,1", "busy_loops": 2, "runs": {}}
    loops = busy_loops([0, 1])
    try:
        time.sleep(0.5)
        for label, path in codes:
            for name, t, gov in (("1 thread", 1, False), ("2 threads", 2, True), ("2 threads fixed", 2, False)):
                if gov and "--fixed-threads" not in opts[label]:
                    continue
                over["runs"][f"{label}, {name}"] = run_dem2d(path, opts[label], case, out / f"over_{label}_{t}_{gov}", t,
                                                             governed=gov, prefix=pin)
                save()
    finally:
        for p in loops:
            p.kill()


def make_table(r):
    m = r["machine"]
    lines = [f"Machine: {m['cpu']}, {m['cores']} cores ({m['usable']} usable), kernel {m['kernel']}; started "
             f"{r['started']}; {r.get('seconds', 0):.0f} s.", ""]
    for size, e in r["settle"].items():
        lines += [f"### settle {size} × {e['steps']} steps (M disk-steps/s)", "",
                  "| cores | " + " | ".join(e["dem2d"]) + " | LAMMPS | ratio | speed-up " + " / ".join(e["dem2d"]) + " / LAMMPS |",
                  "|---" * (len(e["dem2d"]) + 4) + "|"]
        cores = sorted({int(t) for d in e["dem2d"].values() for t in d} | {int(t) for t in e["lammps"]})
        first = next(iter(e["dem2d"]))

        def rate(d, t):
            x = d.get(t) or d.get(str(t))
            return x["rate"] if x else None

        for t in cores:
            rates = [rate(d, t) for d in e["dem2d"].values()]
            lr = rate(e["lammps"], t)
            ratio = f"{rates[0] / lr:.2f}×" if rates[0] and lr else "—"
            ups = [f"{x / rate(d, 1):.2f}" if x and rate(d, 1) else "—" for x, d in zip(rates, e["dem2d"].values())]
            ups.append(f"{lr / rate(e['lammps'], 1):.2f}" if lr and rate(e["lammps"], 1) else "—")
            cells = [f"{x / 1e6:.1f}" if x else "—" for x in rates] + [f"{lr / 1e6:.1f}" if lr else "—", ratio, " / ".join(ups)]
            lines.append(f"| {t} | " + " | ".join(cells) + " |")
        if e.get("governed"):
            g = e["governed"]
            lines.append(f"\n{first}, governed on the most threads: {g['rate'] / 1e6:.1f} (threads: {g['threads']})")
        for us, x in (e.get("spin") or {}).items():
            if x:
                lines.append(f"- spin {us} µs before sleeping: {x['rate'] / 1e6:.1f}; {phase_line(x.get('timings'))}")
        lines += ["", f"Where {first}'s step time goes (thread 0's phases, mean waits of the threads):", ""]
        for t in cores:
            x = e["dem2d"][first].get(t) or e["dem2d"][first].get(str(t))
            if x and x.get("timings"):
                lines.append(f"- {t} threads: {phase_line(x['timings'])}; CPU {x['cpu']:.2f} s for wall {x['wall']:.2f} s")
        lines.append("")
    if r.get("silo"):
        s = r["silo"]
        lines.append(f"### silo 3×10^4 × {s['steps']} steps")
        for label, d in s["dem2d"].items():
            ts = sorted(d, key=int)
            if d.get(ts[0]) and d.get(ts[-1]):
                lines.append(f"- {label}: 1 thread {d[ts[0]]['rate'] / 1e6:.2f}, {ts[-1]} threads {d[ts[-1]]['rate'] / 1e6:.2f} "
                             f"M disk-steps/s: {d[ts[-1]]['rate'] / d[ts[0]]['rate']:.2f}×")
        lines.append("")
    if r.get("oversubscribed"):
        o = r["oversubscribed"]
        lines.append(f"### 10^5 settle × {o['steps']} steps on cpus {o['cpus']} beside {o['busy_loops']} busy loops")
        for name, x in o["runs"].items():
            if x:
                lines.append(f"- {name}: {x['wall']:.2f} s ({x['rate'] / 1e6:.2f} M disk-steps/s; threads {x['threads']})")
        lines.append("")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
