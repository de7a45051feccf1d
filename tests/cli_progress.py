#!/usr/bin/env python3
"""Progress in a batch log (issue 21): when stderr is not a terminal, a line of its own every
--progress SECONDS (default 30; 0 none), with the share done, the speed, the time to go, the
step and the time; --quiet silences it; a bad value is exit 2 with one line. A sweep: a line
'N of M cases' every SECONDS and at the end. In a log of stdout and stderr together the
run's header comes first.

usage: cli_progress.py SPALLBAR WORKDIR
"""
import os
import re
import shutil
import subprocess
import sys

from clitools import Checks, run

DECK = """&run t_end = 2.0e-2, title = 'progress', history_every = 1000 /
&mesh cells = 4000 /
&segments n = 1, length = 1.0, young = 1e9, density = 1000 /
&load kind = 'power', p0 = 1e6, t_k = 1e-4 /
"""
SWEEP = """&run t_end = 2e-3 /
&mesh dt = 1e-6 /
&segments n = 1, length = 1.0, young = 200e9, density = 8000, strength = 3e8 /
&load kind = 'power', p0 = 5e8, t_k = 2e-5 /
&strength_field kind = 'weibull', modulus = 6, scale = 3e8 /
&sweep realizations = 120 /
"""
LINE = re.compile(r"^spallbar: +(\d+\.\d)%  +\S+ steps/s  ETA +\S+ s  \(step (\d+) of (\d+), "
                  r"t = +\S+ s, \S+ s wall\)$")


def main():
    exe, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    with open(os.path.join(work, "p.nml"), "w") as f:
        f.write(DECK)
    r = run(exe, ["p.nml", "--progress", "0.05"], work)
    lines = r.stderr.splitlines()
    parsed = [LINE.match(l) for l in lines]
    check(r.returncode == 0, f"--progress 0.05: exit {r.returncode} {r.stderr[-300:]}")
    check(len(lines) >= 2 and all(parsed), f"--progress 0.05: lines {lines[:3]}")
    steps = [int(m.group(2)) for m in parsed if m]
    check(steps == sorted(steps) and len(set(steps)) == len(steps),
          f"--progress 0.05: steps not increasing {steps}")
    check(all(m.group(3) == "80000" for m in parsed if m), "--progress: total steps")
    print(f"ok   --progress 0.05: {len(lines)} lines, e.g. {lines[0] if lines else ''}")
    r = run(exe, ["p.nml", "--progress", "0.05", "--quiet"], work)
    check(r.returncode == 0 and r.stderr == "", f"--quiet: {r.stderr[:200]!r}")
    r = run(exe, ["p.nml"], work)
    check(r.returncode == 0 and r.stderr == "", f"default 30 s on a short run: {r.stderr[:200]!r}")
    print("ok   --quiet and a run shorter than 30 s: nothing on stderr")
    for bad in ("-1", "x", "1e9"):
        r = run(exe, ["p.nml", "--progress", bad], work)
        e = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(e) == 1 and "--progress needs SECONDS" in e[0],
              f"--progress {bad}: exit {r.returncode} {r.stderr!r}")
    print("ok   --progress -1, x, 1e9: exit 2, one line")
    # a log of stdout and stderr together (Slurm's default): the run's header comes first
    with open(os.path.join(work, "both.log"), "w") as log:
        q = subprocess.run([exe, "p.nml", "--progress", "0.05"], cwd=work, stdout=log,
                           stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, timeout=600)
    both = open(os.path.join(work, "both.log")).read().splitlines()
    check(q.returncode == 0 and both and both[0].startswith("spallbar 0.") and
          any(LINE.match(l) for l in both), f"one log: the header first: {both[:3]}")
    print(f"ok   stdout and stderr in one log: the header first ({both[0] if both else ''})")
    # a sweep in batch: 'spallbar sweep: N of M cases, T s' every SECONDS and at the end
    with open(os.path.join(work, "s.nml"), "w") as f:
        f.write(SWEEP)
    r = run(exe, ["--sweep", "s.nml", "--progress", "0.05"], work)
    lines = r.stderr.splitlines()
    done = [re.match(r"^spallbar sweep: (\d+) of 120 cases, +\S+ s$", l) for l in lines]
    check(r.returncode == 0 and len(lines) >= 2 and all(done) and
          done[-1].group(1) == "120" and "\r" not in r.stderr,
          f"sweep --progress 0.05: exit {r.returncode} {lines[:3]}")
    print(f"ok   sweep --progress 0.05: {len(lines)} lines, the last {lines[-1] if lines else ''}")
    r = run(exe, ["--sweep", "s.nml", "--progress", "0.05", "--quiet"], work)
    check(r.returncode == 0 and r.stderr == "", f"sweep --quiet: {r.stderr[:200]!r}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
