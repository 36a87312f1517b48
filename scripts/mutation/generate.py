#!/usr/bin/env python3
"""Draws a seeded random sample of operator mutants from the C++ sources (scripts/README.md).

  generate.py [--seed S] [--count N] [--folders F ...] [--no-headers] [--out FILE] [--list-sites]

Finds mutation sites with lexical rules on a masked copy of each file (comments, string and character
literals and preprocessor lines blanked out, so that nothing in them is mutated), draws N of them
uniformly with the seed S (printed; the same seed and sources give the same mutants) and writes them in
the format of mutants.txt (each operator class below an equal share of the sample, sites within a
class uniformly at random): each mutant replaces one whole source line (`from`, leading blanks dropped)
by its mutated text (`to`); `nth` names the occurrence when the line's text occurs more than once, so
every mutant applies exactly once. A mutant that does not compile is counted by run.sh as `build-error`
("stillborn", not killed). Operators (the `op` in the id):

  rel     < <= > >= == != : boundary (< <-> <=, > <-> >=) or negation (< -> >=, == -> !=); only
          operators with a blank on both sides (`std::vector<T>` is never touched)
  log     && <-> || (blanks on both sides), or a dropped negation `!x` -> `x`
  arith   + <-> -, * <-> / (blanks on both sides), += <-> -=, *= <-> /=
  const   a numeric literal times 2 or 1/2 (0 and hexadecimal literals are left alone)
  bound   off by one in a `for` loop's bound: `i < n` -> `i < n - 1` or `i < n + 1`
  index   off by one in an index: `a[i]` -> `a[i + 1]` or `a[i - 1]` (i a name)
  stmt    a dropped statement: a simple assignment or call on one line replaced by `;`
"""
import argparse
import random
import re
import sys
from pathlib import Path

# physics (core, contact), readers (cases), run loop and its guards (run), study engine, reports
DEFAULT_FOLDERS = ["lib/dem/core", "lib/dem/contact", "lib/dem/cases", "lib/dem/run",
                   "verification/engine", "reports"]
# not built by the default configuration (a mutant there would survive for no reason)
SKIP_PARTS = {"mpi"}


def mask(text):
    """text with comments, string/char literals and preprocessor lines replaced by blanks (same length,
    newlines kept), so that offsets and line numbers agree with the original."""
    out = list(text)
    i, n = 0, len(text)

    def blank(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    at_line_start = True
    while i < n:
        c = text[i]
        if c == "\n":
            at_line_start = True
            i += 1
            continue
        if at_line_start and c in " \t":
            i += 1
            continue
        if at_line_start and c == "#":  # preprocessor line (with continuations)
            j = i
            while j < n and not (text[j] == "\n" and text[j - 1] != "\\"):
                j += 1
            blank(i, j)
            i = j
            continue
        at_line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            blank(i, j)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            blank(i, j)
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            d = text.index("(", i)
            delim = ")" + text[i + 2:d] + '"'
            j = text.find(delim, d)
            j = n if j < 0 else j + len(delim)
            blank(i, j)
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator 1'000
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            blank(i, j + 1)
            i = j + 1
        else:
            i += 1
    return "".join(out)


REL = {"<": ["<=", ">="], "<=": ["<", ">"], ">": [">=", "<="], ">=": [">", "<"],
       "==": ["!="], "!=": ["=="]}
ARITH = {"+": "-", "-": "+", "*": "/", "/": "*", "+=": "-=", "-=": "+=", "*=": "/=", "/=": "*="}
NUMBER = re.compile(r"(?<![\w.])(\d+\.\d*|\d*\.\d+|\d+)([eE][+-]?\d+)?([fFuUlL]*)(?![\w.])")
FOR_HEAD = re.compile(r"\bfor \(([^;()]*(?:\([^;()]*\))?[^;()]*); ([^;]*?) (<|<=|>|>=) ([^;]+); ")
INDEX = re.compile(r"(?<=[\w)\]])\[([A-Za-z_]\w*)\]")
SIMPLE_STMT = re.compile(r"^(?:[A-Za-z_][\w.:\[\]]*(?:->[\w.\[\]]+)*(?:\([^;]*\))?"
                         r" (?:=|\+=|-=|\*=|/=) [^;]*|[A-Za-z_][\w.:]*(?:->\w+)*(?:\.\w+)*\(.*\));$")
NOT_STMT = ("return", "break", "continue", "goto", "throw", "co_return", "delete", "using", "typedef",
            "case", "default", "else", "const", "static", "auto", "constexpr")


def scaled(literal, factor):
    m = NUMBER.fullmatch(literal)
    mant, expo, suffix = m.group(1), m.group(2) or "", m.group(3)
    is_int = "." not in mant and not expo and not any(s in suffix for s in "fF")
    if is_int:
        v = int(mant)
        if v == 0:
            return None
        new = v * 2 if factor == 2 else v // 2
        return None if new == v else f"{new}{suffix}"
    v = float(mant + expo)
    if v == 0.0:
        return None
    return f"{v * factor!r}{suffix}"


def balanced(s):
    depth = 0
    for c in s:
        depth += (c in "([{") - (c in ")]}")
        if depth < 0:
            return False
    return depth == 0


def sites_of_line(line, mline, prev_end):
    """(op, start, end, replacement) candidates on one line; `mline` is the masked line."""
    out = []
    for m in re.finditer(r"(?<=[ ])(<=|>=|==|!=|<|>)(?= )", mline):
        for to in REL[m.group(1)]:
            out.append(("rel", m.start(), m.end(), to))
    for m in re.finditer(r"(?<= )(&&|\|\|)(?= )", mline):
        out.append(("log", m.start(), m.end(), "||" if m.group(1) == "&&" else "&&"))
    for m in re.finditer(r"(?<![!=<>\w)\]])!(?=[\w(])", mline):
        out.append(("log", m.start(), m.end(), ""))
    for m in re.finditer(r"(?<= )(\+=|-=|\*=|/=|\+|-|\*|/)(?= )", mline):
        out.append(("arith", m.start(), m.end(), ARITH[m.group(1)]))
    for m in NUMBER.finditer(mline):
        if mline[:m.start()].rstrip().endswith(("<", "template")):
            continue
        for factor in (2, 0.5):
            to = scaled(m.group(0), factor)
            if to is not None:
                out.append(("const", m.start(), m.end(), to))
    for m in FOR_HEAD.finditer(mline):
        a, b = m.start(4), m.end(4)
        out.append(("bound", a, b, f"{line[a:b]} - 1"))
        out.append(("bound", a, b, f"{line[a:b]} + 1"))
    for m in INDEX.finditer(mline):
        if m.group(1) in ("this",) or mline[m.end():].startswith("]"):
            continue
        for d in ("+", "-"):
            out.append(("index", m.start(1), m.end(1), f"{m.group(1)} {d} 1"))
    s = mline.strip()
    if (SIMPLE_STMT.match(s) and balanced(s) and not s.startswith(NOT_STMT)
            and prev_end in (";", "{", "}", ":", ")", "else")):
        a = len(mline) - len(mline.lstrip())
        out.append(("stmt", a, a + len(s), ";"))
    return out


def file_sites(repo, rel):
    text = (repo / rel).read_text(encoding="utf-8")
    lines, mlines = text.split("\n"), mask(text).split("\n")
    sites, prev_end = [], "{"
    for no, (line, mline) in enumerate(zip(lines, mlines), 1):
        for op, a, b, to in sites_of_line(line, mline, prev_end):
            new = line[:a] + to + line[b:]
            if new != line:
                sites.append((rel, no, op, line, new))
        if mline.strip():
            prev_end = mline.rstrip()[-1] if not mline.rstrip().endswith("else") else "else"
    return text, sites


def occurrence(text, line_text, line_no):
    """1-based occurrence of `line_text` (as mutants.py searches: overlapping) at line `line_no`."""
    line_start = sum(len(l) + 1 for l in text.split("\n")[:line_no - 1])
    target = line_start + text.split("\n")[line_no - 1].index(line_text)
    at, k = -1, 0
    while True:
        at = text.index(line_text, at + 1)
        k += 1
        if at == target:
            return k


def draw(sites, count, seed):
    """`count` sites: every operator class gets an equal share (round robin over the classes in a
    fixed order, as long as a class has sites left), sites within a class drawn uniformly."""
    rng = random.Random(seed)
    by_op = {}
    for s in sites:
        by_op.setdefault(s[2], []).append(s)
    pools = [rng.sample(by_op[op], len(by_op[op])) for op in sorted(by_op)]
    chosen = []
    while len(chosen) < min(count, len(sites)):
        for pool in pools:
            if pool and len(chosen) < count:
                chosen.append(pool.pop())
    return chosen


def sources(repo, folders, headers):
    exts = (".cpp", ".hpp") if headers else (".cpp",)
    for folder in folders:
        for p in sorted((repo / folder).rglob("*")):
            if p.suffix in exts and not SKIP_PARTS & set(p.relative_to(repo).parts):
                yield p.relative_to(repo).as_posix()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=None, help="default: a fresh one, printed")
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--folders", nargs="+", default=DEFAULT_FOLDERS)
    ap.add_argument("--no-headers", action="store_true", help=".cpp files only (cheaper rebuilds)")
    ap.add_argument("--out", default="-")
    ap.add_argument("--list-sites", action="store_true", help="print the number of sites per folder and op")
    ap.add_argument("--repo", default=str(Path(__file__).resolve().parents[2]))
    args = ap.parse_args()
    repo = Path(args.repo)
    seed = args.seed if args.seed is not None else random.SystemRandom().randrange(1, 10**6)

    texts, sites = {}, []
    for rel in sources(repo, args.folders, not args.no_headers):
        texts[rel], s = file_sites(repo, rel)
        sites += s
    if args.list_sites:
        from collections import Counter
        c = Counter((str(Path(f).parent), op) for f, _, op, _, _ in sites)
        for (folder, op), k in sorted(c.items()):
            print(f"{folder}\t{op}\t{k}")
        print(f"total\t\t{len(sites)}")
        return
    chosen = draw(sites, args.count, seed)
    chosen.sort(key=lambda s: (s[0], s[1]))
    out = [f"# generated by scripts/mutation/generate.py --seed {seed} --count {args.count}"
           f"{' --no-headers' if args.no_headers else ''} --folders {' '.join(args.folders)}",
           f"# seed: {seed}", f"# sites: {len(sites)}", ""]
    for k, (rel, no, op, line, new) in enumerate(chosen, 1):
        frm, to = line.strip(), new.strip()
        nth = occurrence(texts[rel], frm, no)
        out += [f"id: g{seed}-{k:03d}-{op}", f"file: {rel}", f"breaks: {op} at line {no}",
                f"from: {frm}", f"to: {to}", f"nth: {nth}", ""]
    text = "\n".join(out)
    if args.out == "-":
        sys.stdout.write(text)
    else:
        Path(args.out).write_text(text, encoding="utf-8")
    print(f"seed {seed}: {len(chosen)} mutants of {len(sites)} sites", file=sys.stderr)


if __name__ == "__main__":
    main()
