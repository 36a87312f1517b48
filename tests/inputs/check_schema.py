#!/usr/bin/env python3
"""`dem2d schema` against the cases of the project and against planted wrong cases.

Usage: check_schema.py DEM2D_EXECUTABLE SOURCE_DIR WORK_DIR

- The schema is a valid JSON Schema (draft-07).
- Every case file in cases/, tests/lib/fixtures/ and python/examples/ (and any case file in verification/: a TOML file with
  [case] and [numerics]) validates against it (Debian python3-jsonschema, tomllib).
- Each planted wrong case (tests/lib/fixtures/minimal.toml with one line changed: a misspelled key, a wrong
  type, an unknown unit, an angle without its unit, a word not allowed) is refused by both the schema and
  the reader (`dem2d check`: exit status 2 and `file:line: key`).
Prints what it validated; exits 1 with the list of failures.
"""
import json
import pathlib
import subprocess
import sys
import tomllib

import jsonschema

exe, src, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
work.mkdir(parents=True, exist_ok=True)
fails = []

out = subprocess.run([exe, "schema"], capture_output=True, text=True)
if out.returncode != 0:
    sys.exit(f"FAIL: dem2d schema: exit {out.returncode}: {out.stderr}")
schema = json.loads(out.stdout)
jsonschema.Draft7Validator.check_schema(schema)
validator = jsonschema.Draft7Validator(schema)


def errors(doc):
    return [f"{'.'.join(map(str, e.absolute_path)) or '(top)'}: {e.message}" for e in validator.iter_errors(doc)]


cases = sorted(p for d in ("cases", "tests/lib/fixtures", "python/examples") for p in (src / d).rglob("*.toml"))
for p in sorted((src / "verification").rglob("*.toml")):
    doc = tomllib.loads(p.read_text())
    if "case" in doc and "numerics" in doc:
        cases.append(p)
for p in cases:
    errs = errors(tomllib.loads(p.read_text()))
    if errs:
        fails.append(f"{p.relative_to(src)}: the schema refuses a shipped case:\n    " + "\n    ".join(errs[:5]))
print(f"{len(cases)} case files validate against the schema")

minimal = (src / "tests/lib/fixtures/minimal.toml").read_text()
planted = {  # name: (line replaced, replacement, what the reader must say after file:line)
    "misspelled key": ("ks_ratio = 0.25", "ks_raito = 0.25", "contact.0.ks_raito: unknown key; did you mean 'ks_ratio'?"),
    "misspelled required key": ('dt = "1e-5 s"', 'dtt = "1e-5 s"', "numerics.dt: missing (required) (is 'dtt'"),
    "misspelled table": ("[numerics]", "[numeric]", "missing [numerics] table (dt, duration) (is 'numeric', line 37"),
    "wrong type": ('dt = "1e-5 s"', "dt = true", "numerics.dt"),
    "unknown unit": ('kn = "1e5 N/m"', 'kn = "1e5 N/mmm"', "contact.0.kn"),
    "angle without unit": ("friction = 0.5", 'friction_angle = "30"', "contact.0.friction_angle"),
    "word not allowed": ('law = "linear"', 'law = "linaer"', "contact.0.law"),
    "vector of three": ('position = ["0 m", "1 cm"]', 'position = ["0 m", "1 cm", "0 m"]', "element.0.position"),
}
for name, (old, new, key) in planted.items():
    assert old in minimal, old
    text = minimal.replace(old, new, 1)
    f = work / f"planted_{name.replace(' ', '_')}.toml"
    f.write_text(text)
    errs = errors(tomllib.loads(text))
    r = subprocess.run([exe, "check", str(f)], capture_output=True, text=True)
    print(f"planted {name}: schema: {errs[0] if errs else 'ACCEPTED'}; reader: exit {r.returncode}: {r.stderr.strip()}")
    if not errs:
        fails.append(f"planted {name}: the schema accepts it")
    if r.returncode != 2 or key not in r.stderr or f"{f}:" not in r.stderr:
        fails.append(f"planted {name}: the reader: exit {r.returncode}, {r.stderr!r} (expected 2, {f}:LINE: {key})")

if fails:
    sys.exit("FAIL:\n  " + "\n  ".join(fails))
print("OK")
