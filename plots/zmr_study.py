#!/usr/bin/env python3
"""The Zhou-Molinari-Ramesh benchmark: fragment size of a uniformly expanding cohesive bar.

A bar of ZMR's ceramic (E = 275 GPa, rho = 2750 kg/m^3, R = 300 MPa, Gc = 100 N/m) is
stretched at a constant rate between two ends that keep their velocity (&ends 'velocity',
&initial strain_rate): stress E rate t everywhere until the first crack (doc/method.md,
"Ends"; "Cohesive cracks"). The scales are s0 = E Gc / R^2 (length), t0 = s0 / c and
rate0 = c R^3 / (E^2 Gc); the normalised rate is rate / rate0. The strength has a small
random spread: a Weibull field per cell of modulus 50 (coefficient of variation 2.5 %)
whose mean is R. For each normalised rate and mesh the realizations run as one &sweep
(MPI ranks with --ranks), and the mean fragment size is the bar length over the fragments
(fractures + 1) of each realization. The bar holds about 60 ZMR fragments; the run ends
at t = t0 (1/rate_n + 30), when no crack completes any more (checked: doubling that adds
none at 0.1 and 100). Theories (all normalised by s0):
  Grady          (24 / rate_n^2)^(1/3)
  Glenn-Chudnovsky (4 / rate_n) sinh(asinh(1.5 rate_n) / 3)
  ZMR's fit      4.5 / (1 + 4.5 rate_n^(2/3))

usage: zmr_study.py [--exe SPALLBAR] [--out DIR] [--rates 0.1,...] [--resolutions 10,20,40]
                    [--realizations K] [--ranks N] [--table MD] [--figure PNG] [--json F]
                    [--distribution 0.3,10] [--duration F]
A resolution r means dx = min(s0, s_ZMR) / r: r cells per cohesive length s0 and per ZMR
fragment, whichever is smaller; --duration scales t_end (default 1). Prints the table; exit 1
when a run failed. A point whose bars did not break within the run has no fragment size: the
figure leaves it out and says so on stderr, 'zmr_study.py: warning: nothing to draw: ...';
the figure is written all the same, with the theory curves, and the exit status stays 0.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time

E, RHO, R, GC = 275e9, 2750.0, 300e6, 100.0
C = math.sqrt(E / RHO)
S0 = E * GC / R**2
T0 = S0 / C
RATE0 = C * R**3 / (E**2 * GC)
MODULUS = 50.0
N_ZMR = 60          # ZMR fragments the bar holds


def zmr(eb):
    return 4.5 / (1.0 + 4.5 * eb**(2.0 / 3.0))


def grady(eb):
    return (24.0 / eb**2)**(1.0 / 3.0)


def glenn_chudnovsky(eb):
    return 4.0 / eb * math.sinh(math.asinh(1.5 * eb) / 3.0)


def deck(eb, res, k, seed=2026, duration=1.0):
    """The sweep deck of one rate and mesh: K realizations of the strength field."""
    s = zmr(eb) * S0
    length = N_ZMR * s
    cells = max(20, int(round(length / (min(S0, s) / res))))
    scale = R / math.gamma(1.0 + 1.0 / MODULUS)
    t_end = duration * (1.0 / eb + 30.0) * T0
    text = (f"&run title = 'ZMR expanding bar, rate {eb:g} rate0, dx = min(s0, s_ZMR)/{res:g}',\n"
            f"     t_end = {t_end!r}, history_every = 1000000, warnings = .false. /\n"
            f"&mesh cells = {cells} /\n"
            f"&segments n = 1, length = {length!r}, young = {E!r}, density = {RHO!r},\n"
            f"  strength = {R!r}, fracture_energy = {GC!r} /\n"
            "&ends top = 'velocity', bottom = 'velocity' /\n"
            f"&initial strain_rate = {eb * RATE0!r} /\n"
            f"&strength_field kind = 'weibull', modulus = {MODULUS!r}, scale = {scale!r} /\n"
            f"&sweep realizations = {k}, seed = {seed}, bins = 1000 /\n")
    return text, length, cells


def read_sweep(path):
    names, rows = None, []
    for line in open(path):
        if line.startswith("#"):
            continue
        if names is None:
            names = line.split()
            continue
        if line.strip():
            rows.append([float(x) for x in line.split()])
    return [dict(zip(names, r)) for r in rows]


def run_point(exe, out, eb, res, k, ranks, duration=1.0):
    text, length, cells = deck(eb, res, k, duration=duration)
    name = f"zmr_{eb:g}_{res:g}"
    path = os.path.join(out, name + ".nml")
    with open(path, "w") as f:
        f.write(text)
    for ext in (".sweep", "_sweep.h5", ".lock"):
        if os.path.exists(os.path.join(out, name + ext)):
            os.remove(os.path.join(out, name + ext))
    cmd = [exe, "--sweep", path, "-o", os.path.join(out, name), "-q"]
    if ranks > 1:
        cmd = [shutil.which("mpiexec") or "mpiexec", "--oversubscribe", "--allow-run-as-root",
               "-np", str(ranks)] + cmd
    w0 = time.time()
    with open(os.devnull, "w") as null:
        p = subprocess.Popen(cmd, stdout=null, stderr=subprocess.PIPE, text=True)
        err = p.stderr.read()
        _, status, ru = os.wait4(p.pid, 0)
    wall = time.time() - w0
    # the CPU time of mpiexec's children (the ranks) is in its own rusage: wait4 reports the
    # process and the children it waited for
    cpu = ru.ru_utime + ru.ru_stime
    if os.waitstatus_to_exitcode(status) != 0:
        print(f"zmr_study.py: {name}: exit {os.waitstatus_to_exitcode(status)}: "
              f"{err.strip()[:300]}", file=sys.stderr)
        return None
    rows = read_sweep(os.path.join(out, name + ".sweep"))
    if not any(row["fractures"] > 0 for row in rows):
        print(f"zmr_study.py: warning: nothing to draw: rate {eb:g}, dx = min(s0, s)/{res:g}: "
              f"no bar broke by t_end (point left out)", file=sys.stderr)
        return {"rate": eb, "res": res, "empty": True}
    sizes = [length / (row["fractures"] + 1.0) / S0 for row in rows]
    mean = sum(sizes) / len(sizes)
    std = math.sqrt(sum((x - mean)**2 for x in sizes) / max(1, len(sizes) - 1))
    e_coh = sum(row["e_cohesive"] for row in rows) / len(rows)
    return {"rate": eb, "res": res, "cells": cells, "dx_over_s0": length / cells / S0,
            "length_over_s0": length / S0, "realizations": len(rows), "mean": mean,
            "sem": std / math.sqrt(len(sizes)), "std": std, "sizes": sizes,
            "cracks": sum(row["cracks"] for row in rows) / len(rows),
            "fractures": sum(row["fractures"] for row in rows) / len(rows),
            # dissipated energy per unit volume, over Gc / s0 (= R^2 / E)
            "e_volume": e_coh / length / (GC / S0),
            "cpu": cpu, "wall": wall, "name": name}


def table(results, resolutions):
    by = {(r["rate"], r["res"]): r for r in results}
    rates = sorted({r["rate"] for r in results})
    lines = ["| rate/rate0 | " + " | ".join(f"s/s0, dx = min(s0, s)/{x:g}" for x in resolutions)
             + " | ZMR fit | Grady | Glenn-Chudnovsky | cracks / fractures (finest) | "
             "dissipated / (Gc/s0) per volume (finest) |",
             "|---" * (len(resolutions) + 6) + "|"]
    for eb in rates:
        cells = []
        for x in resolutions:
            r = by.get((eb, x))
            cells.append(f"{r['mean']:.3f} ± {r['sem']:.3f}" if r else "—")
        fin = by.get((eb, resolutions[-1]))
        extra = (f"{fin['cracks']:.0f} / {fin['fractures']:.1f}", f"{fin['e_volume']:.3f}") if fin \
            else ("—", "—")
        lines.append(f"| {eb:g} | " + " | ".join(cells) + f" | {zmr(eb):.3f} | {grady(eb):.3f} | "
                     f"{glenn_chudnovsky(eb):.3f} | {extra[0]} | {extra[1]} |")
    return "\n".join(lines)


def figure(results, resolutions, dist, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    xs = [10**(k / 20.0) for k in range(-30, 51)]
    ax.loglog(xs, [zmr(x) for x in xs], "k-", label="ZMR fit 4.5/(1+4.5 ε̄^(2/3))")
    ax.loglog(xs, [grady(x) for x in xs], "k--", label="Grady (24/ε̄²)^(1/3)")
    ax.loglog(xs, [glenn_chudnovsky(x) for x in xs], "k:", label="Glenn–Chudnovsky")
    marks = "os^dv"
    for i, res in enumerate(resolutions):
        rs = sorted((r for r in results if r["res"] == res), key=lambda r: r["rate"])
        ax.errorbar([r["rate"] for r in rs], [r["mean"] for r in rs],
                    yerr=[r["std"] for r in rs], fmt=marks[i % len(marks)], ms=5, capsize=2,
                    label=f"spallbar, dx = min(s0, s)/{res:g}")
    ax.set_xlabel("normalised strain rate ε̇/ε̇0")
    ax.set_ylabel("mean fragment size s/s0")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    for eb in dist:
        rs = [r for r in results if r["rate"] == eb]
        if not rs:
            continue
        fin = max(rs, key=lambda r: r["res"])
        sizes = fin.get("fragment_sizes") or []
        if sizes:
            m = sum(sizes) / len(sizes)
            bx.hist([x / m for x in sizes], bins=30, histtype="step", density=True,
                    label=f"ε̄ = {eb:g} (mean {m:.3f} s0, {len(sizes)} fragments)")
    bx.set_xlabel("fragment size / its mean")
    bx.set_ylabel("probability density")
    if bx.get_legend_handles_labels()[0]:
        bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def fragment_sizes(out, name):
    """Every fragment's length [s0] over a sweep's realizations, at the centre of its bin of
    the sweep's fragment-length histograms (PREFIX_sweep.h5, doc/sweeps.md)."""
    import h5py
    import numpy as np
    with h5py.File(os.path.join(out, name + "_sweep.h5"), "r") as f:
        hist = np.asarray(f["histogram/counts"])
        edges = np.asarray(f["histogram/edges"])
    centres = 0.5 * (edges[1:] + edges[:-1]) / S0
    counts = hist.sum(axis=0) if hist.ndim == 2 else hist
    out_sizes = []
    for c, n in zip(centres, counts.ravel()[:len(centres)]):
        out_sizes += [float(c)] * int(n)
    return out_sizes


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", default="build/release/bin/spallbar")
    ap.add_argument("--out", default="build/release/zmr")
    ap.add_argument("--rates", default="0.1,0.3,1,3,10,30,100")
    ap.add_argument("--resolutions", default="10,20,40")
    ap.add_argument("--realizations", type=int, default=16)
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--distribution", default="0.3,10")
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--table")
    ap.add_argument("--figure")
    ap.add_argument("--json")
    a = ap.parse_args(argv[1:])
    os.makedirs(a.out, exist_ok=True)
    rates = [float(x) for x in a.rates.split(",")]
    resolutions = [float(x) for x in a.resolutions.split(",")]
    dist = [float(x) for x in a.distribution.split(",")] if a.distribution else []
    results, failed = [], 0
    t_all = time.time()
    for eb in rates:
        for res in resolutions:
            r = run_point(os.path.abspath(a.exe), a.out, eb, res, a.realizations, a.ranks,
                          a.duration)
            if r is None:
                failed += 1
                continue
            if r.get("empty"):
                continue
            if eb in dist and res == resolutions[-1]:
                try:
                    r["fragment_sizes"] = fragment_sizes(a.out, r["name"])
                except Exception as exc:   # no HDF5 reader: the distribution is left out
                    print(f"zmr_study.py: {r['name']}: no distribution ({exc})", file=sys.stderr)
            results.append(r)
            print(f"rate {eb:g} res {res:g}: {r['cells']} cells, s/s0 = {r['mean']:.4f} ± "
                  f"{r['sem']:.4f} (ZMR {zmr(eb):.4f}), cracks {r['cracks']:.0f}, fractures "
                  f"{r['fractures']:.1f}, CPU {r['cpu']:.1f} s, wall {r['wall']:.1f} s", flush=True)
    if not results:
        print("zmr_study.py: warning: nothing to draw: no point with a fragment size: only the "
              "theory is drawn", file=sys.stderr)
    cpu = sum(r["cpu"] for r in results)
    text = table(results, resolutions)
    summary = (f"\n{len(results)} points x {a.realizations} realizations on {a.ranks} rank(s): "
               f"CPU {cpu:.1f} s, wall {time.time() - t_all:.1f} s")
    print(text + summary)
    if a.table:
        with open(a.table, "w") as f:
            f.write("<!-- made by plots/zmr_study.py (make fragmentation); do not edit -->\n")
            f.write(text + "\n" + summary.strip() + "\n")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)
    if a.figure:
        figure(results, resolutions, dist, a.figure)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
