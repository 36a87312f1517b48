#!/usr/bin/env python3
"""The score of a mutation run per folder, as a Markdown table (scripts/README.md).

  report.py RESULTS.tsv MUTANTS [--equivalent FILE]

RESULTS.tsv is run.sh's `<work>/results.tsv`; only the mutants listed in MUTANTS are counted (a work
folder may hold the results of several lists). --equivalent names survivors argued equivalent, one per
line: `ID: the one-line argument`. Columns: killed (by the unit tests, by the verification suite),
survived, equivalent, stillborn (does not compile: `build-error`, not counted in the score); score =
killed / (killed + survived), equivalent mutants left out of both.
"""
import argparse
import re
import sys
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import mutants as mutants_file  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("mutants")
    ap.add_argument("--equivalent")
    args = ap.parse_args()
    listed = {m["id"]: m for m in mutants_file.read(args.mutants)}
    seed = re.search(r"^# seed: (\d+)", Path(args.mutants).read_text(), re.M)
    equivalent = {}
    if args.equivalent:
        for line in Path(args.equivalent).read_text().splitlines():
            if line.strip() and not line.startswith("#"):
                k, _, why = line.partition(": ")
                equivalent[k.strip()] = why.strip()
    status = {}
    for line in Path(args.results).read_text().splitlines()[1:]:
        f = line.split("\t")
        if f[0] in listed:
            status[f[0]] = f[1]  # the last record of a mutant counts
    cols = ["killed(unit)", "killed(verification)", "survived", "equivalent", "stillborn"]
    table = defaultdict(lambda: dict.fromkeys(cols, 0))
    survivors = []
    for k, s in status.items():
        folder = str(Path(listed[k]["file"]).parent)
        if s == "build-error":
            c = "stillborn"
        elif s.startswith("killed"):
            c = s
        elif k in equivalent:
            c = "equivalent"
        else:
            c = "survived"
            survivors.append(k)
        table[folder][c] += 1
    print(f"mutants: {args.mutants} (seed {seed.group(1) if seed else '-'}), {len(status)} of "
          f"{len(listed)} run\n")
    print("| folder | " + " | ".join(cols) + " | score |")
    print("|---|" + "---:|" * (len(cols) + 1))
    total = dict.fromkeys(cols, 0)

    def score(r):
        k = r["killed(unit)"] + r["killed(verification)"]
        n = k + r["survived"]
        return f"{k}/{n} ({100 * k / n:.0f} %)" if n else "-"

    for folder in sorted(table):
        r = table[folder]
        for c in cols:
            total[c] += r[c]
        print(f"| {folder} | " + " | ".join(str(r[c]) for c in cols) + f" | {score(r)} |")
    print("| **all** | " + " | ".join(str(total[c]) for c in cols) + f" | {score(total)} |")
    if survivors:
        print("\nsurvivors (neither killed nor argued equivalent):")
        for k in sorted(survivors):
            m = listed[k]
            print(f"- `{k}` {m['file']}: `{m['from']}` → `{m['to']}`")
    if equivalent:
        print("\nequivalent:")
        for k in sorted(e for e in equivalent if e in status):
            print(f"- `{k}`: {equivalent[k]}")


if __name__ == "__main__":
    main()
