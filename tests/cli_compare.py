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
    negative tolerance, an unknown --column): exit 2, one line, no report written;
  * issue 32: a file with a jump (a repeated abscissa) and a .prf of two profile times pass
    against themselves, a jump is compared from both sides (either side wrong fails), the
    blocks of a .prf block by block; --plot or --report into a missing folder is exit 2
    before anything is read; a reference column the candidate lacks is exit 2 naming it
    unless --column leaves it out; a UTF-8 byte-order mark is read as nothing; a 400 % error
    next to a spike of 1e6 or 1e10 fails at the default tolerances; a reference read from a
    FIFO; the peak memory of a ~20 MB comparison stays bounded (streaming).

usage: cli_compare.py SPALLBAR SPALLBAR_COMPARE WORKDIR
"""
import math
import os
import shutil
import subprocess
import sys
import threading

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


def write(work, name, text):
    with open(os.path.join(work, name), "w", encoding="utf-8") as f:
        f.write(text)


def verdict(r):
    """The exit status and the last line of stdout (the PASS or FAIL line)."""
    lines = r.stdout.splitlines()
    return r.returncode, lines[-1] if lines else ""


def jumps(exe, tool, work, check):
    write(work, "j.txt", "0 0\n1 0\n1 1\n2 1\n")
    r = compare(tool, ["j.txt", "j.txt"], work)
    check(verdict(r) == (0, "PASS: 1 columns within the tolerance"),
          f"a jump against itself: {verdict(r)} {r.stderr!r}")
    cases = (("0 0\n1 0\n1 2\n2 1\n", 1, "the right limit wrong"),
             ("0 0\n1 0.5\n1 1\n2 1\n", 1, "the left limit wrong"),
             ("0 0\n2 1\n", 1, "no jump (0.5 at t = 1)"),
             ("0 0\n1 0\n1 1\n1 1\n2 1\n", 0, "the same jump in three rows"))
    for text, status, what in cases:
        write(work, "jc.txt", text)
        r = compare(tool, ["j.txt", "jc.txt"], work)
        row = [l for l in r.stdout.splitlines() if l.startswith("| 2 |")]
        first = row[0].split("|")[9].strip() if row else None
        check(r.returncode == status and first == ("1" if status else ""),
              f"a jump, {what}: exit {r.returncode}, first failure {first!r}\n{r.stdout}")
    # a single reference row at the candidate's jump meets the nearer side (here the left)
    write(work, "single.txt", "0 0\n1 0\n2 1\n")
    r = compare(tool, ["single.txt", "j.txt"], work)
    check(r.returncode == 0, f"a single row at a jump: exit {r.returncode}\n{r.stdout}")
    print("ok   a jump passes against itself; either side wrong fails at the jump")
    with open(os.path.join(work, "prf.nml"), "w") as f:
        f.write(FIXED.replace("t_end = 1.0e-2,", "t_end = 1.0e-2, profile_times = 2.5e-3, 5e-3,"))
    r = run(exe, ["prf.nml", "--quiet"], work)
    check(r.returncode == 0, f"prf run: exit {r.returncode} {r.stderr!r}")
    lines = open(os.path.join(work, "prf.prf")).read().splitlines(keepends=True)
    xs = [l.split()[0] for l in lines if l.startswith(" ")]
    check(len(xs) != len(set(xs)), "the .prf has no repeated abscissa: the check proves nothing")
    r = compare(tool, ["prf.prf", "prf.prf"], work)
    check(verdict(r) == (0, "PASS: 4 columns within the tolerance"),
          f".prf against itself: {verdict(r)} {r.stderr!r}")
    blocks = [k for k, l in enumerate(lines) if l.startswith("# t =")]
    check(len(blocks) == 2, f"the .prf has {len(blocks)} blocks, expected 2")
    row = blocks[1] + 2 + 20      # block 2, a row at an interface
    w = lines[row].split()
    w[3] = repr(float(w[3]) * 1.01 + 1.0)
    write(work, "prf2.prf", "".join(lines[:row]) + " ".join(w) + "\n" + "".join(lines[row + 1:]))
    r = compare(tool, ["prf.prf", "prf2.prf"], work)
    srow = [l for l in r.stdout.splitlines() if l.startswith("| stress |")]
    check(verdict(r)[0] == 1 and srow and srow[0].rstrip("| ").endswith(f"{float(w[0]):.6g} "
                                                                        "(block 2)"),
          f".prf, one stress changed in block 2: {verdict(r)} {srow}")
    write(work, "prf1.prf", "".join(lines[:blocks[1]]))
    r = compare(tool, ["prf.prf", "prf1.prf"], work)
    check(r.returncode == 2 and "prf.prf has 2 blocks (profile times), prf1.prf 1" in r.stderr,
          f".prf, a block fewer: exit {r.returncode} {r.stderr!r}")
    print("ok   a .prf of two profile times passes against itself, is compared block by block")


def refusals(tool, work, check):
    write(work, "ab.txt", "t a b\n0 1 2\n1 1 2\n")
    write(work, "a.txt", "t a\n0 1\n1 1\n")
    cases = ((["j.txt", "j.txt", "--plot", "/nonexistent/x.png"],
              "--plot /nonexistent/x.png: cannot write: no folder /nonexistent"),
             (["j.txt", "j.txt", "--plot", "."], "--plot .: cannot write: it is a folder"),
             (["j.txt", "j.txt", "--plot", "x.png", "--report", "no/r.md"],
              "--report no/r.md: cannot write: no folder"),
             (["nope.txt", "j.txt", "--plot", "/nonexistent/x.png"], "--plot /nonexistent"),
             (["ab.txt", "a.txt"], "the candidate lacks the reference's column b;"))
    for args, expect in cases:
        if os.path.exists(os.path.join(work, "bad.md")):
            os.remove(os.path.join(work, "bad.md"))
        r = compare(tool, args + ["--report", "bad.md"] * ("--report" not in args), work)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(lines) == 1 and expect in lines[0] and r.stdout == "",
              f"{args}: exit {r.returncode} {r.stderr!r}")
        check(not os.path.exists(os.path.join(work, "bad.md")) and
              not os.path.exists(os.path.join(work, "x.png")), f"{args}: wrote a file")
        print(f"ok   {' '.join(args[2:]) or args[0]}: {lines[0] if lines else ''}")
    for args, status in ((["ab.txt", "a.txt", "--column", "a"], 0), (["a.txt", "ab.txt"], 0)):
        r = compare(tool, args, work)
        check(verdict(r) == (status, "PASS: 1 columns within the tolerance"),
              f"{args}: {verdict(r)} {r.stderr!r}")
    print("ok   --column a leaves the missing column out; a candidate's extra column is fine")


def bom(tool, work, check):
    write(work, "bom.txt", "\ufeff0 1\n1 2\n2 3\n")
    write(work, "nobom.txt", "0 1\n1 2\n2 3\n")
    write(work, "bomh.txt", "\ufefft y\n0 1\n1 2\n")
    write(work, "ty.txt", "t y\n0 1\n1 2\n")
    for ref, cand, row in (("bom.txt", "nobom.txt", "| 2 | 3 |"),
                           ("bomh.txt", "ty.txt", "| y | 2 |")):
        r = compare(tool, [ref, cand], work)
        check(r.returncode == 0 and any(l.startswith(row) for l in r.stdout.splitlines()),
              f"a BOM, {ref}: exit {r.returncode}\n{r.stdout}{r.stderr}")
    print("ok   a UTF-8 byte-order mark is read as nothing (before a row, before a header)")


def spike(tool, work, check):
    for height in (1e6, 1e10):
        ref = [1.0 + 0.01 * k for k in range(21)]
        ref[10] = height
        cand = list(ref)
        cand[11] *= 5.0                                   # a 400 % error beside the spike
        write(work, "spike.txt", "".join(f"{k} {v!r}\n" for k, v in enumerate(ref)))
        write(work, "spike_bad.txt", "".join(f"{k} {v!r}\n" for k, v in enumerate(cand)))
        r = compare(tool, ["spike.txt", "spike_bad.txt"], work)
        row = [l for l in r.stdout.splitlines() if l.startswith("| 2 |")]
        check(r.returncode == 1 and row and row[0].split("|")[7].strip() == "1"
              and row[0].split("|")[9].strip() == "11"
              and "atol = 1e-12 of each column's largest |r|" in r.stdout,
              f"a 400 % error beside a spike of {height:g}: exit {r.returncode}\n{r.stdout}")
        r = compare(tool, ["spike.txt", "spike.txt"], work)
        check(r.returncode == 0, f"the spike deck against itself: exit {r.returncode}")
        print(f"ok   a 400 % error beside a spike of {height:g} fails at the defaults")


def fifo(tool, work, check):
    path = os.path.join(work, "ref.fifo")
    os.mkfifo(path)

    def feed():
        with open(path, "w") as f:
            f.write("0 0\n1 0\n1 1\n2 1\n")
    threading.Thread(target=feed, daemon=True).start()
    r = compare(tool, ["ref.fifo", "j.txt"], work)
    check(verdict(r) == (0, "PASS: 1 columns within the tolerance"),
          f"a reference from a FIFO: {verdict(r)} {r.stderr!r}")
    print("ok   a reference from a FIFO (read twice: spooled)")


MEMORY_MB = 60     # the peak RSS allowed comparing ~20 MB (the whole-file reader: ~140 MB)


def memory(tool, work, check):
    names = ["t"] + [f"c{j}" for j in range(15)]
    with open(os.path.join(work, "big.his"), "w") as f, \
            open(os.path.join(work, "big2.his"), "w") as g:
        f.write(" ".join(names) + "\n# a generated history\n# " + " ".join(names) + "\n")
        g.write(" ".join(names) + "\n")
        k = 0
        while f.tell() < 20e6:
            t = (k - k % 3 // 2) * 1e-6       # every third row repeats an abscissa: a jump
            row = " ".join(f"{math.sin(k * 1e-3 * (j + 1)) * 10 ** j:.12E}" for j in range(15))
            f.write(f"{t:.12E} {row}\n")
            g.write(f"{t:.12E} {row}\n")
            k += 1
    size = os.path.getsize(os.path.join(work, "big.his")) / 1e6
    probe = ("import resource, subprocess, sys\n"
             "r = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
             "print(r.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    r = subprocess.run([sys.executable, "-c", probe, sys.executable, tool, "big.his",
                        "big2.his", "--quiet"], cwd=work, capture_output=True, text=True,
                       timeout=600)
    status, kb = (int(w) for w in r.stdout.split())
    check(status == 0 and kb < MEMORY_MB * 1024,
          f"{size:.0f} MB against itself: exit {status}, peak RSS {kb / 1024:.0f} MB "
          f"(bound {MEMORY_MB} MB)")
    print(f"ok   {size:.0f} MB ({k} rows) compared in a peak RSS of {kb / 1024:.0f} MB")


def main():
    exe, tool, work = sys.argv[1], sys.argv[2], sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    closed_form(exe, tool, work, check)
    changed_column(tool, work, check)
    tube(tool, work, check)
    bad_input(tool, work, check)
    jumps(exe, tool, work, check)
    refusals(tool, work, check)
    bom(tool, work, check)
    spike(tool, work, check)
    fifo(tool, work, check)
    memory(tool, work, check)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
