#!/usr/bin/env python3
"""Statistical convergence of the paper's Example 3, case 2 over the whole run (issue 17).

    case2_statistics.py --exe SPALLBAR [--work DIR] [--cells 19,95,190,380,760]
                        [--realizations 32] [--eps 1e-3] [--jobs 2] [--t-end 0.6]
                        [--table OUT.md] [--reuse] [--keep]

After ~0.1 s case 2 is chaotic: a change of the load's p0 by 1e-6 moves the 1 ms window
means of the base reaction over [0, 0.6 s] by 3e-2 at h/380 (bench/case2_convergence.py
--perturb, doc/validation.md), so one trajectory per mesh has no observed order there. This
script measures convergence of statistics that do not depend on the phase of the bouncing:

  ensemble  for every mesh, K realisations with p0 scaled by 1 + eps_k, eps_k the midpoints
            of K equal parts of [-eps, eps] (symmetric: the linear response to eps cancels
            in the mean where the solution is a smooth function of the data, so the mean
            differs from the unperturbed run by O(eps^2) there); the ensemble mean of the
            1 ms window means of reaction_bottom; relative L1 distance between successive
            meshes and the observed order log(d1/d2)/log(r2). Its sampling noise: the
            expected distance of two ensembles of K drawn from the same law, estimated from
            the per-window variances (noise floor, sum sqrt(2/pi) sqrt(s_a^2/K + s_b^2/K)
            / sum |mean_b|), and the standard deviation of the distance over bootstrap
            resamplings of the realisations; the single-trajectory spread (mean absolute
            deviation of a realisation from its ensemble mean, relative) for comparison.
  windows   single (unperturbed) trajectories: window means of 1 ms, 4 h/a (35.7 ms),
            10 ms, 50 ms, and the ensemble mean over 4 h/a windows.
  impulse   the base impulse I(t) = -i_support (history column), sampled every 1 ms:
            relative L1 distance and relative max distance, on the unperturbed run and
            on the ensemble mean. I(t) = I_drive(t) + J(t) with I_drive the exact impulse
            of gravity and the load (mesh independent) and J = p_shift - (momentum -
            momentum(0)) the part the dynamics decides; the distances of I and J differ only
            in the normalisation (the same differences), so the orders agree, but a
            relative distance of I is small mostly because I_drive dominates it; the J
            rows give the honest relative size.

Also: the ensemble-mean distances by time span ([0, 0.1], [0.1, 0.25], [0.25, T]) and the
neighbour ratio of the finest ensemble (how independent the realisations are: the noise
floor and the bootstrap assume independence, so they are optimistic when it is < 1).

Prints Markdown tables (distances between successive meshes, observed orders), the noise
levels and the run times; --table also writes them. Plain Python (no numpy).
Outputs (.his/.evt/.prf/.frg) are deleted after each run unless --keep; the reduced data
of each run is kept in WORK/*.json (--reuse takes them instead of running again).
"""
import argparse
import concurrent.futures as cf
import json
import math
import os
import random
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))
from make_case2_decks import BODY          # the decks of input/example3_case2/  # noqa: E402
from cli_case2 import means_to             # window means up to t_max  # noqa: E402

H = 0.95                                   # bar height [m]
A = (20.0e6 / 1765.8) ** 0.5               # wave speed [m/s]
P0 = 0.1e6                                 # load amplitude [Pa]
WIDTHS = {"1 ms": 1.0e-3, "4 h/a": 4.0 * H / A, "10 ms": 1.0e-2, "50 ms": 5.0e-2}
SAMPLE = 1.0e-3                            # impulse sampling interval [s]


def deck_text(cells, eps=0.0, t_end=0.6):
    """bench/case2_convergence.py's deck (default rules accelerate/above, events
    'admissible', history every step) with p0 scaled by 1 + eps."""
    text = BODY.format(title=f"h/{cells}, accelerate/above", timing="accelerate",
                       shift="above", model="half-mass", cells=cells)
    if eps:
        assert "p0       = 0.1e6" in text
        text = text.replace("p0       = 0.1e6", f"p0       = {P0 * (1.0 + eps)!r}")
    if t_end != 0.6:
        text = text.replace("t_end         = 0.6", f"t_end         = {t_end!r}")
    extra = "  history_every = 1\n  events = 'admissible'\n"
    return "\n".join(l for l in text.splitlines() if not l.strip().startswith("profile_times")) \
        .replace("&run\n", "&run\n" + extra, 1) + "\n"


def sample(t, y, dt, t_max):
    """y linearly interpolated at dt, 2 dt, ... up to t_max."""
    out, j = [], 0
    n = int(round(t_max / dt))
    for k in range(1, n + 1):
        tk = k * dt
        while j + 1 < len(t) - 1 and t[j + 1] < tk:
            j += 1
        if tk >= t[-1]:
            out.append(y[-1])
            continue
        w = (tk - t[j]) / (t[j + 1] - t[j])
        out.append((1.0 - w) * y[j] + w * y[j + 1])
    return out


def reduce_history(path, t_end):
    cols = ("t", "reaction_bottom", "i_support", "i_gravity", "i_ends", "p_shift", "momentum")
    idx, data = None, {c: [] for c in cols}
    with open(path) as f:
        for line in f:
            if line.startswith("# t "):
                names = line[2:].split()
                idx = [names.index(c) for c in cols]
            elif line.startswith(" ") and line.strip():
                w = line.split()
                for c, i in zip(cols, idx):
                    data[c].append(float(w[i]))
    t, r = data["t"], data["reaction_bottom"]
    imp = [-x for x in data["i_support"]]
    m0 = data["momentum"][0]
    jdyn = [ps - (m - m0) for ps, m in zip(data["p_shift"], data["momentum"])]
    drive = [g + e for g, e in zip(data["i_gravity"], data["i_ends"])]
    return {"means": {name: means_to(t, r, w, t_end) for name, w in WIDTHS.items()},
            "impulse": sample(t, imp, SAMPLE, t_end),
            "jdyn": sample(t, jdyn, SAMPLE, t_end),
            "drive": sample(t, drive, SAMPLE, t_end),
            "t_last": t[-1], "rows": len(t)}


def run_one(exe, work, cells, k, eps, t_end, reuse, keep):
    name = f"h{cells}_" + ("ref" if k < 0 else f"k{k:03d}")
    js = os.path.join(work, name + ".json")
    if reuse and os.path.exists(js):
        with open(js) as f:
            d = json.load(f)
        if d["eps"] == eps and d["t_end"] == t_end:
            return cells, k, d
    deck = os.path.join(work, name + ".nml")
    with open(deck, "w") as f:
        f.write(deck_text(cells, eps, t_end))
    t0 = time.perf_counter()
    p = subprocess.run([exe, deck, "--output", os.path.join(work, name), "--quiet"],
                       capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise SystemExit(f"{name}: exit {p.returncode}: {p.stderr.strip()[:200]}")
    d = reduce_history(os.path.join(work, name + ".his"), t_end)
    nev = None
    if keep:
        nev = sum(1 for l in open(os.path.join(work, name + ".evt")) if l.startswith(" "))
    else:
        for ext in (".his", ".evt", ".prf", ".frg", ".lock"):
            try:
                os.remove(os.path.join(work, name + ext))
            except FileNotFoundError:
                pass
    d.update(eps=eps, t_end=t_end, wall=wall, events=nev)
    with open(js, "w") as f:
        json.dump(d, f)
    return cells, k, d


# ---------------------------------------------------------------------------- statistics

def dist(a, b):
    """Relative L1 distance sum |a - b| / sum |b|."""
    n = min(len(a), len(b))
    return sum(abs(a[i] - b[i]) for i in range(n)) / sum(abs(b[i]) for i in range(n))


def dist_max(a, b):
    n = min(len(a), len(b))
    return max(abs(a[i] - b[i]) for i in range(n)) / max(abs(b[i]) for i in range(n))


def mean(rows):
    return [sum(c) / len(c) for c in zip(*rows)]


def var(rows):
    m = mean(rows)
    n = len(rows)
    return [sum((x - mk) ** 2 for x in c) / (n - 1) for c, mk in zip(zip(*rows), m)]


def orders(d, cells):
    return [math.log(d[k] / d[k + 1]) / math.log(cells[k + 2] / cells[k + 1])
            if d[k] > 0 and d[k + 1] > 0 else float("nan") for k in range(len(d) - 1)]


def fmt(xs, f="{:.4f}"):
    return ", ".join(f.format(x) for x in xs)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--work", default="case2_statistics_work")
    ap.add_argument("--cells", default="19,95,190,380,760")
    ap.add_argument("--realizations", type=int, default=32)
    ap.add_argument("--eps", type=float, default=1.0e-3,
                    help="half-width of the relative perturbation of p0")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--t-end", type=float, default=0.6)
    ap.add_argument("--bootstrap", type=int, default=200)
    ap.add_argument("--table")
    ap.add_argument("--reuse", action="store_true", help="take WORK/*.json of earlier runs")
    ap.add_argument("--keep", action="store_true", help="keep the run outputs")
    a = ap.parse_args(argv[1:])
    t_start = time.perf_counter()
    exe = os.path.abspath(a.exe)
    os.makedirs(a.work, exist_ok=True)
    cells = [int(c) for c in a.cells.split(",")]
    K = a.realizations
    eps = [a.eps * (2.0 * (k + 0.5) / K - 1.0) for k in range(K)]
    jobs = [(exe, a.work, c, -1, 0.0, a.t_end, a.reuse, a.keep) for c in reversed(cells)]
    jobs += [(exe, a.work, c, k, eps[k], a.t_end, a.reuse, a.keep)
             for c in reversed(cells) for k in range(K)]      # the longest runs first
    res = {}
    with cf.ProcessPoolExecutor(a.jobs) as ex:
        for c, k, d in ex.map(run_one, *zip(*jobs)):
            res[(c, k)] = d
    pairs = [f"h/{c1}-h/{c2}" for c1, c2 in zip(cells, cells[1:])]
    L = [f"Example 3 case 2, default rules (accelerate/above, events 'admissible'), over "
         f"[0, {a.t_end:g} s]: relative distances between successive meshes and observed "
         f"orders; ensemble of K = {K} runs per mesh with p0 (1 + eps_k), eps_k spread "
         f"symmetrically over [-{a.eps:g}, {a.eps:g}]", "",
         "| measure | " + " | ".join(pairs) + " | observed orders |",
         "|---" * (len(pairs) + 2) + "|"]

    def row(label, d):
        L.append(f"| {label} | " + " | ".join(f"{x:.4f}" for x in d) + " | "
                 + fmt(orders(d, cells), "{:.2f}") + " |")

    def ens(c, key, sub=None):
        return [res[(c, k)][key][sub] if sub else res[(c, k)][key] for k in range(K)]

    def ref(c, key, sub=None):
        return res[(c, -1)][key][sub] if sub else res[(c, -1)][key]

    pair_idx = list(zip(cells, cells[1:]))
    # single trajectories
    for wname in WIDTHS:
        row(f"one run, reaction, {wname} windows, L1",
            [dist(ref(c1, "means", wname), ref(c2, "means", wname)) for c1, c2 in pair_idx])
    row("one run, base impulse I(t), L1", [dist(ref(c1, "impulse"), ref(c2, "impulse"))
                                           for c1, c2 in pair_idx])
    row("one run, base impulse I(t), max", [dist_max(ref(c1, "impulse"), ref(c2, "impulse"))
                                            for c1, c2 in pair_idx])
    row("one run, J = I - I_drive, L1", [dist(ref(c1, "jdyn"), ref(c2, "jdyn"))
                                         for c1, c2 in pair_idx])
    # ensembles
    em = {}
    for key, sub in (("means", "1 ms"), ("means", "4 h/a"), ("impulse", None), ("jdyn", None)):
        em[(key, sub)] = {c: mean(ens(c, key, sub)) for c in cells}
    d_ens = {}
    for key, sub, label in (("means", "1 ms", "ensemble mean, reaction, 1 ms windows, L1"),
                            ("means", "4 h/a", "ensemble mean, reaction, 4 h/a windows, L1"),
                            ("impulse", None, "ensemble mean, base impulse I(t), L1"),
                            ("jdyn", None, "ensemble mean, J = I - I_drive, L1")):
        d_ens[(key, sub)] = [dist(em[(key, sub)][c1], em[(key, sub)][c2]) for c1, c2 in pair_idx]
        row(label, d_ens[(key, sub)])
    row("ensemble mean, base impulse I(t), max",
        [dist_max(em[("impulse", None)][c1], em[("impulse", None)][c2]) for c1, c2 in pair_idx])

    # noise of the ensemble distances
    rng = random.Random(12345)
    L += ["", f"Sampling noise of the ensemble distances (K = {K}): noise floor = the expected "
          "distance of two ensembles drawn from the same law (from the per-window variances); "
          f"bootstrap sd over {a.bootstrap} resamplings of the realisations; spread = mean "
          "|realisation - ensemble mean| of the finer mesh, relative (one trajectory's "
          "scatter)", "",
          "| measure | quantity | " + " | ".join(pairs) + " |", "|---" * (len(pairs) + 2) + "|"]
    for key, sub, label in (("means", "1 ms", "reaction, 1 ms"), ("means", "4 h/a",
                            "reaction, 4 h/a"), ("impulse", None, "impulse I"),
                            ("jdyn", None, "J = I - I_drive")):
        floor, sd, spread, ratio = [], [], [], []
        for (c1, c2), d in zip(pair_idx, d_ens[(key, sub)]):
            x1, x2 = ens(c1, key, sub), ens(c2, key, sub)
            v1, v2, m2 = var(x1), var(x2), em[(key, sub)][c2]
            norm = sum(abs(x) for x in m2)
            floor.append(sum(math.sqrt(2.0 / math.pi * (p + q) / K) for p, q in zip(v1, v2))
                         / norm)
            boots = []
            for _ in range(a.bootstrap):
                b1 = mean([x1[rng.randrange(K)] for _ in range(K)])
                b2 = mean([x2[rng.randrange(K)] for _ in range(K)])
                boots.append(dist(b1, b2))
            mb = sum(boots) / len(boots)
            sd.append(math.sqrt(sum((b - mb) ** 2 for b in boots) / (len(boots) - 1)))
            spread.append(sum(sum(abs(x[i] - m2[i]) for i in range(len(m2))) for x in x2)
                          / K / norm)
            ratio.append(d / floor[-1])
        L.append(f"| {label} | noise floor | " + " | ".join(f"{x:.4f}" for x in floor) + " |")
        L.append(f"| {label} | bootstrap sd | " + " | ".join(f"{x:.4f}" for x in sd) + " |")
        L.append(f"| {label} | distance / floor | " + " | ".join(f"{x:.1f}" for x in ratio)
                 + " |")
        L.append(f"| {label} | spread | " + " | ".join(f"{x:.4f}" for x in spread) + " |")
    # where in time the ensemble means differ, and how independent the realisations are
    spans = [(0.0, 0.1), (0.1, 0.25), (0.25, a.t_end)]
    L += ["", "Ensemble mean of the 1 ms window means by time span: relative L1 distance between "
          "successive meshes; last column: neighbour ratio of the finest mesh over the last span "
          "= mean |x_k - x_k+1| / mean |x_j - x_k| over all pairs (1: the realisations are "
          "independent; << 1: they depend smoothly on eps and the noise floor above is "
          "optimistic)", "",
          "| span [s] | " + " | ".join(pairs) + " | orders | neighbour ratio |",
          "|---" * (len(pairs) + 3) + "|"]
    m1 = em[("means", "1 ms")]
    for t0, t1 in spans:
        i0, i1 = int(round(t0 / 1e-3)), int(round(t1 / 1e-3))
        d = [dist(m1[c1][i0:i1], m1[c2][i0:i1]) for c1, c2 in pair_idx]
        nb = ""
        if (t0, t1) == spans[-1]:
            xs = [x[i0:i1] for x in ens(cells[-1], "means", "1 ms")]

            def l1(u, v):
                return sum(abs(p - q) for p, q in zip(u, v))
            near = sum(l1(xs[k], xs[k + 1]) for k in range(K - 1)) / (K - 1)
            allp = sum(l1(xs[j], xs[k]) for j in range(K) for k in range(j + 1, K)) \
                / (K * (K - 1) / 2)
            nb = f"{near / allp:.2f}"
        L.append(f"| {t0:g}-{t1:g} | " + " | ".join(f"{x:.4f}" for x in d) + " | "
                 + fmt(orders(d, cells), "{:.2f}") + f" | {nb} |")
    walls = {c: [res[(c, k)]["wall"] for k in [-1] + list(range(K))] for c in cells}
    L += ["", "Run time per run [s] (mean): " + ", ".join(
        f"h/{c} {sum(walls[c]) / len(walls[c]):.2f}" for c in cells)
        + f"; total wall {time.perf_counter() - t_start:.0f} s with --jobs {a.jobs}"
        + (" (--reuse: run times of the runs that made the .json)" if a.reuse else "")]
    text = "\n".join(L)
    print(text)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
