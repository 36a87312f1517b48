#!/usr/bin/env python3
"""The longest functions of the C++ sources under the given folders (docs/style.md: no function over
150 lines). A function is a definition that starts at column 0 (the project's namespaces are not
indented) with a line holding '(' and ends at the first '}' at column 0 after it; its length counts
every line from its signature to that brace.

Usage: function_lengths.py [--max N] [--top K] ROOT FOLDER...   exit 1 if a function is longer than N
(and prints them), and also if no function was found at all (a filter that matches nothing fails)."""
import argparse
import pathlib
import re
import sys

SIGNATURE = re.compile(r"^[A-Za-z_~][^;]*\(")  # a declaration at column 0 that takes arguments


def functions(path):
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    k = 0
    while k < len(lines):
        line = lines[k]
        if SIGNATURE.match(line) and not line.startswith(("namespace", "using", "#", "template", "extern", "static_assert")):
            # the body opens on this line or within the next few (long signatures)
            start = k
            j = k
            while j < len(lines) and j < k + 8 and "{" not in lines[j] and not lines[j].rstrip().endswith(";"):
                j += 1
            if j < len(lines) and "{" in lines[j] and not lines[j].rstrip().endswith(";"):
                if lines[j].rstrip().endswith("}"):  # a one-line body
                    k = j + 1
                    continue
                end = j + 1
                while end < len(lines) and not lines[end].startswith("}"):
                    end += 1
                name = re.sub(r"\s+", " ", line.split("(")[0]).strip().split(" ")[-1]
                yield name, start + 1, end - start + 1
                k = end + 1
                continue
        k += 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max", type=int, default=150)
    ap.add_argument("--top", type=int, default=0, help="print the K longest per folder")
    ap.add_argument("root")
    ap.add_argument("folders", nargs="+")
    a = ap.parse_args()
    root = pathlib.Path(a.root)
    found, over = 0, []
    for folder in a.folders:
        rows = []
        for f in sorted((root / folder).rglob("*.[ch]pp")):
            for name, line, n in functions(f):
                found += 1
                rows.append((n, f"{f.relative_to(root)}:{line}", name))
        rows.sort(reverse=True)
        if a.top:
            print(f"{folder}: " + "; ".join(f"{name} {n} lines ({where})" for n, where, name in rows[: a.top]))
        over += [r for r in rows if r[0] > a.max]
    if found == 0:
        sys.exit("function_lengths: no function found (wrong root or folders?)")
    for n, where, name in over:
        print(f"{where}: {name}: {n} lines (at most {a.max})")
    sys.exit(1 if over else 0)


if __name__ == "__main__":
    main()
