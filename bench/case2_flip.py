#!/usr/bin/env python3
"""How far a perturbation that moves an event by a step carries in Example 3, case 2 (issue 17).

    case2_flip.py --exe SPALLBAR [--work DIR] [--cells 95,190,380,760,1520]
                  [--eps 1e-9,1e-7,1e-6,1e-5] [--rule accelerate] [--policy above] [--jobs 2]

For each mesh and each eps, the deck of input/example3_case2 (history every step) is run with
the load's p0 and with p0 (1 + eps), and the 1 ms window means of the base reaction are
compared over [0, 0.6 s]: d_k = |a_k - b_k| / mean |a|. While no event changes its step the
response is linear (the distance over the run is about 0.6 eps, a single window up to about
5 eps); once one does, the difference grows. Printed per mesh and eps: the start of the
first window whose centred 5 ms running mean of d_k exceeds max(1e-4, 20 eps), so up to 2 ms
before the first window that departs ('linear' if none does), and the relative L1 distance
over the run (sum |a - b| / sum |a|). The runs' .evt, .prf and .frg files are deleted (only
the history is read).
"""
import argparse
import concurrent.futures as cf
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from case2_convergence import deck_text, his, distance, window_means   # noqa: E402

WINDOW = 1.0e-3
T_END = 0.6
THRESHOLD = 1.0e-4


def run_one(exe, work, cells, rule, policy, eps):
    """Run one deck; its output prefix."""
    name = f"{rule}_{policy}_h{cells}_e{eps:g}"
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(deck_text(cells, rule, policy, "admissible", eps))
    p = subprocess.run([exe, name + ".nml", "-q"], cwd=work, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"{name}: exit {p.returncode} {p.stderr.strip()[:200]}")
    for ext in (".evt", ".prf", ".frg"):
        if os.path.exists(os.path.join(work, name + ext)):
            os.remove(os.path.join(work, name + ext))
    return name


def first_departure(a, b, eps):
    """Start [s] of the first window whose centred 5-window running mean of |a - b| / mean|a|
    exceeds max(THRESHOLD, 20 eps) (above the linear response), or None."""
    limit = max(THRESHOLD, 20.0 * eps)
    scale = sum(abs(x) for x in a) / len(a)
    d = [abs(x - y) / scale for x, y in zip(a, b)]
    for k in range(len(d)):
        lo, hi = max(0, k - 2), min(len(d), k + 3)
        if sum(d[lo:hi]) / (hi - lo) > limit:
            return k * WINDOW
    return None


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--work", default="case2_flip_work")
    ap.add_argument("--cells", default="95,190,380,760,1520")
    ap.add_argument("--eps", default="1e-9,1e-7,1e-6,1e-5")
    ap.add_argument("--rule", default="accelerate")
    ap.add_argument("--policy", default="above")
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args(argv[1:])
    exe = os.path.abspath(a.exe)
    os.makedirs(a.work, exist_ok=True)
    cells = [int(c) for c in a.cells.split(",")]
    eps = [float(e) for e in a.eps.split(",")]
    jobs = [(c, e) for c in cells for e in [0.0] + eps]
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        list(ex.map(lambda j: run_one(exe, a.work, j[0], a.rule, a.policy, j[1]), jobs))

    def means(c, e):
        h = his(os.path.join(a.work, f"{a.rule}_{a.policy}_h{c}_e{e:g}.his"))
        return window_means(h["t"], h["reaction_bottom"], WINDOW, T_END)

    print(f"Example 3 case 2, {a.rule}/{a.policy}: p0 (1 + eps) against p0, 1 ms means of the "
          f"base reaction; first time the 5 ms running mean of the difference exceeds "
          f"max({THRESHOLD:g}, 20 eps) of the mean reaction; distance over [0, {T_END:g} s]\n")
    print("| eps | " + " | ".join(f"h/{c}" for c in cells) + " |")
    print("|---" * (len(cells) + 1) + "|")
    for e in eps:
        cols = []
        for c in cells:
            base, pert = means(c, 0.0), means(c, e)
            t = first_departure(base, pert, e)
            dist = distance(pert, base)
            cols.append(f"linear ({dist:.1e})" if t is None else f"{t:.2f} s; {dist:.1e}")
        print(f"| {e:g} | " + " | ".join(cols) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
