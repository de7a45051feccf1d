#!/usr/bin/env python3
"""The results archive (issue 20, archive/, scripts/archive.py): every archived deck run again
gives its archived history within the deck's tolerance; a deliberately changed deck is
reported with the columns that moved (exit 1); the round-off measures are compared at their
scale's tolerance (a change of their last bits passes, one of 1e-6 of the scale does not);
re-baselining without a reason is refused.

usage: cli_archive.py SPALLBAR SPALLBAR_COMPARE WORKDIR
"""
import os
import re
import shutil
import subprocess
import sys

from clitools import Checks

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SCRIPT = os.path.join(ROOT, "scripts", "archive.py")


def archive(args):
    return subprocess.run([sys.executable, SCRIPT] + args, capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, timeout=3000)


def main():
    exe, tool, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    r = archive(["check", "--exe", exe, "--compare", tool, "--work", os.path.join(work, "all")])
    print(r.stdout[-3000:], r.stderr)
    decks = [l for l in r.stdout.splitlines() if l.startswith(("PASS ", "MOVED "))]
    check(r.returncode == 0 and len(decks) >= 30 and all(l.startswith("PASS") for l in decks),
          f"archive check: exit {r.returncode}, {len(decks)} decks")
    # a deliberate change of one input: example2's load 1 % higher
    changed = os.path.join(work, "input")
    shutil.copytree(os.path.join(ROOT, "input"), changed)
    deck = os.path.join(changed, "example2.nml")
    text = open(deck).read()
    new = re.sub(r"p0\s*=\s*5\.0e6", "p0 = 5.05e6", text)
    check(new != text, "example2.nml has p0 = 5.0e6")
    open(deck, "w").write(new)
    r = archive(["check", "--exe", exe, "--compare", tool, "--work", os.path.join(work, "one"),
                 "--deck", "example2", "--input", changed])
    print(r.stdout)
    moved = [l for l in r.stdout.splitlines() if l.startswith("MOVED example2.nml:")]
    check(r.returncode == 1 and len(moved) == 1 and "reaction_bottom (" in moved[0]
          and "e_kin (" in moved[0] and "1 moved: example2" in r.stdout,
          f"changed example2: exit {r.returncode}\n{r.stdout}{r.stderr}")
    # the round-off measures are compared at their scale's tolerance (doc/archive.md,
    # "Tolerances"): the sweep table's max_excess 10x and ledger_drift + 1e-12 of the energy
    # scale pass, each at 1e-6 of its scale is reported, and so is a 1e-6 change of a
    # column that is not a round-off measure
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import archive as arc
    ref = os.path.join(ROOT, "archive", "sweeps__weibull_spall.sweep")
    names = arc.columns_of(ref)
    scale = arc.energy_scale(ref, names)
    check(scale > 0 and "max_excess" in names and "ledger_drift" in names,
          f"weibull sweep table: scale {scale}, columns {names}")

    def changed_table(tag, change):
        path = os.path.join(work, f"sweep_{tag}.sweep")
        with open(ref) as f, open(path, "w") as out:
            for line in f:
                words = line.split()
                if line.startswith("#") or len(words) != len(names) or \
                        not words[0].isdigit():
                    out.write(line)
                    continue
                change(words)
                out.write(" ".join(words) + "\n")
        return arc.compare(tool, ref, path, "sweeps__weibull_spall")

    def scaled(column, factor=1.0, add=0.0):
        def change(words):
            k = names.index(column)
            v = float(words[k])
            if v == v:
                words[k] = repr(v * factor + add)
        return change
    for tag, change, moves in (
            ("excess10", scaled("max_excess", factor=10.0), None),
            ("drift_1e-12", scaled("ledger_drift", add=1e-12 * scale), None),
            ("excess_1e-6", scaled("max_excess", add=1e-6), "max_excess ("),
            ("drift_1e-6", scaled("ledger_drift", add=1e-6 * scale), "ledger_drift ("),
            ("ekin_1e-6", scaled("e_kin_end", factor=1.0 + 1e-6), "e_kin_end (")):
        status, moved, _ = changed_table(tag, change)
        ok = (status == 0 and not moved) if moves is None else \
            (status == 1 and len(moved) == 1 and moved[0].startswith(moves))
        check(ok, f"sweep table {tag}: status {status}, moved {moved}")
    # re-baselining needs a reason, and writes nothing without one
    before = open(os.path.join(ROOT, "archive", "CHANGES.md")).read()
    r = archive(["rebaseline", "--exe", exe, "--work", os.path.join(work, "rb")])
    check(r.returncode == 2 and "needs --why" in r.stderr, f"rebaseline without --why: "
          f"exit {r.returncode} {r.stderr!r}")
    check(open(os.path.join(ROOT, "archive", "CHANGES.md")).read() == before,
          "rebaseline without --why changed CHANGES.md")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
