#!/usr/bin/env python3
"""Reads mutants.txt; lists, checks or applies one mutant to a tree (scripts/mutation/run.sh uses it).

  mutants.py list  MUTANTS                  ids, one per line
  mutants.py check MUTANTS TREE             every mutant applies to TREE exactly once (exit 1 if not)
  mutants.py apply MUTANTS TREE ID          applies mutant ID to TREE in place
  mutants.py show  MUTANTS ID               file and what it breaks
"""
import sys
from pathlib import Path


def read(path):
    mutants, cur = [], {}
    for raw in Path(path).read_text(encoding="utf-8").splitlines():
        if raw.startswith("#"):
            continue
        if not raw.strip():
            if cur:
                mutants.append(cur)
                cur = {}
            continue
        key, sep, value = raw.partition(": ")
        if not sep or key not in ("id", "file", "breaks", "from", "to", "nth"):
            sys.exit(f"{path}: bad line: {raw!r}")
        cur[key] = value
    if cur:
        mutants.append(cur)
    ids = set()
    for m in mutants:
        for k in ("id", "file", "breaks", "from", "to"):
            if k not in m:
                sys.exit(f"{path}: mutant {m.get('id', '?')}: missing {k}")
        if m["id"] in ids:
            sys.exit(f"{path}: duplicate id {m['id']}")
        ids.add(m["id"])
    return mutants


def mutated(m, tree):
    text = (Path(tree) / m["file"]).read_text(encoding="utf-8")
    count = text.count(m["from"])
    nth = int(m.get("nth", "0"))
    if nth == 0 and count != 1:
        raise ValueError(f"{m['id']}: '{m['from']}' occurs {count} times in {m['file']} (give nth)")
    if nth > count:
        raise ValueError(f"{m['id']}: occurrence {nth} of '{m['from']}' not in {m['file']} ({count})")
    at = -1
    for _ in range(max(nth, 1)):
        at = text.index(m["from"], at + 1)
    return text[:at] + m["to"] + text[at + len(m["from"]):]


def main():
    cmd, path = sys.argv[1], sys.argv[2]
    mutants = read(path)
    if cmd == "list":
        print("\n".join(m["id"] for m in mutants))
    elif cmd == "check":
        bad = 0
        for m in mutants:
            try:
                mutated(m, sys.argv[3])
            except (ValueError, FileNotFoundError) as e:
                print(e)
                bad += 1
        print(f"{len(mutants)} mutants, {bad} do not apply")
        sys.exit(1 if bad else 0)
    elif cmd == "apply":
        m = next((m for m in mutants if m["id"] == sys.argv[4]), None)
        if m is None:
            sys.exit(f"no mutant {sys.argv[4]}")
        (Path(sys.argv[3]) / m["file"]).write_text(mutated(m, sys.argv[3]), encoding="utf-8")
    elif cmd == "show":
        m = next(m for m in mutants if m["id"] == sys.argv[3])
        print(f"{m['file']}\t{m['breaks']}")


if __name__ == "__main__":
    main()
