#!/usr/bin/env python3
"""Progress of `dem2d study` and `dem2d sweep` (verification/engine/progress.hpp): under a pseudo-terminal
one status line (runs done / total, reused, elapsed, time left, slowest run); with -v a line per
finished run, on a terminal or not; nothing extra when stderr is not a terminal.
Usage: check_progress.py DEM2D_EXECUTABLE SOURCE_DIR."""
import os
import pty
import re
import subprocess
import sys
import tempfile

exe, src = sys.argv[1], sys.argv[2]
fails = []


def under_pty(args):
    """Runs dem2d with stdout and stderr on a pseudo-terminal; returns (exit status, all it printed)."""
    leader, follower = pty.openpty()
    p = subprocess.Popen([exe, *args], cwd=src, stdin=subprocess.DEVNULL, stdout=follower, stderr=follower)
    os.close(follower)
    chunks = []
    while True:
        try:
            data = os.read(leader, 65536)
        except OSError:  # the follower side closed: the program ended
            break
        if not data:
            break
        chunks.append(data)
    os.close(leader)
    return p.wait(), b"".join(chunks).decode("utf-8", "replace")


with tempfile.TemporaryDirectory() as tmp:
    study = ["study", "verification/free_fall/study.toml", "--out", os.path.join(tmp, "ff"), "--jobs", "1"]
    rc, text = under_pty(study + ["--fresh"])
    line = re.compile(r"study free_fall: 4/4 runs \(0 reused\), \d+:\d\d elapsed, slowest [0-9.e+-]+ s")
    if rc != 0 or not line.search(text) or "~" not in text:
        fails.append(f"study on a terminal: exit {rc}, no status line with time left in {text[:600]!r}")
    rc, text = under_pty(study)
    if rc != 0 or "study free_fall: 4/4 runs (4 reused)" not in text:
        fails.append(f"study again (cached): exit {rc}, no '4/4 runs (4 reused)' in {text[:400]!r}")
    piped = subprocess.run([exe, *study, "--fresh"], cwd=src, capture_output=True, text=True)
    if piped.returncode != 0 or "runs (" in piped.stderr or "runs (" in piped.stdout:
        fails.append(f"study not on a terminal: exit {piped.returncode}, progress printed: {piped.stderr[:300]!r}")
    verbose = subprocess.run([exe, *study, "--fresh", "-v"], cwd=src, capture_output=True, text=True)
    runs = re.findall(r"^run (\d)/4: completed in [0-9.e+-]+ s: ", verbose.stderr, re.M)
    if verbose.returncode != 0 or sorted(runs) != ["1", "2", "3", "4"]:
        fails.append(f"study -v: exit {verbose.returncode}, expected 4 run lines, got {verbose.stderr[:400]!r}")
    sweep_file = os.path.join(tmp, "sweep", "sensitivity.toml")
    os.makedirs(os.path.dirname(sweep_file))
    with open(sweep_file, "w") as f:
        f.write(f'[sensitivity]\ntitle = "progress"\ncase = "{src}/cases/basic/rest_on_wall.toml"\n'
                'outputs = ["overlap"]\nmethods = ["oat"]\n[[parameter]]\npath = "contact.0.kn"\n'
                'low = "5e5 N/m"\nhigh = "4e6 N/m"\n[oat]\npoints = 3\n')
    rc, text = under_pty(["sweep", sweep_file, "--out", os.path.join(tmp, "sweep_out"), "--jobs", "1"])
    if rc != 0 or "sweep sweep: 4/4 runs (0 reused)" not in text:
        fails.append(f"sweep on a terminal: exit {rc}, no status line in {text[:400]!r}")

if fails:
    sys.exit("FAIL:\n  " + "\n  ".join(fails))
print("OK: progress on a terminal, with -v, and silent in a pipe")
