#!/usr/bin/env python3
"""Equation labels: one spelling, no label the docs do not define, every named code site holds its labels.

  check_labels.py REPO_ROOT          checks the repository; exit 0 when clean, 1 with one line per fault
  check_labels.py --self-test        plants each kind of fault in a small temporary tree; exit 0 when
                                     every planted fault is reported and the clean tree passes

Words used below:

- A *label* is K, M, R (the rolling resistance of docs/model.md §4) or P (the polygon element, §5), an equation number of 1 or 2 digits, and an optional sub-equation written with
  a dot and one digit or lower-case letter: K19, K6.a, M15.1 (Kiyama & Fujimura, Matsui & Nishimura;
  docs/model.md). A group label (K7) stands for all its sub-equations (K7.a, K7.b).
- docs/model.md *defines* a label when the label opens a parenthesis or opens an item of a parenthesised
  list (items separated by "," or ";"): "(K6.a)", "(K6.b, K7.b)", "(M25, the second …)". A range item
  "(K6–K14)" defines its two ends and every whole number between them. A group label (K7) counts as
  defined when it or any of its sub-labels is defined; a sub-label (K7.a) only when itself is. Labels
  inside tables are not definitions (the tables below are where the code sites are named).
- A *code site table* is a Markdown table of docs/model.md whose header row has "Equations" as its first
  cell and "Code" as its last. Each row names labels in its first cell ("K6.a, K7.a", ranges as above)
  and code sites in its last: every backticked text there that contains a "/" is a path from the
  repository root, a file (`lib/dem/contact/linear_contact.hpp`), a folder (ends with "/": `lib/dem/core/`,
  every file below it) or a glob (`lib/dem/contact/face_contact*`). A row whose last cell has no such path
  names no site ("—": not implemented as such, or not labelled where it is).

Faults reported:

(a) a file of the code (lib/, app/, reference/, reports/, verification/engine/) cites a label that
    docs/model.md does not define; the same for the other files that cite labels (docs/ but model.md
    itself, cases/, verification/, bench/, scripts/; tests/ is left out: its tests plant labels that
    do not exist, K99, M27);
(b) a code site of a table does not exist, or does not contain one of its row's labels (a group label
    K19 is found as K19 or any K19.x; a sub-label only as itself; for a folder or a glob, in at least one
    of its files);
(c) a label is written in a non-canonical spelling anywhere in the project's text files (the dotless
    sub-equation: digits followed directly by a letter; or the paper's middle dot): the dotted form is the
    only spelling;
(d) nothing was found: no label defined, no label cited in the code, or no code site table: a check that
    finds nothing checks nothing.
"""
import re
import sys
import tempfile
from pathlib import Path

CODE_DIRS = ["lib", "app", "reference", "reports", "verification/engine"]
CITING_DIRS = ["docs", "cases", "verification", "bench", "scripts"]  # verification/engine: counted once
SPELLING_DIRS = ["lib", "app", "reference", "reports", "verification", "tests", "cases", "docs", "bench",
                 "scripts", "fuzz", "cmake"]
SPELLING_FILES = ["README.md", "CMakeLists.txt"]
TEXT_SUFFIXES = {".cpp", ".hpp", ".h", ".c", ".md", ".py", ".toml", ".txt", ".sh", ".cmake", ".html", ".js",
                 ".json", ".csv"}
MODEL = "docs/model.md"

W = r"A-Za-z0-9_"
# A label in canonical spelling; the look-ahead keeps "K1" out of "K19" and "K6" out of "K6.a".
LABEL = re.compile(rf"(?<![{W}])([KMRPB])([0-9]{{1,2}})(?:\.([0-9a-z]))?(?![{W}]|\.[0-9a-z](?![{W}]))")
# Non-canonical: digits followed directly by lower-case letters, or by the paper's middle dot.
BAD_SPELLING = re.compile(rf"(?<![{W}])[KMRPB][0-9]{{1,2}}(?:[a-z]|\s*[·・]\s*[0-9a-z])(?![{W}])")
ITEM = re.compile(r"^([KMRPB])([0-9]{1,2})(?:\.([0-9a-z]))?(?:\s*[–-]\s*([KMRPB])([0-9]{1,2}))?(?![A-Za-z0-9_.])")


def labels_of_item(item):
    """The labels an item of a parenthesised list or a table cell names ("K6.a", "K16–K19")."""
    m = ITEM.match(item.strip())
    if not m:
        return []
    letter, num, sub = m.group(1), int(m.group(2)), m.group(3)
    if m.group(4):
        if m.group(4) != letter or sub:
            return []
        return [f"{letter}{k}" for k in range(num, int(m.group(5)) + 1)]
    return [f"{letter}{num}" + (f".{sub}" if sub else "")]


def split_table_row(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def read_model(text):
    """(defined labels, [(line number, labels, sites)] of the code site tables)."""
    defined = set()
    prose = []
    rows = []
    lines = text.splitlines()
    in_sites = False
    for n, line in enumerate(lines, 1):
        if line.lstrip().startswith("|"):
            cells = split_table_row(line)
            if cells and cells[0] == "Equations" and cells[-1] == "Code":
                in_sites = True
                continue
            if in_sites and not set("".join(cells)) <= set("-: "):
                labels = [l for item in cells[0].split(",") for l in labels_of_item(item)]
                sites = [t for t in re.findall(r"`([^`]+)`", cells[-1]) if "/" in t]
                rows.append((n, labels, sites, cells[0]))
            continue
        in_sites = False
        prose.append(line)
    for group in re.findall(r"\(([^()]*)\)", "\n".join(prose)):
        for item in re.split(r"[,;]", group):
            defined.update(labels_of_item(item))
    groups = {l.split(".")[0] for l in defined}
    return defined | groups, rows


def text_files(root, dirs, files=()):
    for d in dirs:
        base = root / d
        if base.is_dir():
            for p in sorted(base.rglob("*")):
                if p.is_file() and (p.suffix in TEXT_SUFFIXES or p.name == "CMakeLists.txt"):
                    yield p
    for f in files:
        if (root / f).is_file():
            yield root / f


def read(p):
    return p.read_text(encoding="utf-8", errors="replace")


def cited(text):
    """(line number, label) of every label in canonical spelling."""
    for n, line in enumerate(text.splitlines(), 1):
        for m in LABEL.finditer(line):
            yield n, m.group(1) + m.group(2) + (f".{m.group(3)}" if m.group(3) else "")


def contains_label(text, label):
    """A sub-label only as itself; a group label as itself or any of its sub-labels."""
    found = {l for _, l in cited(text)}
    return label in found or ("." not in label and any(l.split(".")[0] == label for l in found))


def site_files(root, site):
    if site.endswith("/"):
        base = root / site
        return [p for p in sorted(base.rglob("*")) if p.is_file()] if base.is_dir() else None
    if any(c in site for c in "*?["):
        found = [p for p in sorted(root.glob(site)) if p.is_file()]
        return found or None
    return [root / site] if (root / site).is_file() else None


def check(root, skip=()):
    root = Path(root)
    faults = []
    model = root / MODEL
    if not model.is_file():
        return [f"{MODEL}: missing"]
    defined, rows = read_model(read(model))
    if not defined:
        faults.append(f"{MODEL}: (d) defines no label")
    if not rows:
        faults.append(f"{MODEL}: (d) has no code site table (header | Equations | ... | Code |)")

    n_cited = 0
    for p in text_files(root, CODE_DIRS):
        rel = p.relative_to(root).as_posix()
        for n, label in cited(read(p)):
            n_cited += 1
            if label not in defined:
                faults.append(f"{rel}:{n}: (a) cites {label}, which {MODEL} does not define")
    for p in text_files(root, CITING_DIRS):
        rel = p.relative_to(root).as_posix()
        if rel == MODEL or rel.startswith("verification/engine/"):
            continue
        for n, label in cited(read(p)):
            if label not in defined:
                faults.append(f"{rel}:{n}: (a) cites {label}, which {MODEL} does not define")
    if n_cited == 0:
        faults.append(f"(d) no label cited in {', '.join(CODE_DIRS)}")

    n_sites = 0
    for n, labels, sites, first in rows:
        if not labels:
            faults.append(f"{MODEL}:{n}: (b) a code site row names no label: '{first}'")
        for label in labels:
            if label not in defined:
                faults.append(f"{MODEL}:{n}: (b) the table names {label}, which {MODEL} does not define")
        for site in sites:
            n_sites += 1
            files = site_files(root, site)
            if files is None:
                faults.append(f"{MODEL}:{n}: (b) code site `{site}` does not exist")
                continue
            texts = [read(f) for f in files]
            for label in labels:
                if not any(contains_label(t, label) for t in texts):
                    faults.append(f"{MODEL}:{n}: (b) code site `{site}` does not contain {label}")
    if rows and n_sites == 0:
        faults.append(f"{MODEL}: (d) the code site tables name no file")

    for p in text_files(root, SPELLING_DIRS, SPELLING_FILES):
        rel = p.relative_to(root).as_posix()
        if rel in skip:
            continue
        for n, line in enumerate(read(p).splitlines(), 1):
            for m in BAD_SPELLING.finditer(line):
                faults.append(f"{rel}:{n}: (c) non-canonical label '{m.group(0)}' (write the sub-equation "
                              "after a dot)")
    return faults


def self_test():
    """Each planted fault must be reported with its letter; the clean tree must pass."""
    model = ("# m\n\nSprings: a (K6.a), b (K6.b, K7.b); totals (K9); range (K16–K18); velocity (K17.a).\n\n"
             "| Equations | What | Code |\n|---|---|---|\n"
             "| K6.a, K9 | spring | `lib/law.hpp` |\n| K16–K18 | step | `lib/core/` |\n"
             "| K6.b | dashpot | `lib/la*.hpp` |\n")
    law = "// (K6.a) (K6.b)\n// (K9)\n"
    core = "// (K16) (K17.a) (K18)\n"
    dot = "\u00b7"
    cases = {
        "clean": ({}, None),
        "undefined label in code": ({"lib/law.hpp": law + "// (K10)\n"}, "(a)"),
        "undefined sub-label in code": ({"lib/law.hpp": law + "// (K6.c)\n"}, "(a)"),
        "undefined label in another doc": ({"docs/findings.md": "see (M27)\n"}, "(a)"),
        "site lacks its label": ({"lib/law.hpp": "// (K6.a) (K6.b)\n"}, "(b)"),
        "folder site lacks its label": ({"lib/core/a.hpp": "// (K16) (K18)\n"}, "(b)"),
        "site missing": ({"docs/model.md": model.replace("lib/law.hpp", "lib/gone.hpp")}, "(b)"),
        "glob matches nothing": ({"docs/model.md": model.replace("lib/la*.hpp", "lib/zz*.hpp")}, "(b)"),
        "glob lacks its label": ({"lib/law.hpp": "// (K6.a) (K9)\n"}, "(b)"),
        "dotless spelling": ({"lib/law.hpp": law + "// (K6" + "a)\n"}, "(c)"),
        "middle dot spelling": ({"cases/x.toml": "# K6 " + dot + " a\n"}, "(c)"),
        "no labels at all": ({"docs/model.md": "# m\n\n| Equations | What | Code |\n|---|---|---|\n",
                              "lib/law.hpp": "", "lib/core/a.hpp": ""}, "(d)"),
        "no site table": ({"docs/model.md": model.split("\n\n|")[0] + "\n"}, "(d)"),
    }
    bad = 0
    for name, (change, expect) in cases.items():
        with tempfile.TemporaryDirectory() as tmp:
            files = {"docs/model.md": model, "lib/law.hpp": law, "lib/core/a.hpp": core}
            files.update(change)
            for rel, text in files.items():
                (Path(tmp) / rel).parent.mkdir(parents=True, exist_ok=True)
                (Path(tmp) / rel).write_text(text, encoding="utf-8")
            faults = check(tmp)
        ok = (not faults) if expect is None else any(expect in f for f in faults)
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {len(faults)} fault(s)" + "".join(f"\n       {f}" for f in faults))
        bad += not ok
    return 1 if bad else 0


def main():
    if len(sys.argv) == 2 and sys.argv[1] == "--self-test":
        return self_test()
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    root = Path(sys.argv[1]).resolve()
    me = Path(__file__).resolve()
    skip = {me.relative_to(root).as_posix()} if me.is_relative_to(root) else set()
    faults = check(root, skip)
    for f in faults:
        print(f)
    defined, rows = read_model(read(root / MODEL)) if (root / MODEL).is_file() else (set(), [])
    print(f"{len(faults)} fault(s); {len(defined)} labels defined in {MODEL}, {len(rows)} code site rows")
    return 1 if faults else 0


if __name__ == "__main__":
    sys.exit(main())
