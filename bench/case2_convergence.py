#!/usr/bin/env python3
"""Convergence of the paper's Example 3, case 2 under mesh refinement (issue 17).

    case2_convergence.py --exe SPALLBAR [--work DIR] [--cells 19,95,190,380,760]
                         [--rules accelerate,delay,min] [--policies above,fragment]
                         [--events admissible|paper|none] [--window 1e-3] [--table OUT.md]
                         [--jobs 2] [--horizons 0.1,0.2,0.6] [--perturb 1e-6,1e-4,1e-2]
                         [--perturb-cells 380] [--reuse]

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

--horizons: the same distances and orders over [0, T] for each T (the window means up to T).
--perturb: the sensitivity of the same quantity to the data: each combination is run again at
--perturb-cells with the load's p0 scaled by 1 + eps for each eps, and the distance of its
window means to the unperturbed run's is given over each horizon. Where a perturbation of
the data far below the mesh's error moves the result as much as a mesh refinement, the
distance between meshes measures that sensitivity, not the discretisation.
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
from cli_case2 import distance, means_to as window_means   # window means, L1 distance  # noqa: E402


def deck_text(cells, timing, shift, events, eps=0.0):
    """input/example3_case2's deck at this mesh, rule and policy, history every step,
    with &run events unless events == 'none'; the load's p0 scaled by 1 + eps."""
    text = BODY.format(title=f"h/{cells}, {timing}/{shift}", timing=timing, shift=shift,
                       model="half-mass", cells=cells)
    if eps:
        assert "p0       = 0.1e6" in text
        text = text.replace("p0       = 0.1e6", f"p0       = {0.1e6 * (1.0 + eps)!r}")
    extra = "  history_every = 1\n" + ("" if events == "none" else f"  events = '{events}'\n")
    return "\n".join(l for l in text.splitlines() if not l.strip().startswith("profile_times")) \
        .replace("&run\n", "&run\n" + extra, 1) + "\n"


def run_one(exe, work, cells, timing, shift, events, eps=0.0, reuse=False):
    name = f"{timing}_{shift}_h{cells}" + (f"_p{eps:g}" if eps else "")
    deck = os.path.join(work, name + ".nml")
    if reuse and os.path.exists(os.path.join(work, name + ".evt")):
        nev = sum(1 for l in open(os.path.join(work, name + ".evt")) if l.startswith(" "))
        return name, 0, "", float("nan"), nev
    with open(deck, "w") as f:
        f.write(deck_text(cells, timing, shift, events, eps))
    t0 = time.perf_counter()
    p = subprocess.run([exe, deck, "-q"], cwd=work, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    nev = sum(1 for l in open(os.path.join(work, name + ".evt")) if l.startswith(" "))
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
    ap.add_argument("--horizons", default="")
    ap.add_argument("--perturb", default="")
    ap.add_argument("--perturb-cells", type=int, default=380)
    ap.add_argument("--reuse", action="store_true",
                    help="take the outputs already in --work (run times shown as nan)")
    a = ap.parse_args(argv[1:])
    exe = os.path.abspath(a.exe)
    os.makedirs(a.work, exist_ok=True)
    cells = [int(c) for c in a.cells.split(",")]
    combos = [(r, p) for r in a.rules.split(",") for p in a.policies.split(",")]
    jobs = [(exe, a.work, c, r, p, a.events) for (r, p) in combos for c in cells]
    perturb = [float(e) for e in a.perturb.split(",") if e]
    jobs += [(exe, a.work, a.perturb_cells, r, p, a.events, e) for (r, p) in combos
             for e in perturb]
    if perturb and a.perturb_cells not in cells:
        jobs += [(exe, a.work, a.perturb_cells, r, p, a.events) for (r, p) in combos]
    res = {}
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        for name, rc, err, wall, nev in ex.map(lambda j: run_one(*j, reuse=a.reuse) if len(j) == 7
                                                       else run_one(*j, 0.0, a.reuse), jobs):
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
    means = {}

    def means_of(name, t_max):
        if name not in means:
            h = his(os.path.join(a.work, name + ".his"))
            means[name] = (h["t"], h["reaction_bottom"])
        return window_means(*means[name], a.window, t_max)

    for t_max in [float(x) for x in a.horizons.split(",") if x]:
        lines += ["", f"Over [0, {t_max:g} s]: distances between successive meshes and orders", "",
                  "| rule / policy | " + " | ".join(f"h/{c1}-h/{c2}" for c1, c2 in
                                                     zip(cells, cells[1:])) + " | orders |",
                  "|---" * (len(cells) + 1) + "|"]
        for r, p in combos:
            hs = [means_of(f"{r}_{p}_h{c}", t_max) for c in cells]
            d = [distance(hs[k], hs[k + 1]) for k in range(len(cells) - 1)]
            orders = [math.log(d[k] / d[k + 1]) / math.log(cells[k + 2] / cells[k + 1])
                      if d[k + 1] > 0 else float("inf") for k in range(len(d) - 1)]
            lines.append(f"| {r} / {p} | " + " | ".join(f"{x:.4f}" for x in d) + " | "
                         + ", ".join(f"{o:.2f}" for o in orders) + " |")
    if perturb:
        hz = [float(x) for x in a.horizons.split(",") if x] or [0.6]
        lines += ["", f"Sensitivity at h/{a.perturb_cells}: distance to the unperturbed run when "
                  "the load's p0 is scaled by 1 + eps, over [0, T]", "",
                  "| rule / policy | eps | " + " | ".join(f"T = {t:g} s" for t in hz) + " |",
                  "|---" * (len(hz) + 2) + "|"]
        for r, p in combos:
            base = f"{r}_{p}_h{a.perturb_cells}"
            for e in perturb:
                lines.append(f"| {r} / {p} | {e:g} | " + " | ".join(
                    f"{distance(means_of(base + f'_p{e:g}', t), means_of(base, t)):.2e}"
                    for t in hz) + " |")
    text = "\n".join(lines)
    print(text)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
