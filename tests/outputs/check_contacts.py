#!/usr/bin/env python3
"""contacts.csv ([output] contacts, lib/dem/run/contacts_csv.hpp) and the VTK contact lines, read back with
parsers of this file's own (the csv module; the .vtp's XML head and its appended raw arrays with struct):

1. cases/basic/rest_on_wall.toml, 1 kg and (second set) 3 kg: one contact, disk 0 on the wall "floor", at the
   wall's point under the centre, n = (0, -1), f_n = m g, f_s = 0, linear, one link, no segments.
2. tests/outputs/two_stacked_disks.toml, masses (1, 1) kg at 0.1 s and (1, 3) kg at 0.6 s: floor f_n = (m0 + m1) g, pair 0-1
   f_n = m1 g with n = (0, 1) at the middle of the pair's overlap; the hand-known overlaps m g / K.
3. cases/pre/block_mode.toml with gravity straight down: a stack of 3 bonded PREs (N = 2) on a floor
   (N = 2, unbonded): faces 0-1, 1-2 carry 2 m g and m g, all links bonded ("BB"); the floor 3 m g ("LL").
4. tests/lib/fixtures/restart_pre_break.toml every 20 steps: the face's letters against bond_breaks.csv
   (each break an x, from below: xBBB, xxBB, ...) and against the series' e1.links.e0.
5. Each snapshot's contact lines (cell kind 3): as many as contacts.csv's rows of that step, the same pairs,
   normal_force = fn, shear_force = fs, links = links, bit for bit (both written with 17 digits).
6. cases/bench/settle_10k.toml for 5000 steps with the elements renumbered in space at every rebuild
   (numerics.reorder_every = 1): ids, not array indices — every pair with i < j, unit normals — and 5.

Usage: check_contacts.py <dem2d> <source dir> <work dir> [--plant-fn-factor F]. Exit status 1 on any failure.
"""
import csv
import math
import pathlib
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

G = 9.80665
HEADER = ["step", "t [s]", "i", "j", "wall", "law", "x [m]", "y [m]", "nx", "ny", "fn [N]", "fs [N]", "links", "segments", "mr [N*m]"]
failures = []
plant = float(sys.argv[sys.argv.index("--plant-fn-factor") + 1]) if "--plant-fn-factor" in sys.argv else 1.0


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def close(a, b, rel=1e-9, abs_=0.0):
    return math.isclose(a, b, rel_tol=rel, abs_tol=abs_)


def run(dem2d, case, out, *sets):
    if out.exists():
        shutil.rmtree(out)
    cmd = [dem2d, "run", str(case), "--out", str(out), "-q"] + [a for s in sets for a in ("--set", s)]
    subprocess.run(cmd, check=True)


def read_contacts(path):
    """contacts.csv as {step: [row dict]}: numbers as numbers, the header exactly as documented."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    check(rows[0] == HEADER, f"{path.parent.name}: contacts.csv header {rows[0]}")
    steps = {}
    short = [r for r in rows[1:] if len(r) != len(HEADER)]
    check(not short, f"{path.parent.name}: {len(HEADER)} cells in every row {short[:1]}")
    for r in rows[1:]:
        d = dict(zip(HEADER, r))
        for k in ("step", "i", "j", "links"):
            d[k] = int(d[k])
        for k in ("t [s]", "x [m]", "y [m]", "nx", "ny", "fn [N]", "fs [N]"):
            d[k] = float(d[k])
        d["fn [N]"] *= plant  # --plant-fn-factor: a planted misreading, the checks must fail
        steps.setdefault(d["step"], []).append(d)
    return steps


def read_vtp(path):
    """A dem2d snapshot: {'step': n, 'cells': {name: [values]}}, from the XML head and the raw appended block."""
    blob = path.read_bytes()
    marker = b'<AppendedData encoding="raw">\n_'
    head, data = blob.split(marker, 1)
    root = ET.fromstring(head + b"</VTKFile>")
    fmt = {"Float64": "d", "Int64": "q", "Int32": "i"}

    def values(a):
        off = int(a.get("offset"))
        (n,) = struct.unpack_from("<Q", data, off)
        code = fmt[a.get("type")]
        return list(struct.unpack_from(f"<{n // struct.calcsize(code)}{code}", data, off + 8))

    step = values(root.find("PolyData/FieldData/DataArray[@Name='step']"))[0]
    cells = {a.get("Name"): values(a) for a in root.find("PolyData/Piece/CellData")}
    return {"step": step, "cells": cells}


def only(rows, what):
    check(len(rows) == 1, f"{what}: one contact ({len(rows)})")
    return rows[0]


def disk_on_floor(dem2d, src, work):
    for m in (1.0, 3.0):
        out = work / f"rest_{m:g}kg"
        run(dem2d, src / "cases/basic/rest_on_wall.toml", out, "output.contacts=true", f"element.0.mass={m} kg")
        steps = read_contacts(out / "contacts.csv")
        check(max(steps) == 10000, f"rest {m:g} kg: rows at the last step")
        c = only(steps[10000], f"rest {m:g} kg")
        check((c["i"], c["j"], c["wall"], c["law"]) == (0, -1, "floor", "linear"), f"rest {m:g} kg: disk 0 on floor")
        check(c["x [m]"] == 0.0 and c["y [m]"] == 0.0 and (c["nx"], c["ny"]) == (0.0, -1.0), "point (0, 0), n = (0, -1)")
        check(close(c["fn [N]"], m * G), f"rest {m:g} kg: fn = m g: {c['fn [N]']!r} vs {m * G!r}")
        check(abs(c["fs [N]"]) < 1e-9 and c["links"] == 1 and c["segments"] == "", "no shear, one link, no segments")
        check(close(c["t [s]"], 0.1), "t = 0.1 s")


def stacked_disks(dem2d, src, work):
    K, r = 1e6, 0.01
    # the heavier upper disk's slow mode is less damped (the dashpots are set on each contact's mass basis):
    # its transient is down to 4e-4 of m g at 0.1 s, to round-off at 0.6 s
    for m0, m1, duration in ((1.0, 1.0, 0.1), (1.0, 3.0, 0.6)):
        out = work / f"stack_{m0:g}_{m1:g}"
        run(dem2d, src / "tests/outputs/two_stacked_disks.toml", out, f"element.1.mass={m1} kg",
            f"numerics.duration={duration} s")
        steps = read_contacts(out / "contacts.csv")
        check(max(steps) == round(duration / 1e-5), f"stack {m0:g}/{m1:g}: rows at the last step")
        rows = steps[max(steps)]
        check(len(rows) == 2, f"stack {m0:g}/{m1:g}: two contacts")
        pair = [c for c in rows if c["j"] == 1][0]
        floor = [c for c in rows if c["wall"] == "floor"][0]
        check(pair["i"] == 0 and floor["i"] == 0 and floor["j"] == -1 and pair["wall"] == "", "pair 0-1, disk 0 on floor")
        check(close(floor["fn [N]"], (m0 + m1) * G, 1e-7), f"floor fn = (m0 + m1) g: {floor['fn [N]']!r}")
        check(close(pair["fn [N]"], m1 * G, 1e-7), f"pair fn = m1 g: {pair['fn [N]']!r}")
        check((pair["nx"], pair["ny"]) == (0.0, 1.0) and close(floor["ny"], -1.0), "n from i towards j (up), to the floor (down)")
        y0 = r - (m0 + m1) * G / K  # the lower centre; the pair's overlap m1 g / K, its middle r - overlap/2 above
        check(close(pair["y [m]"], y0 + r - 0.5 * m1 * G / K, 0.0, 1e-12), f"pair point y {pair['y [m]']!r}")
        check(abs(pair["fs [N]"]) < 1e-9 and abs(floor["fs [N]"]) < 1e-9, "no shear")


def pre_stack(dem2d, src, work):
    out = work / "pre_stack"
    run(dem2d, src / "cases/pre/block_mode.toml", out, "physics.gravity.direction=-90 deg", "output.contacts=true",
        "output.vtk=true")
    m = 0.0671
    rows = read_contacts(out / "contacts.csv")
    last = rows[max(rows)]
    want = {(0, 1, ""): (2 * m * G, "BB"), (1, 2, ""): (m * G, "BB"), (0, -1, "slope"): (3 * m * G, "LL")}
    got = {(c["i"], c["j"], c["wall"]): c for c in last}
    check(sorted(got) == sorted(want), f"PRE stack: contacts {sorted(got)}")
    for k, (fn, letters) in want.items():
        if k in got:
            c = got[k]
            check(c["law"] == "face" and c["links"] == 2, f"PRE {k}: a face, 2 links")
            check(close(c["fn [N]"], fn, 1e-6), f"PRE {k}: fn {c['fn [N]']!r} vs {fn!r}")
            check(c["segments"] == letters, f"PRE {k}: segments {c['segments']!r} vs {letters!r}")
    return out


def breaking_face(dem2d, src, work):
    out = work / "pre_break"
    run(dem2d, src / "tests/lib/fixtures/restart_pre_break.toml", out, "output.contacts=true",
        "output.contacts_every=20", "output.bond_breaks=true")
    rows = read_contacts(out / "contacts.csv")
    with open(out / "bond_breaks.csv", newline="") as f:
        breaks = [int(b["step"]) for b in csv.DictReader(f)]
    with open(out / "series.csv", newline="") as f:
        series = list(csv.DictReader(f))
        col = "e1.links.e0 [1]"
        links = {round(float(s["t [s]"]) / 1e-6): float(s[col]) for s in series}
    seen = set()
    for step, cs in sorted(rows.items()):
        broken = sum(b <= step for b in breaks)
        if not cs:
            continue
        c = only(cs, f"break step {step}")
        s = c["segments"]
        seen.add(s)
        ok = len(s) == 4 and s == "x" * broken + "B" * (4 - broken) and c["links"] == 4 - broken
        check(ok, f"break step {step}: {s!r}, links {c['links']}, {broken} broken by then")
        if step in links:
            check(links[step] == c["links"], f"break step {step}: links = the series' e1.links.e0")
    check({"BBBB", "xBBB", "xxBB", "xxxB"} <= seen, f"the face opens from below: {sorted(seen)}")


def vtk_lines(out):
    """Each snapshot's contact lines (kind 3) against contacts.csv's rows of its step."""
    rows = read_contacts(out / "contacts.csv")
    files = sorted((out / "vtk").glob("snapshot_*.vtp"))
    check(len(files) >= 2, f"{out.name}: {len(files)} snapshots")
    for f in files:
        v = read_vtp(f)
        c = v["cells"]
        lines = [k for k, kind in enumerate(c["kind"]) if kind == 3]
        csv_rows = rows.get(v["step"], [])
        check(len(lines) == len(csv_rows), f"{f.name}: {len(lines)} contact lines, {len(csv_rows)} rows in contacts.csv")
        differ = []
        for k, row in zip(lines, csv_rows):
            other = row["j"] if row["wall"] == "" else -1
            if (c["element_id"][k], c["other_element_id"][k], c["normal_force"][k], c["shear_force"][k],
                    c["links"][k]) != (row["i"], other, row["fn [N]"], row["fs [N]"], row["links"]):
                differ.append(f"line {k} vs contact {row['i']}-{row['j']}{row['wall']}")
        check(not differ, f"{f.name}: each contact line is its row's contact with its fn, fs, links {differ[:3]}")


def renumbered(dem2d, src, work):
    out = work / "settle_reordered"
    run(dem2d, src / "cases/bench/settle_10k.toml", out, "numerics.duration=0.02", "output.contacts=true",
        "numerics.reorder_every=1", "output.vtk=true")
    rows = read_contacts(out / "contacts.csv")
    last = rows[max(rows)]
    pairs = [c for c in last if c["wall"] == ""]
    check(max(rows) == 5000 and len(pairs) > 10000, f"settle: {len(last)} contacts at step {max(rows)}, {len(pairs)} pairs")
    check(all(c["i"] < c["j"] for c in pairs), "settle: every pair written as ids with i < j")
    check(max(abs(math.hypot(c["nx"], c["ny"]) - 1) for c in last) < 1e-15, "settle: unit normals")
    return out


def main():
    dem2d, src, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    disk_on_floor(dem2d, src, work)
    stacked_disks(dem2d, src, work)
    vtk_lines(work / "stack_1_3")
    vtk_lines(pre_stack(dem2d, src, work))
    breaking_face(dem2d, src, work)
    vtk_lines(renumbered(dem2d, src, work))
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


main()
