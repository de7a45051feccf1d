#!/usr/bin/env python3
"""Progress in a batch log (issue 21): when stderr is not a terminal, a line of its own every
--progress SECONDS (default 30; 0 none), with the share done, the speed, the time to go, the
step and the time; --quiet silences it; a bad value is exit 2 with one line.

usage: cli_progress.py SPALLBAR WORKDIR
"""
import os
import re
import shutil
import sys

from clitools import Checks, run

DECK = """&run t_end = 2.0e-2, title = 'progress', history_every = 1000 /
&mesh cells = 4000 /
&segments n = 1, length = 1.0, young = 1e9, density = 1000 /
&load kind = 'power', p0 = 1e6, t_k = 1e-4 /
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
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
