#!/usr/bin/env python3
"""Convergence of the paper's Example 3, case 2 under mesh refinement (issue 17).

    case2_convergence.py --exe SPALLBAR [--work DIR] [--cells 19,95,190,380,760]
                         [--rules accelerate,delay,min] [--policies above,fragment]
                         [--events admissible|paper|none] [--window 1e-3] [--table OUT.md]
                         [--jobs 2]

Writes the decks of input/example3_case2/ (zero tensile strength, the bar on the rigid
base under the top load) at each cell count for every timing rule x shift policy, runs
them, and compares the base reaction (history column reaction_bottom) of successive meshes:
the mean over consecutive windows of the given width (1 ms by default), then the relative
L1 distance sum |a_k - b_k| / sum |b_k| of the finer mesh's window means. The observed order
between three successive meshes is log(d1/d2)/log(r2) with d1, d2 the distances of the two
successive pairs and r2 the refinement of the second (for the doubling sequence 95, 190,
380, 760: log2(d1/d2)). Prints a Markdown table with the distances, the orders, the event
counts and the run times; exit 0. --events none leaves &run events out (for a program from
before the variable existed).
"""
import argparse
import concurrent.futures as cf
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))
from make_case2_decks import BODY          # the decks of input/example3_case2/  # noqa: E402
from cli_event_layer import his            # the history reader by column names  # noqa: E402


def deck_text(cells, timing, shift, events):
    """input/example3_case2's deck at this mesh, rule and policy, history every step,
    with &run events unless events == 'none'."""
    text = BODY.format(title=f"h/{cells}, {timing}/{shift}", timing=timing, shift=shift,
                       model="half-mass", cells=cells)
    extra = "  history_every = 1\n" + ("" if events == "none" else f"  events = '{events}'\n")
    return "\n".join(l for l in text.splitlines() if not l.strip().startswith("profile_times")) \
        .replace("&run\n", "&run\n" + extra, 1) + "\n"


def window_means(t, r, width, t_end):
    sums, counts = {}, {}
    for tk, rk in zip(t, r):
        k = int(tk / width)
        if (k + 1) * width <= t_end + 1e-12:
            sums[k] = sums.get(k, 0.0) + rk
            counts[k] = counts.get(k, 0) + 1
    return [sums[k] / counts[k] for k in sorted(sums)]


def distance(a, b):
    n = min(len(a), len(b))
    return sum(abs(a[k] - b[k]) for k in range(n)) / sum(abs(b[k]) for k in range(n))


def run_one(exe, work, cells, timing, shift, events):
    name = f"{timing}_{shift}_h{cells}"
    deck = os.path.join(work, name + ".nml")
    with open(deck, "w") as f:
        f.write(deck_text(cells, timing, shift, events))
    t0 = time.perf_counter()
    p = subprocess.run([exe, deck, "-q"], cwd=work, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    nev = sum(1 for l in open(os.path.join(work, name + ".evt")) if not l.startswith("#"))
    return name, p.returncode, p.stderr.strip(), wall, nev


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--work", default="case2_convergence_work")
    ap.add_argument("--cells", default="19,95,190,380,760")
    ap.add_argument("--rules", default="accelerate,delay,min")
    ap.add_argument("--policies", default="above,fragment")
    ap.add_argument("--events", default="admissible")
    ap.add_argument("--window", type=float, default=1.0e-3)
    ap.add_argument("--table")
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args(argv[1:])
    exe = os.path.abspath(a.exe)
    os.makedirs(a.work, exist_ok=True)
    cells = [int(c) for c in a.cells.split(",")]
    combos = [(r, p) for r in a.rules.split(",") for p in a.policies.split(",")]
    jobs = [(exe, a.work, c, r, p, a.events) for (r, p) in combos for c in cells]
    res = {}
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        for name, rc, err, wall, nev in ex.map(lambda j: run_one(*j), jobs):
            res[name] = (rc, err, wall, nev)
    lines = [f"Base reaction of Example 3 case 2, events = '{a.events}': relative L1 distance of "
             f"{a.window * 1e3:g} ms window means between successive meshes, observed order, "
             "events and run time (Release)", "",
             "| rule / policy | " + " | ".join(f"h/{c1}-h/{c2}" for c1, c2 in zip(cells, cells[1:]))
             + " | orders | events (" + ", ".join(f"h/{c}" for c in cells) + ") | time [s] |",
             "|---" * (len(cells) + 3) + "|"]
    for r, p in combos:
        hs, bad = [], []
        for c in cells:
            name = f"{r}_{p}_h{c}"
            rc, err, wall, nev = res[name]
            if rc != 0:
                bad.append(f"h/{c}: exit {rc} {err[:80]}")
            h = his(os.path.join(a.work, name + ".his"))
            hs.append(window_means(h["t"], h["reaction_bottom"], a.window, 0.6))
        d = [distance(hs[k], hs[k + 1]) for k in range(len(cells) - 1)]
        orders = []
        for k in range(len(d) - 1):
            ratio = cells[k + 2] / cells[k + 1]
            orders.append(math.log(d[k] / d[k + 1]) / math.log(ratio) if d[k + 1] > 0 else float("inf"))
        ev = [res[f"{r}_{p}_h{c}"][3] for c in cells]
        tm = [res[f"{r}_{p}_h{c}"][2] for c in cells]
        lines.append(f"| {r} / {p} | " + " | ".join(f"{x:.3f}" for x in d) + " | "
                     + ", ".join(f"{o:.2f}" for o in orders) + " | "
                     + ", ".join(str(e) for e in ev) + " | " + ", ".join(f"{x:.2f}" for x in tm)
                     + " |" + ("" if not bad else "  FAILED: " + "; ".join(bad)))
    text = "\n".join(lines)
    print(text)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
