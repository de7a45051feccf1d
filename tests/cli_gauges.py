#!/usr/bin/env python3
"""&gauges through the executable (issue 20): PREFIX.gau and /gauges.

The paper's Example 2 (spall in a layered bar) with gauges on the top face, inside a cell,
on an interior node, on the node where the first spall opens, on the interface node and on
the transmitting bottom, every 5 steps, with PREFIX.h5:

  * the other outputs' rows are those of the same deck without gauges (gauges only read);
  * PREFIX.gau: the usual header (version line, title, the echoed deck with &gauges, one
    line per gauge saying where it is, units) ending in the column line
    t stress_k velocity_k u_k; a row at t = 0, every 5 steps and at t_end;
  * at the spall node, two gauges (side 'above', the default, and 'below'): after the
    fracture the stress is 0 and velocity and u are those of the node's upper and lower
    half (the .prf rows at a profile time, to their 13 digits), never their mean;
  * /gauges/t, /gauges/{stress,velocity,u} (rows x gauges in h5py) equal the text, the
    attribute x the positions;
  * bad &gauges: x outside the bar, more than 100 positions, every = 0 or < 0, no x: exit
    2, one line naming &gauges and the variable, no output file;
  * plots/gauges.py draws from PREFIX.h5 and from the text, and warns when there are no
    gauges.

usage: cli_gauges.py SPALLBAR INPUT_DIR PLOTS_DIR WORKDIR     (needs h5py, numpy, matplotlib)
"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

from clitools import Checks, expect_refused, run

EVERY = 5


def body_rows(path):
    with open(path) as f:
        return [line for line in f if line.startswith(" ")]


def header(path):
    with open(path) as f:
        return [line.rstrip("\n") for line in f if line.startswith("#")]


def table(path):
    names = header(path)[-1][1:].split()
    rows = np.array([[float(v) for v in line.split()] for line in body_rows(path)])
    return names, rows


def main():
    exe, input_dir, plots, work = (os.path.abspath(sys.argv[1]), sys.argv[2],
                                   os.path.abspath(sys.argv[3]), sys.argv[4])
    check = Checks()
    work = os.path.join(work, "gauges")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    base = open(os.path.join(input_dir, "example2.nml")).read()
    base = base.replace("&run", "&run\n  hdf5 = .true.", 1)
    with open(os.path.join(work, "plain.nml"), "w") as f:
        f.write(base)
    p = run(exe, ["plain.nml", "-q"], work)
    check(p.returncode == 0, f"example 2 without gauges runs ({p.stderr.strip()})")
    check(not os.path.exists(os.path.join(work, "plain.gau")), "no gauges: no PREFIX.gau")
    with h5py.File(os.path.join(work, "plain.h5"), "r") as h:
        check("gauges" not in h, "no gauges: no /gauges")
    evt_names = header(os.path.join(work, "plain.evt"))[-1][1:].split()
    evt = [line.split() for line in body_rows(os.path.join(work, "plain.evt"))]
    first = [e[evt_names.index("kind")] for e in evt].index("fracture")
    x_crack = float(evt[first][evt_names.index("x")])
    t_crack = float(evt[first][evt_names.index("t")])
    dx1 = 0.84 / 30
    xs = [0.0, 3.57 * dx1, 0.42, x_crack, 0.84, 2.89, x_crack]
    sides = ["above"] * 6 + ["below"]
    deck = base + "&gauges\n  x = " + ", ".join(repr(x) for x in xs) + \
        "\n  side = " + ", ".join(f"'{s}'" for s in sides) + f"\n  every = {EVERY}\n/\n"
    with open(os.path.join(work, "gau.nml"), "w") as f:
        f.write(deck)
    p = run(exe, ["gau.nml", "-q"], work)
    check(p.returncode == 0, f"example 2 with gauges runs ({p.stderr.strip()})")
    for ext in [".his", ".prf", ".evt", ".frg"]:
        same = body_rows(os.path.join(work, "plain" + ext)) == \
            body_rows(os.path.join(work, "gau" + ext))
        check(same, f"gauges change no row of {ext}")

    gau = os.path.join(work, "gau.gau")
    head = header(gau)
    cols = "t " + " ".join(f"stress_{k} velocity_{k} u_{k}" for k in range(1, len(xs) + 1))
    check(head[0].startswith("# spallbar ") and "gauges" in head[0], "version line")
    check(head[1].startswith("# title: Example 2"), "title line")
    check("# &gauges" in head, "the echoed deck holds &gauges")
    check(any(h.startswith("# units: t [s]; stress_k [Pa] (compression > 0); velocity_k "
                           "[m/s] along +x (down); u_k [m]") for h in head), "units line")
    check(head[-1] == "# " + cols, f"column line ({head[-1][:60]})")
    where = [h for h in head if h.startswith("# gauge ")]
    check(len(where) == len(xs), "one line per gauge")
    check("is on node 0, the top end" in where[0], "gauge 1 on the top node")
    check("is inside cell 4" in where[1], "gauge 2 inside cell 4")
    check("is on node 15:" in where[2] and "the face above it (side = 'above')" in where[2],
          "gauge 3 on node 15, says which face it reads where the node splits")
    check("the face below it (side = 'below')" in where[6], "gauge 7 reads the face below")
    check("is on node 30:" in where[4], "gauge 5 on the interface node 30")
    check("the bottom end" in where[5], "gauge 6 on the bottom end")
    names, rows = table(gau)
    check(names == cols.split() and rows.shape[1] == 1 + 3 * len(xs), "row width")
    dt, nsteps = 8.0e-6, 250
    steps = list(range(0, nsteps + 1, EVERY))
    if steps[-1] != nsteps:
        steps.append(nsteps)
    check(np.allclose(rows[:, 0], np.array(steps) * dt, rtol=1e-12, atol=0),
          f"rows at t = 0, every {EVERY} steps, t_end ({len(rows)} rows)")
    with open(gau) as f:
        widths = {len(line.rstrip("\n")) for line in f if line.startswith(" ")}
    check(widths == {21 * (1 + 3 * len(xs))}, f"fixed-width rows ({widths})")
    # the top face carries the load; the crack node reads 0 once split, and its halves
    load = rows[:, 1]
    check(load[0] == 0.0 and abs(load[1] - 5.0e6 * np.mean(
        [(1 - t / 1e-3) ** 5 for t in np.linspace(4 * dt, 5 * dt, 20001)])) < 1e-4 * 5e6,
        "top gauge: the load's mean over the step")
    k = 4   # the crack gauge (above); 7 the same node read below
    s_k, v_k, u_k = rows[:, 1 + 3 * (k - 1)], rows[:, 2 + 3 * (k - 1)], rows[:, 3 + 3 * (k - 1)]
    s_b, v_b, u_b = rows[:, 19], rows[:, 20], rows[:, 21]
    check(np.any(np.abs(s_k[rows[:, 0] < t_crack - 1e-12]) > 1e5), "crack node loaded before")
    sys.path.insert(0, plots)
    import spbread
    r = spbread.load(os.path.join(work, "gau"))
    checked = 0
    for prof in r.profiles:
        if prof["t"] <= t_crack + 1e-12:
            continue
        row = np.flatnonzero(np.abs(rows[:, 0] - prof["t"]) < 0.5 * dt)
        if len(row) == 0:
            continue
        at = np.flatnonzero(np.abs(prof["x"] - x_crack) < 1e-9)
        if len(at) != 2 or prof["u"][at[0]] == prof["u"][at[1]]:
            continue
        j = row[0]
        check(s_k[j] == 0.0 and s_b[j] == 0.0, f"t = {prof['t']}: the split node reads stress 0")
        for side, u_g, v_g, h in (("above", u_k, v_k, at[0]), ("below", u_b, v_b, at[1])):
            u_h, v_h = prof["u"][h], prof["v"][h]
            check(abs(u_g[j] - u_h) <= 1e-12 * max(abs(u_h), 1e-30),
                  f"t = {prof['t']}: u {side} is that half's")
            check(abs(v_g[j] - v_h) <= 1e-12 * max(abs(v_h), 1e-12),
                  f"t = {prof['t']}: velocity {side} is that half's")
        check(abs(u_k[j] - u_b[j]) > 0.0, f"t = {prof['t']}: the two sides differ")
        checked += 1
    check(checked >= 1, f"compared the crack gauge with the profiles ({checked} times)")

    with h5py.File(os.path.join(work, "gau.h5"), "r") as h:
        g = h["gauges"]
        check(np.array_equal(g.attrs["x"], np.array(xs)), "/gauges x attribute")
        check(g["t"].shape == (len(rows),), "/gauges/t: one per row")
        for q, off in (("stress", 1), ("velocity", 2), ("u", 3)):
            a = g[q][()]
            text = rows[:, off::3]
            check(a.shape == (len(rows), len(xs)), f"/gauges/{q} is rows x gauges in h5py")
            check(np.allclose(a, text, rtol=1e-12, atol=1e-300 + 1e-12 * np.abs(text).max()),
                  f"/gauges/{q} equals the text")
        check(np.allclose(g["t"][()], rows[:, 0], rtol=1e-12, atol=0), "/gauges/t equals t")

    # bad &gauges
    def bad(what, group, needles):
        expect_refused(check, exe, work, what, base + group, needles)
    bad("negative x", "&gauges x = -0.1 /\n", ["&gauges", "x(1)", "outside the bar"])
    bad("x beyond the bar", "&gauges x = 0.1, 2.9 /\n", ["&gauges", "x(2)", "outside"])
    bad("101 gauges", "&gauges x = " + ", ".join(["0.5"] * 101) + " /\n",
        ["&gauges", "x", "at most 100"])
    bad("every = 0", "&gauges x = 0.5, every = 0 /\n", ["&gauges", "every", ">= 1"])
    bad("every < 0", "&gauges x = 0.5, every = -3 /\n", ["&gauges", "every", ">= 1"])
    bad("no x", "&gauges every = 2 /\n", ["&gauges", "x is required"])
    bad("a hole in x", "&gauges x(1) = 0.5, x(3) = 0.7 /\n", ["&gauges", "x(3)"])
    bad("unknown variable", "&gauges x = 0.5, y = 1 /\n", ["&gauges", "y"])

    # the plot, from PREFIX.h5 and from the text files; a warning without gauges
    py = sys.executable
    for src in ("h5", "text"):
        if src == "text":
            os.rename(os.path.join(work, "gau.h5"), os.path.join(work, "gau.h5.aside"))
        out = os.path.join(work, f"gauges_{src}.png")
        p = subprocess.run([py, os.path.join(plots, "gauges.py"), "gau", "-o", out], cwd=work,
                           capture_output=True, text=True)
        check(p.returncode == 0 and os.path.getsize(out) > 10000 and not p.stderr.strip(),
              f"plots/gauges.py from {src} ({p.stderr.strip()[-200:]})")
    out = os.path.join(work, "gauges_none.png")
    p = subprocess.run([py, os.path.join(plots, "gauges.py"), "plain", "-o", out], cwd=work,
                       capture_output=True, text=True)
    check(p.returncode == 0 and "nothing to draw" in p.stderr, "plot without gauges warns")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
