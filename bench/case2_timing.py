#!/usr/bin/env python3
"""Run time of the paper's Example 3, case 2 at h/190 for several builds (issue 17: "case 2's
run time at h/190 before and after, not more than 1.5x").

    case2_timing.py [--repeats 25] [--work DIR] LABEL=SPALLBAR [LABEL=SPALLBAR ...]

Runs input/example3_case2/accelerate_{above,fragment}_h190.nml (history every step, a row
per event) with each program, interleaved (repeat 1: every deck with every program, then
repeat 2, ...), so that the load of a shared machine falls on all of them alike. Prints,
per program and deck, the median and the minimum of the wall time of the process (start-up
and deck reading included) and of the run's own time ("N steps in T s": stepping and
outputs), and the ratios of the medians to the first program's. Every run writes its
outputs under WORK (default: a temporary folder, removed at the end).

To build an old revision beside the work tree: git worktree add /tmp/wt-base REV, then
cmake -S /tmp/wt-base -B /tmp/wt-base/build/release -G Ninja -DCMAKE_BUILD_TYPE=Release
-DSPALLBAR_BUILD_TESTING=OFF -DCMAKE_Fortran_COMPILER=gfortran and cmake --build that
folder (the same flags as make build).
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECKS = {d: os.path.join(ROOT, "input", "example3_case2", f"accelerate_{d}_h190.nml")
         for d in ("above", "fragment")}
LOOP_RE = re.compile(r"steps in +([-+0-9.Ee]+) s")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("programs", nargs="+", help="LABEL=PATH of a spallbar executable")
    ap.add_argument("--repeats", type=int, default=25)
    ap.add_argument("--work", default=None)
    a = ap.parse_args(argv)
    progs = [p.split("=", 1) for p in a.programs]
    if any(len(p) != 2 for p in progs):
        ap.error("give each program as LABEL=PATH")
    work = a.work or tempfile.mkdtemp(prefix="case2_timing_")
    os.makedirs(work, exist_ok=True)
    times = {}
    try:
        for _ in range(a.repeats):
            for deck, path in DECKS.items():
                for label, exe in progs:
                    t0 = time.perf_counter()
                    r = subprocess.run([exe, path, "--output", os.path.join(work, label + "_" +
                                        deck)], capture_output=True, text=True)
                    wall = time.perf_counter() - t0
                    if r.returncode != 0:
                        sys.exit(f"{label} on {deck}: exit {r.returncode}\n{r.stderr}")
                    m = LOOP_RE.search(r.stdout + r.stderr)
                    loop = float(m.group(1)) if m else float("nan")
                    times.setdefault((deck, label), []).append((wall, loop))
    finally:
        if a.work is None:
            shutil.rmtree(work, ignore_errors=True)
    print(f"{'deck':9s} {'program':12s} {'wall med':>9s} {'wall min':>9s} {'run med':>9s} "
          f"{'run min':>9s} {'wall/1st':>9s} {'run/1st':>8s}   ({a.repeats} repeats, s)")
    for deck in DECKS:
        ref = times[(deck, progs[0][0])]
        ref_wall = statistics.median(w for w, _ in ref)
        ref_loop = statistics.median(l for _, l in ref)
        for label, _ in progs:
            v = times[(deck, label)]
            walls = [w for w, _ in v]
            loops = [l for _, l in v]
            print(f"{deck:9s} {label:12s} {statistics.median(walls):9.4f} {min(walls):9.4f} "
                  f"{statistics.median(loops):9.4f} {min(loops):9.4f} "
                  f"{statistics.median(walls) / ref_wall:9.2f} "
                  f"{statistics.median(loops) / ref_loop:8.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
