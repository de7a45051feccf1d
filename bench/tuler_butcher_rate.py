#!/usr/bin/env python3
"""Spall strength against loading rate with the Tuler-Butcher criterion (issue 35).

A concrete bar (E = 35 GPa, rho = 2350 kg/m^3, static tensile strength R = 3.5 MPa),
free-free, takes on its top face a symmetric triangular pressure pulse: it rises linearly
to P over the rise time t_r and falls back to 0 over t_r. Its reflection from the free
bottom turns the falling half into tension, which rises at the spall plane at the rate
2 P / t_r. A gauge on the bottom face (&gauges, side irrelevant at an end node) reads the
rear-face velocity, from which the spall strength is read as a lab reads it (Novikov):

    sigma_spall = 1/2 rho c (v_peak - v_pullback)

with v_peak the rear face's first maximum and v_pullback the first minimum after it (the
spall signal turns the velocity back up there), and the strain rate as a lab reads it,
eps_dot = |dv/dt| / (2 c) over the unloading between them. Each rise time is run brittle
(K = 0: the strength criterion alone) and with the Tuler-Butcher damage integral
(&segments damage_integral K, damage_exponent lambda). The table gives, per rise time, the
measured strain rate, the Novikov strength of both runs, its ratio to R (the dynamic
increase factor, DIF), and the closed form for a tension rising at the constant rate
sigma_dot = 2 E eps_dot at a section, R + ((lambda + 1) K sigma_dot)^(1/(lambda+1)).

The pulse amplitude is three times that closed-form strength (so the bar spalls well
inside), the bar 2.5 pulse lengths long, the mesh --cells-per-rise cells per rise time
(the same lattice at every rate: the runs differ only in the ratio of their time scale
to the damage's).

usage: tuler_butcher_rate.py --exe SPALLBAR [--rates 1,3,10,...] [--k 5e7] [--lam 2]
                             [--r 3.5e6] [--cells-per-rise 400] [--work DIR] [--table MD]
Prints a Markdown table (and writes it with --table); exit 1 when a run failed.
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np

E, RHO = 35e9, 2350.0
C = math.sqrt(E / RHO)
Z = RHO * C


def closed_form(r, k, lam, eps_dot):
    """The Tuler-Butcher break stress of a tension rising at 2 E eps_dot [Pa]."""
    if k <= 0.0:
        return r
    return r + ((lam + 1.0) * k * 2.0 * E * eps_dot) ** (1.0 / (lam + 1.0))


def deck(name, t_r, p, cells_per_rise, k, lam, r):
    dt = t_r / cells_per_rise
    n = int(round(2.5 * 2 * cells_per_rise))       # 2.5 pulse lengths (2 t_r each)
    length = n * C * dt
    t_end = (n + 5 * cells_per_rise) * dt
    table = f"{name}.txt"
    dmg = f"  damage_integral = {k!r}\n  damage_exponent = {lam!r}\n" if k > 0 else ""
    text = f"""&run
  title = 'Tuler-Butcher rate study: t_r = {t_r:.4g} s'
  t_end = {t_end!r}
  history_every = 100000
/
&mesh
  dt = {dt!r}
  fit = 'stretch'
/
&segments
  n = 1
  length = {length!r}
  young = {E!r}
  density = {RHO!r}
  strength = {r!r}
{dmg}/
&ends
  top = 'free', bottom = 'free'
/
&load
  kind = 'table', table = '{table}'
/
&gauges
  x = {length!r}
  every = 1
/
"""
    pulse = f"0 0\n{t_r!r} {p!r}\n{2 * t_r!r} 0\n{4 * t_end!r} 0\n"
    return text, table, pulse


def read_gauge(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith(" "):
                rows.append([float(v) for v in line.split()])
    a = np.array(rows)
    return a[:, 0], a[:, 2]


def pullback(t, v):
    """v_peak, v_min, the strain rate over the unloading between them, and whether a
    pull-back (a minimum followed by a rise) was found."""
    # the first local maximum after the pulse arrives (the rise is monotone on the lattice)
    k_peak = int(np.argmax(v > 0.01 * v.max()))
    while k_peak + 1 < len(v) and v[k_peak + 1] >= v[k_peak]:
        k_peak += 1
    v_peak = v[k_peak]
    k = k_peak
    k_min = k_peak
    found = False
    while k + 1 < len(v):
        k += 1
        if v[k] < v[k_min]:
            k_min = k
        elif v[k] > v[k_min] + 0.01 * v_peak:
            found = True
            break
    v_min = v[k_min]
    # the unloading's slope between 90 % and 10 % of the way down to the minimum
    hi = v_peak - 0.1 * (v_peak - v_min)
    lo = v_peak - 0.9 * (v_peak - v_min)
    sel = np.arange(k_peak, k_min + 1)
    sel = sel[(v[sel] <= hi) & (v[sel] >= lo)]
    slope = np.polyfit(t[sel], v[sel], 1)[0] if len(sel) > 2 else float("nan")
    return v_peak, v_min, abs(slope) / (2.0 * C), found


def one(exe, work, name, t_r, p, cells_per_rise, k, lam, r):
    text, table, pulse = deck(name, t_r, p, cells_per_rise, k, lam, r)
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(text)
    with open(os.path.join(work, table), "w") as f:
        f.write(pulse)
    run = subprocess.run([exe, name + ".nml", "-q"], cwd=work, capture_output=True,
                         text=True)
    if run.returncode != 0:
        print(f"{name}: exit {run.returncode}: {run.stderr.strip()}", file=sys.stderr)
        return None
    t, v = read_gauge(os.path.join(work, name + ".gau"))
    v_peak, v_min, eps_dot, found = pullback(t, v)
    return dict(sigma=0.5 * RHO * C * (v_peak - v_min), eps_dot=eps_dot, found=found)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--rates", default="1,3,10,30,100,300,1000",
                    help="nominal strain rates [1/s] that set the rise times")
    ap.add_argument("--k", type=float, default=5.0e7, help="damage_integral K [Pa^lambda s]")
    ap.add_argument("--lam", type=float, default=2.0, help="damage_exponent lambda")
    ap.add_argument("--r", type=float, default=3.5e6, help="static tensile strength R [Pa]")
    ap.add_argument("--cells-per-rise", type=int, default=400)
    ap.add_argument("--work", default="/tmp/tuler_butcher_rate")
    ap.add_argument("--table", default="")
    a = ap.parse_args()
    exe = os.path.abspath(a.exe)
    os.makedirs(a.work, exist_ok=True)
    lines = ["| nominal ε̇ [1/s] | t_r [µs] | P [MPa] | ε̇ read [1/s] | σ Novikov, "
             "brittle [MPa] | σ Novikov, Tuler–Butcher [MPa] | DIF (TB / R) | "
             "closed form at ε̇ read [MPa] |",
             "|---|---|---|---|---|---|---|---|"]
    failed = False
    for rate in [float(x) for x in a.rates.split(",")]:
        p = 3.0 * closed_form(a.r, a.k, a.lam, rate)
        t_r = p / (E * rate)        # the unloading's strain rate P / (E t_r) is the nominal
        res = {}
        for label, k in (("brittle", 0.0), ("tb", a.k)):
            res[label] = one(exe, a.work, f"rate{rate:g}_{label}", t_r, p, a.cells_per_rise,
                             k, a.lam, a.r)
        if res["brittle"] is None or res["tb"] is None:
            failed = True
            continue
        b, tb = res["brittle"], res["tb"]
        flag = "" if (b["found"] and tb["found"]) else " (no pull-back)"
        lines.append(f"| {rate:g} | {t_r * 1e6:.4g} | {p / 1e6:.4g} | {tb['eps_dot']:.3g} | "
                     f"{b['sigma'] / 1e6:.3f} | {tb['sigma'] / 1e6:.3f} | "
                     f"{tb['sigma'] / a.r:.2f} | "
                     f"{closed_form(a.r, a.k, a.lam, tb['eps_dot']) / 1e6:.3f}{flag} |")
    text = "\n".join(lines)
    print(f"R = {a.r / 1e6:g} MPa, K = {a.k:g} Pa^{a.lam:g} s, lambda = {a.lam:g}, "
          f"{a.cells_per_rise} cells per rise time, c = {C:.1f} m/s")
    print(text)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
