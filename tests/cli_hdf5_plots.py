#!/usr/bin/env python3
"""PREFIX.h5 read back with h5py equals the text outputs; every plot script runs headless
and writes a PNG, from the HDF5 file and from the text files alone.

usage: cli_hdf5_plots.py SPALLBAR INPUT_DIR PLOTS_DIR WORKDIR   (a Python with h5py, numpy,
matplotlib: the project venv)
"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

from clitools import Checks, run

SCRIPTS = ("profiles", "reaction", "xt", "fragments")


def text_table(path):
    names, rows = None, []
    for line in open(path):
        if line.startswith("#"):
            names = line[1:].split()
        elif line.startswith(" "):          # not the column-name first line
            rows.append(line.split())
    return names, rows


def blocks(path):
    out, t, rows = [], None, []
    for line in open(path):
        if line.startswith("# t = "):
            if t is not None:
                out.append((t, rows))
            t, rows = float(line[6:]), []
        elif line.startswith(" ") and t is not None:
            rows.append([float(x) for x in line.split()])
    if t is not None:
        out.append((t, rows))
    return out


def close(a, b):
    """Equal to the text's 13 significant digits."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    scale = max(np.max(np.abs(b)) if b.size else 0.0, 1e-300)
    return a.shape == b.shape and np.max(np.abs(a - b), initial=0.0) <= 1e-12 * scale


def png_ok(path):
    return os.path.exists(path) and os.path.getsize(path) > 1000 and \
        open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n"


def main():
    exe, indir, plots, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    # Example 2 (spall, collisions) for 0.6 ms, HDF5 and x-t rows every 4 steps
    deck = open(os.path.join(indir, "example2.nml")).read()
    deck = deck.replace("&run", "&run\n  hdf5 = .true.\n  field_every = 4", 1)
    deck = deck.replace("t_end         = 2.0e-3", "t_end         = 1.2e-3")
    deck = deck.replace(", 1.4e-3, 1.6e-3, 1.8e-3, 2.0e-3", "")
    with open(os.path.join(work, "ex2.nml"), "w") as f:
        f.write(deck)
    r = run(exe, ["ex2.nml", "-q"], work)
    check(r.returncode == 0, f"run: exit {r.returncode} {r.stderr}")
    prefix = os.path.join(work, "ex2")
    with h5py.File(prefix + ".h5", "r") as f:
        names, rows = text_table(prefix + ".his")
        check(sorted(names) == sorted(f["history"].keys()), "history: the same columns")
        for k, n in enumerate(names):
            check(close(f["history"][n][:], [row[k] for row in rows]), f"/history/{n} = text")
        names, rows = text_table(prefix + ".evt")
        kinds = {1: "fracture", 2: "collision", 3: "separation", 4: "base-collision"}
        check(len(rows) > 3, f"events: {len(rows)} rows")
        for k, n in enumerate(names[:-1]):                # the text's last: kind_code
            col = f["events"][n][:]
            if n == "kind":
                check([kinds[int(c)] for c in col] == [row[k] for row in rows], "/events/kind")
                check([str(int(c)) for c in col] == [row[-1] for row in rows],
                      "kind_code (text) = /events/kind")
            else:
                check(close(col, [float(row[k]) for row in rows]), f"/events/{n} = text")
        prf = blocks(prefix + ".prf")
        groups = sorted(f["fields"]["profiles"])
        check(len(groups) == len(prf), f"profiles: {len(groups)} groups, {len(prf)} text blocks")
        for g, (t, rows) in zip(groups, prf):
            a = np.array(rows)
            p = f["fields"]["profiles"][g]
            check(abs(p.attrs["t"] - t) <= 1e-12 * t, f"profile {g}: t")
            check(close(f["mesh"]["x_half"][:], a[:, 0]), f"profile {g}: x")
            for j, n in enumerate(("u", "v", "stress")):
                check(close(p[n][:], a[:, j + 1]), f"profile {g}: {n}")
        frg = blocks(prefix + ".frg")
        check(len(frg) == len(f["fragments"]), "fragments: one group per text block")
        for g, (t, rows) in zip(sorted(f["fragments"]), frg):
            a = np.array(rows)
            check(close(f["fragments"][g]["velocity"][:], a[:, 6]), f"fragments {g}: velocity")
            check(close(f["fragments"][g]["id"][:], a[:, 0]), f"fragments {g}: id")
        # x-t: Fortran (rows, snapshots) is (snapshots, rows) in h5py; t = 0, 4 dt, ...
        n = int(f["mesh"].attrs["cells"])
        nt = len(f["fields"]["xt"]["t"])
        check(f["fields"]["xt"]["stress"].shape == (nt, 2 * n), "x-t shape (snapshots, rows)")
        dt = float(f["mesh"].attrs["dt"])
        check(np.allclose(f["fields"]["xt"]["t"][:], 4 * dt * np.arange(nt), rtol=0,
                          atol=1e-12 * dt * nt), "x-t times every 4 steps")
        last = prf[-1]
        k = int(round(last[0] / (4 * dt)))
        if k < nt:
            check(close(f["fields"]["xt"]["u"][k, :], np.array(last[1])[:, 1]),
                  "x-t row = the profile at the same time")
        check(f["deck"]["run"].attrs["field_every"] == 4, "deck as attributes (typed)")
        check(f["deck"]["segments"].attrs["n:from"].decode() == "input", "deck: input/default")
        check(f["history"]["t"].attrs["units"].decode() == "s", "units as attributes")
    # every plot script, from the HDF5 file and from the text files alone
    text_only = os.path.join(work, "text_only")
    for ext in (".his", ".evt", ".prf", ".frg"):
        shutil.copy(prefix + ext, text_only + ext)
    env = dict(os.environ, MPLBACKEND="Agg")
    for source, p in (("hdf5", prefix), ("text", text_only)):
        for s in SCRIPTS:
            png = os.path.join(work, f"{s}_{source}.png")
            r = subprocess.run([sys.executable, os.path.join(plots, s + ".py"), p, "-o", png],
                               capture_output=True, text=True, env=env, timeout=300)
            check(r.returncode == 0 and png_ok(png), f"{s}.py from {source}: exit "
                  f"{r.returncode} {r.stderr[-500:]}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
