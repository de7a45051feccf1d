#!/usr/bin/env python3
"""Progress in a batch log (issue 21): when stderr is not a terminal, a line of its own every
--progress SECONDS (default 30; 0 none), with the share done, the speed, the time to go, the
step and the time; --quiet silences it; a bad value is exit 2 with one line. A sweep: a line
'N of M cases' every SECONDS and at the end. In a log of stdout and stderr together the
run's header comes first.

The first line within 10 s whatever a step costs (issue 32): on a mesh of 1e6 cells, where
1024 steps take seconds to minutes, the first line of the default --progress 30 comes at
5 s of stepping (it came at 30 s), and with --progress 1 after a second, before step 1024
(the clock was looked at only every 1024 steps before); both within 10 s of the start.

usage: cli_progress.py SPALLBAR WORKDIR
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time

from clitools import Checks, run

# (400 000 steps: long enough for several lines at 0.05 s also where the characteristic steps
# take them, 2 us a step in Debug; 80 000 gave one line on a fast machine)
DECK = """&run t_end = 1.0e-1, title = 'progress', history_every = 1000 /
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
SHORT = DECK.replace("t_end = 1.0e-1", "t_end = 5.0e-4")
# 1e6 cells: a step takes tens of ms in Release, more in Debug, so that 1024 steps are far
# beyond 5 s; t_end is a day of steps (the run is stopped by SIGTERM after its first line)
BIG = """&run t_end = 1.0e-3, title = 'big', history_every = 100000 /
&mesh cells = 1000000 /
&segments n = 1, length = 5.0, young = 200e9, density = 7850 /
&load kind = 'power', p0 = 1e8, t_k = 1e-6 /
"""
LINE = re.compile(r"^spallbar: +(\d+\.\d)%  +\S+ steps/s  ETA +\S+ s  \(step (\d+) of (\d+), "
                  r"t = +\S+ s, \S+ s wall\)$")


def first_line(exe, args, work):
    """Start the run, wait for its first stderr line that is no warning (120 s at most), stop
    it (SIGTERM): that line, the seconds since the start, the warnings before it. The steps
    are the lattice's (SPALLBAR_STEPPING=lattice): this is about steps that take long, and
    the characteristic steps (spb_ring) take the big intact bar's 1e6 steps in seconds."""
    t0 = time.monotonic()
    env = dict(os.environ, SPALLBAR_STEPPING="lattice")
    p = subprocess.Popen([exe] + args, cwd=work, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True, env=env)
    watchdog = threading.Timer(120.0, p.kill)
    watchdog.start()
    warnings = []
    line = p.stderr.readline().rstrip("\n")
    while line.startswith("spallbar: warning: "):
        warnings.append(line)
        line = p.stderr.readline().rstrip("\n")
    wall = time.monotonic() - t0
    p.send_signal(signal.SIGTERM)
    p.communicate()
    watchdog.cancel()
    return line, wall, warnings


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
    check(all(m.group(3) == "400000" for m in parsed if m), "--progress: total steps")
    print(f"ok   --progress 0.05: {len(lines)} lines, e.g. {lines[0] if lines else ''}")
    r = run(exe, ["p.nml", "--progress", "0.05", "--quiet"], work)
    check(r.returncode == 0 and r.stderr == "", f"--quiet: {r.stderr[:200]!r}")
    with open(os.path.join(work, "short.nml"), "w") as f:
        f.write(SHORT)
    r = run(exe, ["short.nml"], work)
    check(r.returncode == 0 and r.stderr == "", f"default 30 s on a short run: {r.stderr[:200]!r}")
    print("ok   --quiet and a run shorter than 5 s: nothing on stderr")
    with open(os.path.join(work, "big.nml"), "w") as f:
        f.write(BIG)
    for args, lo, hi in (([], 5.0, 9.0), (["--progress", "1"], 1.0, 6.0)):
        line, wall, warnings = first_line(exe, ["big.nml"] + args, work)
        # the estimate's warning first (1e12 cell-steps: hours)
        check(len(warnings) == 1 and "&mesh cells = 1000000 and &run t_end" in warnings[0],
              f"big mesh {args}: warnings {warnings}")
        m = LINE.match(line)
        check(m is not None, f"big mesh {args}: first stderr line {line!r}")
        if m:
            step = int(m.group(2))
            said = float(re.search(r"([0-9.]+) s wall\)$", line).group(1))
            # with --progress 1 the line comes at the first look at the clock after 1 s:
            # before step 1024 (where the clock was looked at first before)
            check(lo <= said <= hi and (step < 1024 or not args),
                  f"big mesh {args}: first line at {said} s wall, step {step}: {line!r}")
            print(f"ok   1e6 cells {args or 'default'}: the first line {wall:.1f} s after the "
                  f"start, at {said} s of the run, step {step}")
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
