#!/usr/bin/env python3
"""FORD-style documentation coverage of the Fortran sources (issue 18): how many procedures
have a `!>` comment above them, how many dummy arguments a `!!` comment on their
declaration line (or the lines that continue it), how many public entities are documented.

    doc_coverage.py [DIR ...] [--list] [--min-args SHARE]

--list prints the undocumented dummy arguments; --min-args: exit 1 when the documented share
of dummy arguments is below SHARE (0..1)."""
import argparse
import os
import re
import sys

PROC = re.compile(r"^\s*(?:(?:pure|elemental|recursive|impure|module|integer|real|logical|"
                  r"character|type|class|complex)\s*(?:\([^)]*\))?\s*)*(subroutine|function)"
                  r"\s+(\w+)\s*\(([^)]*)\)", re.IGNORECASE)


def joined_lines(text):
    """Statements with their continuation lines joined; each with its first line number and
    the comments of all its lines."""
    out, buf, comments, first = [], "", "", None
    for k, line in enumerate(text.splitlines()):
        code, _, comment = line.partition("!")
        if first is None:
            first = k
        buf += code.rstrip().rstrip("&") + " "
        comments += "!" + comment if comment else ""
        if not code.rstrip().endswith("&"):
            out.append((first, buf, comments, line))
            buf, comments, first = "", "", None
    return out


def scan(path, rows):
    lines = open(path, encoding="utf-8", errors="replace").read().splitlines()
    stmts = joined_lines("\n".join(lines))
    for idx, (k, code, comments, raw) in enumerate(stmts):
        m = PROC.match(code)
        if not m or code.strip().lower().startswith("end"):
            continue
        name = m.group(2)
        args = [a.strip().lower() for a in m.group(3).split(",") if a.strip()]
        above = lines[k - 1].strip() if k > 0 else ""
        rows["procs"] += 1
        rows["procs_doc"] += above.startswith("!>") or above.startswith("!!")
        # the declarations that follow, up to the first executable-looking statement
        documented = set()
        for k2, code2, comments2, _ in stmts[idx + 1:idx + 60]:
            if "::" not in code2:
                if re.match(r"^\s*(use|implicit|import)\b", code2, re.I) or not code2.strip():
                    continue
                break
            names = [re.sub(r"\(.*", "", v).strip().lower()
                     for v in code2.split("::", 1)[1].split(",")]
            if "!!" in comments2:
                documented.update(names)
        for a in args:
            rows["args"] += 1
            if a in documented:
                rows["args_doc"] += 1
            else:
                rows["missing"].append(f"{path}:{k + 1} {name}({a})")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dirs", nargs="*", default=["src", "app"])
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--min-args", type=float)
    a = ap.parse_args(argv[1:])
    rows = {"procs": 0, "procs_doc": 0, "args": 0, "args_doc": 0, "missing": []}
    for d in a.dirs:
        for root, _, files in os.walk(d):
            for f in sorted(files):
                if f.endswith(".f90"):
                    scan(os.path.join(root, f), rows)
    if a.list:
        print("\n".join(rows["missing"]))
    print(f"procedures with a !> comment: {rows['procs_doc']} of {rows['procs']}; "
          f"dummy arguments with a !! comment: {rows['args_doc']} of {rows['args']}")
    if a.min_args is not None and rows["args"]:
        return 0 if rows["args_doc"] / rows["args"] >= a.min_args else 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
