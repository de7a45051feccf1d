#!/usr/bin/env python3
"""spallbar-compare (issue 20): verdicts, measures and exit statuses.

  * a run against a closed form: a bar with a fixed bottom under a step load on its free top
    has the base reaction 2 p0 on (L/a, 3L/a] and 0 on (3L/a, 5L/a], period 4L/a (at
    dx = a dt the lattice reproduces it at the row times); the closed form as a plain
    headerless table passes, and a closed form of the wrong period fails, naming the column;
  * a column changed by 1e-3 fails at the default rtol (exit 1, the column named, the
    others pass), passes with --rtol 1e-2; an identical file passes every column;
  * the tube: a curve shifted by 2 ms fails without --time-tol, passes with --time-tol 3e-3
    and reports the shift it needed (2e-3), fails with --time-tol 1e-3;
  * a candidate shorter than the reference fails (points outside its range);
  * bad input (missing file, a row of words, a decreasing abscissa, no common column, a
    negative tolerance, an unknown --column): exit 2, one line, no report written.

usage: cli_compare.py SPALLBAR SPALLBAR_COMPARE WORKDIR
"""
import math
import os
import shutil
import subprocess
import sys

from clitools import Checks, run

FIXED = """&run t_end = 1.0e-2, title = 'fixed bar under a step load' /
&mesh cells = 50 /
&segments n = 1, length = 1.0, young = 1e9, density = 1000 /
&ends top = 'free', bottom = 'fixed' /
&load kind = 'power', p0 = 1e6, exponent = 0 /
"""


def compare(tool, args, cwd):
    return subprocess.run([sys.executable, tool] + args, cwd=cwd, capture_output=True,
                          text=True, timeout=120, stdin=subprocess.DEVNULL)


def history_times(path):
    return [float(l.split()[0]) for l in open(path) if l.strip() and l.startswith(" ")]


def fixed_bar_reaction(t, p0=1e6, transit=1e-3, period_transits=4):
    """2 p0 on (L/a, 3L/a] of each period 4L/a, else 0 (t on the grid of dt = L/a / 50)."""
    k = round(t / (transit / 50)) % (50 * period_transits)
    return 2 * p0 if 51 <= k <= 150 else 0.0


def closed_form(exe, tool, work, check):
    with open(os.path.join(work, "fixed.nml"), "w") as f:
        f.write(FIXED)
    r = run(exe, ["fixed.nml", "--quiet"], work)
    check(r.returncode == 0, f"fixed bar run: exit {r.returncode} {r.stderr!r}")
    times = history_times(os.path.join(work, "fixed.his"))
    with open(os.path.join(work, "exact.txt"), "w") as f:
        f.write("# the fixed bar's base reaction, closed form: t [s], R [Pa]\n")
        for t in times:
            f.write(f"{t!r} {fixed_bar_reaction(t)!r}\n")
    r = compare(tool, ["exact.txt", "fixed.his", "--column", "reaction_bottom"], work)
    check(r.returncode == 0 and "PASS: 1 columns" in r.stdout,
          f"closed form: exit {r.returncode}\n{r.stdout}{r.stderr}")
    print("ok   closed form (fixed bar, 501 points): " + r.stdout.splitlines()[-2])
    with open(os.path.join(work, "wrong.txt"), "w") as f:
        for t in times:   # a period of 6 L/a instead of 4
            f.write(f"{t!r} {fixed_bar_reaction(t, period_transits=6)!r}\n")
    r = compare(tool, ["wrong.txt", "fixed.his", "--column", "2:reaction_bottom"], work)
    check(r.returncode == 1 and "FAIL: 1 of 1 columns outside the tolerance: 2:reaction_bottom"
          in r.stdout, f"wrong closed form: exit {r.returncode}\n{r.stdout}{r.stderr}")
    print("ok   a wrong period fails: " + r.stdout.splitlines()[-1])


def changed_column(tool, work, check):
    src = os.path.join(work, "fixed.his")
    lines = open(src).read().splitlines(keepends=True)
    names = [l for l in lines if l.startswith("#")][-1][1:].split()
    j = names.index("e_kin")
    out = []
    for l in lines:
        if not l.startswith(" "):           # '#' lines, the column-name first line
            out.append(l)
            continue
        w = l.split()
        w[j] = repr(float(w[j]) * (1 + 1e-3))
        out.append(" ".join(w) + "\n")
    with open(os.path.join(work, "changed.his"), "w") as f:
        f.writelines(out)
    r = compare(tool, ["fixed.his", "changed.his", "--report", "rep.md"], work)
    failed = [l for l in r.stdout.splitlines() if l.startswith("FAIL")]
    ncol = len([l for l in open(os.path.join(work, "fixed.his")) if not l.startswith("#")][0].split()) - 1
    check(r.returncode == 1 and failed == [f"FAIL: 1 of {ncol} columns outside the tolerance: e_kin"],
          f"changed e_kin: exit {r.returncode} {failed}\n{r.stderr}")
    row = [l for l in r.stdout.splitlines() if l.startswith("| e_kin |")]
    check(len(row) == 1 and abs(float(row[0].split("|")[4]) - 1e-3) < 1e-9,
          f"changed e_kin: max rel error {row}")
    check(open(os.path.join(work, "rep.md")).read() == r.stdout, "--report differs from stdout")
    print("ok   " + failed[0] if failed else "FAIL changed column")
    r = compare(tool, ["fixed.his", "changed.his", "--rtol", "1e-2", "--quiet"], work)
    check(r.returncode == 0 and r.stdout == "", f"--rtol 1e-2: exit {r.returncode}")
    r = compare(tool, ["fixed.his", "fixed.his", "--quiet"], work)
    check(r.returncode == 0, f"identical: exit {r.returncode}")
    print("ok   --rtol 1e-2 passes; an identical file passes")


def tube(tool, work, check):
    t = [k * 1e-4 for k in range(201)]
    with open(os.path.join(work, "ref.txt"), "w") as f:
        f.write("t y\n")
        for x in t:
            f.write(f"{x!r} {math.sin(2 * math.pi * x / 0.01)!r}\n")
    with open(os.path.join(work, "shifted.txt"), "w") as f:
        f.write("t y\n")
        for x in [k * 1e-4 for k in range(-40, 241)]:
            f.write(f"{x!r} {math.sin(2 * math.pi * (x - 2e-3) / 0.01)!r}\n")
    r0 = compare(tool, ["ref.txt", "shifted.txt", "--rtol", "1e-3"], work)
    r1 = compare(tool, ["ref.txt", "shifted.txt", "--rtol", "1e-3", "--time-tol", "3e-3"], work)
    r2 = compare(tool, ["ref.txt", "shifted.txt", "--rtol", "1e-3", "--time-tol", "1e-3"], work)
    check(r0.returncode == 1, f"shifted, no tube: exit {r0.returncode}")
    check(r1.returncode == 0, f"shifted, tube 3e-3: exit {r1.returncode}\n{r1.stdout}")
    check(r2.returncode == 1, f"shifted, tube 1e-3: exit {r2.returncode}")
    row = [l for l in r1.stdout.splitlines() if l.startswith("| y |")]
    shift = float(row[0].split("|")[8]) if row else -1
    check(abs(shift - 2e-3) < 1e-6, f"tube: largest shift {shift}, expected 2e-3")
    print(f"ok   tube: a 2 ms shift fails bare and with 1 ms, passes with 3 ms (shift {shift:g})")
    with open(os.path.join(work, "short.txt"), "w") as f:
        f.write("t y\n")
        for x in t[:150]:
            f.write(f"{x!r} {math.sin(2 * math.pi * x / 0.01)!r}\n")
    r = compare(tool, ["ref.txt", "short.txt"], work)
    check(r.returncode == 1 and "51 points outside the candidate's range" in r.stdout,
          f"short candidate: exit {r.returncode}\n{r.stdout}")
    print("ok   a shorter candidate fails (51 points outside its range)")


def bad_input(tool, work, check):
    with open(os.path.join(work, "words.txt"), "w") as f:
        f.write("t y\n0 1\nfoo bar\n")
    with open(os.path.join(work, "back.txt"), "w") as f:
        f.write("t y\n0 1\n2 1\n1 1\n")
    with open(os.path.join(work, "other.txt"), "w") as f:
        f.write("t z\n0 1\n1 1\n")
    cases = ((["nope.txt", "ref.txt"], "nope.txt: cannot read"),
             (["words.txt", "ref.txt"], "words.txt: line 3: not a row of numbers"),
             (["back.txt", "ref.txt"], "back.txt: the abscissa (t) decreases"),
             (["other.txt", "ref.txt"], "the two tables share no column name"),
             (["ref.txt", "ref.txt", "--rtol", "-1"], "--rtol must be a finite number >= 0"),
             (["ref.txt", "ref.txt", "--column", "q"], "--column q: the reference has no column"),
             (["ref.txt"], "the following arguments are required"))
    for args, expect in cases:
        if os.path.exists(os.path.join(work, "bad.md")):
            os.remove(os.path.join(work, "bad.md"))
        r = compare(tool, args + ["--report", "bad.md"], work)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(lines) == 1 and lines[0].startswith("spallbar-compare: ")
              and expect in lines[0], f"{args}: exit {r.returncode} {r.stderr!r}")
        check(not os.path.exists(os.path.join(work, "bad.md")), f"{args}: wrote the report")
        print(f"ok   bad input {args[0]}: {lines[0] if lines else ''}")


def main():
    exe, tool, work = sys.argv[1], sys.argv[2], sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    closed_form(exe, tool, work, check)
    changed_column(tool, work, check)
    tube(tool, work, check)
    bad_input(tool, work, check)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
