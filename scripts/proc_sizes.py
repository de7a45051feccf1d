#!/usr/bin/env python3
"""Sizes of the Fortran procedures in src/ (lines from the procedure statement to its end,
internal procedures included in their host and listed on their own).

    proc_sizes.py [SRC_DIR] [--top N] [--max LINES]

Prints the largest procedures; with --max, exit 1 when one is longer (issue 18: 120)."""
import argparse
import os
import re
import sys

START = re.compile(r"^\s*(?:(?:pure|elemental|recursive|impure|module|integer|real|logical|"
                   r"character|type|class|complex)\s*(?:\([^)]*\))?\s*)*"
                   r"(subroutine|function)\s+(\w+)", re.IGNORECASE)
END = re.compile(r"^\s*end\s*(subroutine|function)\b", re.IGNORECASE)


def procedures(path):
    stack, out = [], []
    for k, line in enumerate(open(path, encoding="utf-8", errors="replace")):
        code = line.split("!")[0]
        if END.match(code):
            name, start = stack.pop()
            out.append((k - start + 1, path, name, start + 1))
        elif START.match(code) and not re.match(r"^\s*end\b", code, re.IGNORECASE):
            stack.append((START.match(code).group(2), k))
    return out


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("src", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", "src"))
    ap.add_argument("--top", type=int, default=15)
    ap.add_argument("--max", type=int)
    a = ap.parse_args(argv[1:])
    rows = []
    for d, _, files in os.walk(a.src):
        for f in sorted(files):
            if f.endswith((".f90", ".F90")):
                rows += procedures(os.path.join(d, f))
    rows.sort(reverse=True)
    for n, path, name, line in rows[:a.top]:
        print(f"{n:5d}  {os.path.relpath(path, a.src)}:{line}  {name}")
    over = [r for r in rows if a.max and r[0] > a.max]
    print(f"{len(rows)} procedures; {len(over)} over {a.max} lines" if a.max else f"{len(rows)} procedures")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
