#!/usr/bin/env python3
"""Deck fuzzer (issue 9): mutate valid decks into hostile ones and hold spallbar to the
bad-input contract for every one of them:

  * exit status 2 (never 0, never a signal, never another status),
  * exactly one line on stderr, 'spallbar: ' + a message naming the group (&name) and,
    for a mutation of one variable, that variable ('deck' for a file that cannot be read),
  * no Fortran runtime error or warning, no backtrace,
  * no output file left behind (the case's folder holds only its inputs afterwards).

Every mutation is invalid by construction (a wrong type, a value out of its range, a
duplicate, binary junk, an unterminated string or group, ...). The random choices come
from a seeded generator: the same seed gives the same cases (printed on failure).

usage: fuzz_decks.py SPALLBAR WORKDIR [--cases N] [--seed S]
"""
import argparse
import os
import random
import shutil
import stat
import subprocess
import sys

from clitools import Checks

# Valid base decks: (name, [(group, [(variable, value text), ...]), ...], extra files).
# Short runs, so that a mutation the contract does not catch would still end quickly.
BASES = [
    ("two_segments", [
        ("run", [("title", "'fuzz base'"), ("t_end", "2.0e-5"), ("gravity", "0.0"),
                 ("timing", "'accelerate'"), ("shift", "'fragment'"), ("history_every", "1"),
                 ("profile_times", "1.0e-5"), ("energy_guard", "0.01")]),
        ("mesh", [("cells", "10"), ("fit", "'strict'")]),
        ("segments", [("n", "2"), ("length", "0.05, 0.05"), ("young", "200e9, 200e9"),
                      ("density", "8000, 8000"), ("strength", "1.0e7, -1.0"),
                      ("interface", "'bonded'"), ("velocity", "0.0, 0.0")]),
        ("ends", [("top", "'free'"), ("bottom", "'free'")]),
        ("load", [("kind", "'power'"), ("face", "'top'"), ("p0", "1.0e8"), ("t_k", "1.0e-5"),
                  ("exponent", "1.0"), ("t_cut", "1.0e-5")]),
        ("initial", [("state", "'unstressed'")]),
    ], {}),
    ("base_table_hdf5", [
        ("run", [("title", "'fuzz table'"), ("t_end", "2.0e-3"), ("gravity", "9.81"),
                 ("hdf5", ".true."), ("field_every", "5"), ("model", "'half-mass'")]),
        ("mesh", [("cells", "8")]),
        ("segments", [("n", "1"), ("length", "0.4"), ("young", "20e6"),
                      ("density", "1765.8"), ("strength", "0.0")]),
        ("ends", [("top", "'free'"), ("bottom", "'base'")]),
        ("load", [("kind", "'table'"), ("table", "'load.txt'")]),
        ("initial", [("state", "'static'")]),
    ], {"load.txt": "# t [s]  p [Pa]\n0 0\n1e-4 1e5\n5e-4 0\n"}),
    ("dt_dry", [
        ("run", [("t_end", "1.0e-5"), ("timing", "'min'")]),
        ("mesh", [("dt", "1.0e-6"), ("fit", "'stretch'")]),
        ("segments", [("n", "3"), ("length", "0.025, 0.0102, 0.05"),
                      ("young", "200e9, 70e9, 200e9"), ("density", "8000, 2700, 8000"),
                      ("interface", "'dry', 'bonded'"), ("gap", "1.0e-4, 0.0"),
                      ("velocity", "10.0, 0.0, 0.0")]),
        ("ends", [("top", "'free'"), ("bottom", "'fixed'")]),
    ], {}),
]

# variable -> kind ('real', 'int', 'logical', 'word', 'text'), and values out of range
KINDS = {
    "title": "text", "t_end": "real", "gravity": "real", "timing": "word", "shift": "word",
    "history_every": "int", "profile_times": "real", "energy_guard": "real", "cells": "int",
    "fit": "word", "n": "int", "length": "real", "young": "real", "density": "real",
    "strength": "real", "interface": "word", "velocity": "real", "top": "word",
    "bottom": "word", "kind": "word", "face": "word", "p0": "real", "t_k": "real",
    "exponent": "real", "t_cut": "real", "state": "word", "hdf5": "logical",
    "field_every": "int", "model": "word", "table": "text", "dt": "real", "gap": "real",
}
OUT_OF_RANGE = {
    "t_end": ["0.0", "-1.0", "-1e-9"], "history_every": ["0", "-3"],
    "energy_guard": ["-0.5"], "cells": ["0", "-10", "2000000000"],
    "n": ["0", "-1", "101", "5"], "length": ["0.0", "-0.05", "0.0, 0.05", "0.05, -1"],
    "young": ["0.0", "-200e9", "200e9, 0"], "density": ["0", "-8000", "8000, -1"],
    "t_k": ["0.0", "-1.0"], "t_cut": ["-1.0"], "dt": ["-1.0e-6", "0.5"],
    "field_every": ["-1"], "gap": ["-1.0e-4, 0.0"], "profile_times": ["-1.0e-5"],
}
# variables a base deck cannot do without
REQUIRED = {"two_segments": ["t_end", "cells", "length", "young", "density", "p0"],
            "base_table_hdf5": ["t_end", "cells", "length", "young", "density", "table"],
            "dt_dry": ["t_end", "dt", "length", "young", "density"]}
CONTROL = [c for c in range(32) if c not in (9, 10, 13)] + [127]
NONFINITE = ["NaN", "Inf", "-Inf", "+Infinity", "1e999", "-1e999", "nan(0x7)"]


def render(groups):
    lines = []
    for g, items in groups:
        lines.append(f"&{g}")
        lines += [f"  {v} = {t}" for v, t in items]
        lines.append("/")
    return "\n".join(lines) + "\n"


def replace(groups, g, v, text):
    return [(gg, [(vv, text if (gg, vv) == (g, v) else tt) for vv, tt in items])
            for gg, items in groups]


def pick_var(rng, groups, kinds=None):
    cands = [(g, v) for g, items in groups for v, _ in items
             if kinds is None or KINDS[v] in kinds]
    return rng.choice(cands)


def mutations(rng, base):
    """One hostile deck: (label, deck bytes, files, expected group, expected variable)."""
    name, groups, files = base
    files = dict(files)
    kind = rng.choice(["wrong_type", "missing", "duplicate_var", "unknown_group", "unknown_var",
                       "duplicate_group", "out_of_range", "nonfinite", "huge_array",
                       "binary_junk", "unterminated_string", "unterminated_group",
                       "truncated", "long_string", "subscript", "table"])
    if kind == "wrong_type":
        g, v = pick_var(rng, groups, ("real", "int", "logical", "word"))
        k = KINDS[v]
        bad = {"real": ["'abc'", ".true.", "1.2.3", "12abc", "1e", "(1.0, 2.0)"],
               "int": ["1.5", "'x'", ".false.", "3e", "1 2 3 4 5 6 7 8 9"],
               "logical": ["3.5", "'maybe'", "2", "yes"],
               "word": ["'glued'", "42", "'" + "z" * rng.randint(1, 30) + "'", ".true."]}[k]
        return kind, render(replace(groups, g, v, rng.choice(bad))).encode(), files, g, v
    if kind == "missing":
        v = rng.choice(REQUIRED[name])
        g = [gg for gg, items in groups for vv, _ in items if vv == v][0]
        return kind, render([(gg, [(vv, t) for vv, t in items if vv != v])
                             for gg, items in groups]).encode(), files, g, v
    if kind == "duplicate_var":
        g, v = pick_var(rng, groups)
        out = [(gg, items + [(vv, t) for vv, t in items if (gg, vv) == (g, v)])
               for gg, items in groups]
        return kind, render(out).encode(), files, g, v
    if kind == "unknown_group":
        word = rng.choice(["gizmo", "rn", "segment", "mesh2", "Runs", "sweeps", "ending",
                           "x" * rng.randint(1, 40)])
        pos = rng.randint(0, len(groups))
        text = render(groups[:pos]) + f"&{word} a = 1 /\n" + render(groups[pos:])
        return kind, text.encode(), files, word.lower(), None
    if kind == "unknown_var":
        g = rng.choice(groups)[0]
        word = rng.choice(["celz", "tend", "lenght", "youngs", "q", "strength_x", "p00"])
        out = [(gg, items + ([(word, "1")] if gg == g else [])) for gg, items in groups]
        return kind, render(out).encode(), files, g, word
    if kind == "duplicate_group":
        k = rng.randrange(len(groups))
        out = groups[:k + 1] + [groups[k]] + groups[k + 1:]
        return kind, render(out).encode(), files, groups[k][0], None
    if kind == "out_of_range":
        cands = [(g, v) for g, items in groups for v, _ in items if v in OUT_OF_RANGE]
        g, v = rng.choice(cands)
        return kind, render(replace(groups, g, v, rng.choice(OUT_OF_RANGE[v]))).encode(), \
            files, g, v
    if kind == "nonfinite":
        g, v = pick_var(rng, groups, ("real",))
        return kind, render(replace(groups, g, v, rng.choice(NONFINITE))).encode(), files, g, v
    if kind == "huge_array":
        g, v = pick_var(rng, groups, ("real", "int"))
        text = rng.choice([f"{rng.randint(101, 100000)}*1.0",
                           ", ".join(["1.0"] * rng.randint(101, 20000))])
        if v in ("profile_times", "length", "young", "density", "strength", "velocity", "gap"):
            return kind, render(replace(groups, g, v, text)).encode(), files, g, v
        return kind, render(replace(groups, g, v, text)).encode(), files, g, None
    if kind == "binary_junk":
        text = bytearray(render(groups).encode())
        for _ in range(rng.randint(1, 4)):
            text.insert(rng.randrange(len(text) + 1), rng.choice(CONTROL))
        return kind, bytes(text), files, None, None
    if kind == "unterminated_string":
        text = render(groups)
        quotes = [i for i, c in enumerate(text) if c == "'"]
        i = quotes[-1] if rng.random() < 0.5 else quotes[rng.randrange(0, len(quotes), 2)]
        # the deck ends inside the string: nothing after it can close it
        return kind, (text[:i + 1] + "never closed\n").encode(), files, None, None
    if kind == "unterminated_group":
        k = rng.randrange(len(groups))
        text = "".join(render([grp]) if j != k else render([grp])[:-2] + "\n"
                       for j, grp in enumerate(groups))
        return kind, text.encode(), files, groups[k][0], None
    if kind == "truncated":
        text = render(groups)
        last = text.rstrip().rfind("/")
        start = text.rfind("&", 0, last)
        cut = rng.randint(start + 2, last - 1)
        return kind, text[:cut].encode(), files, None, None
    if kind == "long_string":
        g, v = pick_var(rng, groups, ("text", "word"))
        # keywords hold 32 characters, titles and paths 511
        n = rng.choice([33, 100, 600, 5000, 100000] if KINDS[v] == "word" else [512, 5000, 100000])
        return kind, render(replace(groups, g, v, "'" + "w" * n + "'")).encode(), files, g, v
    if kind == "subscript":
        g, v = pick_var(rng, groups, ("real",))
        idx = rng.choice(["0", "101", "1000", "-1", "1:200"])
        out = [(gg, items + ([(f"{v}({idx})", "1.0")] if gg == g else [])) for gg, items in groups]
        return kind, render(out).encode(), files, g, None
    # table: a broken load table on a deck that uses one (else: out of range)
    groups = BASES[1][1]
    files = {"load.txt": rng.choice([
        "0 0\n1e-4\n", "0 0\n1e-4 abc\n", "0 0\n2e-4 1\n1e-4 2\n", "0 0\n1e-4 NaN\n",
        "0 0\n1e-4 1e999\n", "", "# only a comment\n", "-1 0\n1 0\n", "0 0\n\x01\x02 3\n",
        "0 0\n1e-4 1e5\n1e-4 2e5\n1e-4 3e5\n"])}
    if rng.random() < 0.2:
        files = {}
    return kind, render(groups).encode(), files, "load", "table"


def file_cases(work):
    """The deck itself cannot be read: (label, path relative to the case folder)."""
    cases = [("missing_file", "nope.nml"), ("directory", "adir"), ("empty", "empty.nml"),
             ("dev_null", "/dev/null"), ("binary_file", "bin.nml"), ("trailing_slash", "x.nml/")]
    if os.geteuid() != 0:
        cases.append(("unreadable", "locked.nml"))
    return cases


def run_case(exe, folder, deck, timeout=120):
    before = set(os.listdir(folder))
    try:
        r = subprocess.run([exe, deck, "-q"], cwd=folder, capture_output=True, timeout=timeout,
                           stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return None, "", set()
    left = set(os.listdir(folder)) - before
    return r.returncode, r.stderr.decode("utf-8", "replace"), left


def judge(check, label, rc, err, left, group, var):
    lines = err.splitlines()
    ok = True

    def c(cond, what):
        nonlocal ok
        check(cond, f"{label}: {what}; stderr {err[:300]!r}")
        ok = ok and cond
    c(rc is not None, "timed out")
    c(rc == 2, f"exit status {rc}, expected 2")
    c(len(lines) == 1, f"{len(lines)} stderr lines, expected 1")
    c("Fortran runtime" not in err and "Backtrace" not in err, "a Fortran runtime message")
    c(not left, f"left {sorted(left)}")
    if lines:
        first = lines[0]
        c(first.startswith("spallbar: "), "message does not start with 'spallbar: '")
        if group is not None:
            c(f"&{group}" in first.lower(), f"message does not name &{group}")
        else:
            c("&" in first or first.startswith("spallbar: deck"), "message names no group")
        if var is not None:
            c(var.lower() in first.lower(), f"message does not name {var}")
    return ok


def main():
    p = argparse.ArgumentParser()
    p.add_argument("exe")
    p.add_argument("work")
    p.add_argument("--cases", type=int, default=600)
    p.add_argument("--seed", type=int, default=20261122)
    args = p.parse_args()
    exe = os.path.abspath(args.exe)
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    check = Checks()
    rng = random.Random(args.seed)

    # the bases themselves are valid: exit 0 (this keeps the fuzzer honest)
    for name, groups, files in BASES:
        folder = os.path.join(args.work, "base_" + name)
        os.makedirs(folder)
        for f, text in files.items():
            with open(os.path.join(folder, f), "w") as fh:
                fh.write(text)
        with open(os.path.join(folder, "deck.nml"), "w") as fh:
            fh.write(render(groups))
        rc, err, _ = run_case(exe, folder, "deck.nml")
        check(rc == 0, f"base deck {name} must run: exit {rc} {err!r}")

    tally, failed = {}, 0
    for k in range(args.cases):
        base = BASES[rng.randrange(len(BASES))]
        label, text, files, group, var = mutations(rng, base)
        folder = os.path.join(args.work, f"case{k:04d}")
        os.makedirs(folder)
        for f, t in files.items():
            with open(os.path.join(folder, f), "w", encoding="latin-1") as fh:
                fh.write(t)
        with open(os.path.join(folder, "deck.nml"), "wb") as fh:
            fh.write(text)
        rc, err, left = run_case(exe, folder, "deck.nml")
        ok = judge(check, f"case {k} ({label}, base {base[0]}, seed {args.seed})", rc, err,
                   left, group, var)
        tally[label] = tally.get(label, 0) + 1
        if ok:
            shutil.rmtree(folder)
        else:
            failed += 1

    # decks that cannot be read at all
    folder = os.path.join(args.work, "files")
    os.makedirs(os.path.join(folder, "adir"))
    open(os.path.join(folder, "empty.nml"), "w").close()
    with open(os.path.join(folder, "bin.nml"), "wb") as fh:
        fh.write(bytes(random.Random(args.seed).randrange(256) for _ in range(4096)) + b"\x00")
    with open(os.path.join(folder, "locked.nml"), "w") as fh:
        fh.write(render(BASES[0][1]))
    os.chmod(os.path.join(folder, "locked.nml"), 0)
    for label, path in file_cases(folder):
        rc, err, left = run_case(exe, folder, path)
        # an empty deck lacks &run; /dev/null (a device, like a FIFO) is not a deck file
        judge(check, f"file case {label}", rc, err, left,
              "run" if label == "empty" else None, None)
        if label == "dev_null":
            check("spallbar: deck: '/dev/null' is not a regular file" in err,
                  f"file case dev_null: {err!r}")
        tally[label] = 1
    os.chmod(os.path.join(folder, "locked.nml"), stat.S_IRUSR | stat.S_IWUSR)

    total = sum(tally.values())
    print(f"fuzz: {total} hostile decks (seed {args.seed}), {failed} broke the contract")
    print("fuzz: by mutation: " + ", ".join(f"{k} {v}" for k, v in sorted(tally.items())))
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
