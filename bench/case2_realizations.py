#!/usr/bin/env python3
"""Mesh distances of Example 3, case 2 over realizations of the data (issue 17, convergence).

    case2_realizations.py --exe SPALLBAR [--work DIR] [--cells 19,95,190,380,760]
                          [--rule accelerate] [--policy above] [--events admissible]
                          [--eps 0,1e-5,2e-5,3e-5,4e-5,5e-5,6e-5,7e-5] [--horizons 0.1,0.3,0.6]
                          [--window 1e-3] [--jobs 2]

bench/case2_convergence.py compares one run per mesh. Over the whole run that one run is a
single draw: a change of the load's p0 by one part in 1e5 (a hundred times below the mesh's
error over [0, 0.1 s]) moves the later bouncing by a step here and there, and with it the
distance between two meshes. This script runs every mesh once per eps (p0 scaled by 1 + eps)
and gives, over [0, T] for each horizon T: the relative L1 distance of the base reaction's
window means between successive meshes, its mean, spread, minimum and maximum over the
realizations, the observed orders of the mean distances (as in case2_convergence.py), the
spread within one mesh (mean distance between two of its realizations: the floor below which
a mesh distance says nothing about the discretisation) and the distances of the ensemble
means. Exit 0.
"""
import argparse
import concurrent.futures as cf
import itertools
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from case2_convergence import deck_text, his, distance, window_means   # noqa: E402


def run_one(exe, work, cells, timing, shift, events, eps):
    """Run one realization (kept if its history exists); the output prefix."""
    name = f"h{cells}_e{eps:g}"
    if not os.path.exists(os.path.join(work, name + ".his")):
        with open(os.path.join(work, name + ".nml"), "w") as f:
            f.write(deck_text(cells, timing, shift, events, eps))
        p = subprocess.run([exe, name + ".nml", "-q"], cwd=work, capture_output=True, text=True)
        if p.returncode != 0:
            print(f"warning: {name}: exit {p.returncode} {p.stderr.strip()[:120]}")
        # only the history is read; the events file of a fine 'fragment' run is ~1 GB
        for ext in (".evt", ".xt", ".h5"):
            if os.path.exists(os.path.join(work, name + ext)):
                os.remove(os.path.join(work, name + ext))
    return name


def mean_sd(xs):
    m = sum(xs) / len(xs)
    return m, math.sqrt(sum((x - m) ** 2 for x in xs) / len(xs))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", required=True, help="the spallbar program")
    ap.add_argument("--work", default="case2_realizations_work", help="folder for decks and outputs")
    ap.add_argument("--cells", default="19,95,190,380,760", help="the mesh sequence (cells)")
    ap.add_argument("--rule", default="accelerate", help="&run timing")
    ap.add_argument("--policy", default="above", help="&run shift")
    ap.add_argument("--events", default="admissible", help="&run events: admissible or paper")
    ap.add_argument("--eps", default="0,1e-5,2e-5,3e-5,4e-5,5e-5,6e-5,7e-5",
                    help="the realizations: p0 scaled by 1 + eps")
    ap.add_argument("--horizons", default="0.1,0.3,0.6", help="distances over [0, T] for each T [s]")
    ap.add_argument("--window", type=float, default=1.0e-3, help="window of the means [s]")
    ap.add_argument("--jobs", type=int, default=2, help="runs at once")
    a = ap.parse_args(argv[1:])
    exe = os.path.abspath(a.exe)
    os.makedirs(a.work, exist_ok=True)
    cells = [int(c) for c in a.cells.split(",")]
    epss = [float(e) for e in a.eps.split(",")]
    runs = list(itertools.product(cells, epss))
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        names = dict(zip(runs, ex.map(lambda ce: run_one(exe, a.work, ce[0], a.rule, a.policy,
                                                         a.events, ce[1]), runs)))
    hist = {}
    for key, name in names.items():
        h = his(os.path.join(a.work, name + ".his"))
        hist[key] = (h["t"], h["reaction_bottom"])
    pairs = list(zip(cells, cells[1:]))
    print(f"Base reaction of Example 3 case 2, {a.rule} / {a.policy}, events = '{a.events}': "
          f"relative L1 distance of {a.window * 1e3:g} ms window means between successive "
          f"meshes over {len(epss)} realizations (p0 x (1 + eps), eps = {a.eps})")
    for t_max in [float(x) for x in a.horizons.split(",") if x]:
        w = {k: window_means(*hist[k], a.window, t_max) for k in runs}
        d = [[distance(w[(c1, e)], w[(c2, e)]) for e in epss] for c1, c2 in pairs]
        stats = [mean_sd(x) for x in d]
        orders = [math.log(stats[k][0] / stats[k + 1][0]) / math.log(cells[k + 2] / cells[k + 1])
                  for k in range(len(pairs) - 1)]
        npairs = max(1, len(epss) * (len(epss) - 1) // 2)
        within = [sum(distance(w[(c, e1)], w[(c, e2)])
                      for e1, e2 in itertools.combinations(epss, 2)) / npairs for c in cells]
        ens = {c: [sum(col) / len(epss) for col in zip(*[w[(c, e)] for e in epss])] for c in cells}
        print(f"\nOver [0, {t_max:g} s]\n")
        print("| | " + " | ".join(f"h/{c1}-h/{c2}" for c1, c2 in pairs) + " |")
        print("|---" * (len(pairs) + 1) + "|")
        print("| mean +- sd | " + " | ".join(f"{m:.4f} +- {s:.4f}" for m, s in stats) + " |")
        print("| min | " + " | ".join(f"{min(x):.4f}" for x in d) + " |")
        print("| max | " + " | ".join(f"{max(x):.4f}" for x in d) + " |")
        print("| ensemble means | " + " | ".join(f"{distance(ens[c1], ens[c2]):.4f}"
                                                for c1, c2 in pairs) + " |")
        print("\norders of the mean distances: " + ", ".join(f"{o:.2f}" for o in orders))
        print("spread within a mesh: " + ", ".join(f"h/{c} {x:.4f}" for c, x in zip(cells, within)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
