#!/usr/bin/env python3
"""`dem2d --version` and `dem2d check` (issue 12): the version line names the code version, build type and
compiler; check prints every resolved default (integrator, velocity start, per contact law the
increments, segment positions, end rule, onset), the total mass and what limits the time step, in
words; a wrong case fails with exit status 2. Usage: check_cli.py DEM2D_EXECUTABLE SOURCE_DIR."""
import re
import subprocess
import sys

exe, src = sys.argv[1], sys.argv[2]
fails = []


def run(*args):
    return subprocess.run([exe, *args], cwd=src, capture_output=True, text=True)


v = run("--version")
if v.returncode != 0 or not re.fullmatch(r"dem2d \S+ \(\S+ build, (g\+\+|clang\+\+) [0-9][^)]*\)\n", v.stdout):
    fails.append(f"--version: exit {v.returncode}, printed {v.stdout!r}")

want = {
    "cases/impact/disk_wall.toml": [
        r"integrator K18 \(du = v dt, K18\), velocity start plain",
        r"total mass [0-9.e+-]+ kg",
        r"contact \S+: linear law, kn = [0-9.e+-]+ N/m, .*end rule elastic \(opens when e_n < 0, K8\), onset increment",
        r"probe e: restitution \[1\]",
        r"probe tc: contact_duration \[s\]",
        r"what limits it: the fastest mode of element 0 \(a disk .* pressed by 0 element and 1 wall contact",
        r"K18 \(symplectic Euler\) loses stability",
    ],
    "cases/pre/block_on_slope.toml": [
        r"contact \S+: face law, [0-9] segment\(s\) at the (segment centres \(M13.1\)|face ends \(M13.2\)), "
        r"normal increment (exact|linearised), tangential increment (exact|literal|linearised|hisatake), onset (increment|overlap)",
        r"what limits it: .*PRE",
    ],
}
for case, patterns in want.items():
    r = run("check", case)
    if r.returncode != 0:
        fails.append(f"check {case}: exit {r.returncode}: {r.stderr}")
        continue
    for p in patterns:
        if not re.search(p, r.stdout):
            fails.append(f"check {case}: no line matches {p!r}")

bad = run("check", "cases/impact/disk_wall.toml", "--set", "numerics.integrator=K20")
if bad.returncode != 2 or "numerics.integrator" not in bad.stderr:
    fails.append(f"check with integrator K20: exit {bad.returncode}, stderr {bad.stderr!r} (expected 2 naming the key)")

# --threads: a number or auto (the machine's cores); anything else is refused before the run, naming the option
import os
import tempfile
with tempfile.TemporaryDirectory() as tmp:
    ok = run("run", "cases/impact/disk_wall.toml", "-q", "--threads", "auto", "--out", os.path.join(tmp, "auto"))
    if ok.returncode != 0:
        fails.append(f"run --threads auto: exit {ok.returncode}, stderr {ok.stderr!r}")
    for value in ("0", "zero", "-2"):
        r = run("run", "cases/impact/disk_wall.toml", "-q", "--threads", value, "--out", os.path.join(tmp, value))
        if r.returncode == 0 or "--threads" not in r.stderr or os.path.exists(os.path.join(tmp, value)):
            fails.append(f"run --threads {value}: exit {r.returncode}, stderr {r.stderr!r} (expected a refusal naming "
                         f"--threads, no output folder)")

# `dem2d run` prints each probe with its SI unit (a restitution coefficient is a pure number).
import tempfile as _tf
with _tf.TemporaryDirectory() as tmp:
    r = run("run", "cases/impact/disk_wall.toml", "--out", tmp + "/o")
    if r.returncode != 0 or not re.search(r"^  tc = [0-9.e+-]+ s$", r.stdout, re.M) or not re.search(r"^  e = [0-9.e+-]+$", r.stdout, re.M):
        fails.append(f"run: probes without their units in {r.stdout!r}")

# The command line's own mistakes: an unknown subcommand is named with the nearest one; every usage
# error is exit 2 (the exit statuses are listed in --help).
typo = run("rnu", "cases/impact/disk_wall.toml")
if typo.returncode != 2 or "unknown subcommand 'rnu'; did you mean 'run'?" not in typo.stderr:
    fails.append(f"dem2d rnu: exit {typo.returncode}, stderr {typo.stderr!r} (expected 2 and \"did you mean 'run'?\")")
far = run("frobnicate")
if far.returncode != 2 or "unknown subcommand 'frobnicate'" not in far.stderr or "did you mean" in far.stderr:
    fails.append(f"dem2d frobnicate: exit {far.returncode}, stderr {far.stderr!r} (expected 2, no suggestion)")
for args in (("run",), ("run", "no/such/case.toml"), ("check", "cases/impact/disk_wall.toml", "--bogus"), ()):
    r = run(*args)
    if r.returncode != 2:
        fails.append(f"dem2d {' '.join(args)}: exit {r.returncode} (expected 2 for a command-line mistake)")
h = run("--help")
if h.returncode != 0 or "Exit status: 0 done" not in h.stdout or "3 a run blew up" not in h.stdout:
    fails.append(f"--help: exit {h.returncode}, no exit statuses in {h.stdout[-300:]!r}")
hs = run("study", "--help")
if hs.returncode != 0 or "Exit status:" not in hs.stdout:
    fails.append(f"study --help: exit {hs.returncode}, no exit statuses")

# Ctrl-C during a long `dem2d check` ends it at once (check writes nothing: SIGINT keeps its default action).
# The case: minimal.toml with a row of 2 000 000 disks and their sand–sand contact (reading and checking it
# take seconds; without that contact the reader refused the case in 0.45 s, before the signal, and the test
# failed on a faster machine without having tested anything).
import signal
import time
with tempfile.TemporaryDirectory() as tmp:
    text = open(os.path.join(src, "tests/lib/fixtures/minimal.toml")).read()
    row = '[[row]]\nmaterial = "sand"\nradius = "1 cm"\nstart = ["0 m", "5 cm"]\nstep = ["2.1 cm", "0 m"]\ncount = 2000000\n\n'
    pair = '[[contact]]\nbetween = ["sand", "sand"]\nlaw = "linear"\nkn = "1e5 N/m"\nks_ratio = 0.25\nfriction = 0.5\ndamping_ratio = 0.3\n\n'
    big = os.path.join(tmp, "long_check.toml")
    open(big, "w").write(text.replace("[[element]]", pair + "[[element]]", 1).replace("[[wall]]", row + "[[wall]]", 1))
    p = subprocess.Popen([exe, "check", big], cwd=src, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    time.sleep(0.2)  # the whole check takes 0.7 s here: the signal comes in the middle of it
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        p.wait(timeout=20)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
    took = time.monotonic() - sent
    if p.returncode != -signal.SIGINT or took > 1.0:
        fails.append(f"check stopped by SIGINT after 0.2 s: exit {p.returncode} {took:.2f} s after the signal "
                     f"(expected to end at once by the signal, {-signal.SIGINT})")

if fails:
    sys.exit("FAIL:\n  " + "\n  ".join(fails))
print("OK:", v.stdout.strip())
