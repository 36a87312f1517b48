#!/usr/bin/env python3
"""The guard's limits pinned as check values in verification/beam_stability/study.toml are the ones
`dem2d check` prints now, for each variant's overrides: a change of the guard (docs/model.md G1-G7)
that leaves the study's pinned values stale fails here.

Usage: check_guard_values.py DEM2D STUDY_TOML [--scale S]   (--scale: plant a stale value, expect failure)
"""
import re
import subprocess
import sys
import tomllib
from pathlib import Path


def printed_limit(dem2d, case, overrides):
    cmd = [dem2d, "check", str(case)]
    for o in overrides:
        cmd += ["--set", o]
    out = subprocess.run(cmd, capture_output=True, text=True)
    text = out.stdout + out.stderr
    m = re.search(r"stability limit:? ([0-9.e+-]+) s", text)
    if not m:
        sys.exit(f"no stability limit in the output of {' '.join(cmd)}:\n{text}")
    return float(m.group(1))


def main():
    dem2d, study = sys.argv[1], Path(sys.argv[2])
    scale = float(sys.argv[4]) if len(sys.argv) > 4 and sys.argv[3] == "--scale" else 1.0
    s = tomllib.loads(study.read_text())
    case = (study.parent / s["study"]["case"]).resolve()
    variants = {v["label"]: v["set"] for v in s["variant"]}
    failures, n = [], 0
    for c in s["check"]:
        m = re.search(r"(above|below (?P<k>[0-9.]+) ×) the guard's limit", c["label"])
        if not m:
            continue
        (label,) = c["variants"]
        guard = printed_limit(dem2d, case, variants[label])
        factor = float(m.group("k")) if m.group("k") else 1.0
        pinned = c["value"] * scale
        n += 1
        if abs(pinned - factor * guard) > 5e-6 * factor * guard:
            failures.append(f"{label}: pinned {pinned:g} s, dem2d check gives {factor:g} × {guard:g} s")
    if n == 0:
        sys.exit("no guard check found in " + str(study))
    if failures:
        sys.exit("stale guard values in {}:\n  {}".format(study, "\n  ".join(failures)))
    print(f"{n} pinned guard values equal dem2d check's")


if __name__ == "__main__":
    main()
