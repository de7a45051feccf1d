"""Run the paper's examples and render its figures into OUT (the `figures` target):

  fig07c.png  Example 1: the one-cell splinter's translation and vibration velocities and
              its spring stress, model against the paper's closed forms (V^n, V~^n)
  fig08b.png  Example 2: x-t spall map (stress field, fractures, collisions)
  fig10.png   Example 3 case 1: base reaction, accelerate / delay / bar fixed in the base
  fig11.png   Example 3 case 2: fragment configurations with stress profiles
  fig12.png   Example 3 case 2: base reaction, half-mass vs full-mass model

usage: figures.py --exe SPALLBAR --input INPUT_DIR --out OUT_DIR
"""
import argparse
import glob
import os
import shutil
import re
import subprocess

import numpy as np

from _common import plt, save, spbread
import reaction
import xt


def run_deck(exe, deck, out_dir, name, overrides):
    """Copy DECK with &run variables replaced, run it (cwd = the deck's folder, for
    table files), return the output prefix. The paper's figures are drawn with the paper's
    event rules (events = 'paper'; doc/method.md, "Admissible events")."""
    overrides = {"events": "'paper'", **overrides}
    text = open(deck).read()
    lines, in_run = [], False
    for line in text.splitlines():
        stripped = line.strip().lower()
        if stripped.startswith("&run"):
            in_run = True
            lines.append(line)
            lines.extend(f"  {k} = {v}" for k, v in overrides.items())
            continue
        if in_run and stripped.startswith("/"):
            in_run = False
        if in_run and any(re.match(rf"{k}\s*=", stripped) for k in overrides):
            continue
        lines.append(line)
    copy = os.path.join(out_dir, name + ".nml")
    with open(copy, "w") as f:
        f.write("\n".join(lines) + "\n")
    # file names in a deck are relative to the deck's folder: its load tables go beside the copy
    for table in glob.glob(os.path.join(os.path.dirname(os.path.abspath(deck)), "*.txt")):
        shutil.copy(table, out_dir)
    prefix = os.path.join(out_dir, name)
    subprocess.run([exe, copy, "--quiet", "--output", prefix], check=True,
                   cwd=os.path.dirname(os.path.abspath(deck)))
    return prefix


def fig07c(exe, indir, out):
    dt, cells, g = 5.0e-4, 20, 9.81
    prefix = run_deck(exe, os.path.join(indir, "example1.nml"), out, "fig07c_example1",
                      {"t_end": (cells - 1 + 40) * dt, "hdf5": ".true.", "field_every": 1})
    run = spbread.load(prefix)
    v, s, t = run.xt["v"], run.xt["stress"], run.xt["t"]
    steps = np.rint(t / dt).astype(int) - (cells - 1)      # the paper's n: t^0 = step 19
    v_end, v_top = v[:, 2 * cells - 1], v[:, 2 * cells - 2]   # the splinter's two halves
    vt, vv = 0.5 * (v_end + v_top), v_end - 0.5 * (v_end + v_top)
    dm, sig1, del1 = 1.8e5 * dt, 160.0e3, 60.0e3
    n = np.arange(3, steps[-1] + 1)
    ref_v = (2 * sig1 - del1 + (n - 2.5) * dm * g) * dt / dm
    ref_vib = (-1.0) ** n * (del1 + 0.5 * dm * g) * dt / dm
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    sel = steps >= -2
    a1.plot(steps[sel], vt[sel], "-", color="tab:blue", label=r"model: translation $V$")
    a1.plot(steps[sel], vv[sel], "-", color="tab:orange", label=r"model: vibration $\tilde V$")
    a1.plot(n, ref_v, "o", mfc="none", color="tab:blue", label=r"paper: $V^n$ (closed form)")
    a1.plot(n, ref_vib, "s", mfc="none", color="tab:orange", label=r"paper: $\tilde V^n$ (closed form)")
    a1.set_ylabel("velocity [m/s] (down > 0)")
    a1.legend(fontsize=7, ncol=2)
    a1.set_title("Fig. 7c - Example 1: one-cell splinter at the free end", fontsize=9)
    a2.step(steps[sel], s[sel, 2 * cells - 1] / 1e3, where="post", color="k")
    a2.set_ylabel("splinter spring stress [kPa]")
    a2.set_xlabel(r"step $n$ (the paper's $t^0$: the front one cell from the free end)")
    save(fig, os.path.join(out, "fig07c.png"))


def fig08b(exe, indir, out):
    prefix = run_deck(exe, os.path.join(indir, "example2.nml"), out, "fig08b_example2",
                      {"hdf5": ".true.", "field_every": 1})
    run = spbread.load(prefix)
    fig, ax = plt.subplots(figsize=(8, 6.5))
    xt.plot(run, ax)
    ax.set_title("Fig. 8b - Example 2: spall, secondary division and re-collisions", fontsize=9)
    save(fig, os.path.join(out, "fig08b.png"))


def fig10(exe, indir, out):
    runs = []
    for rule in ("accelerate", "delay", "fixed"):
        runs.append(spbread.load(run_deck(exe, os.path.join(indir, f"example3_case1_{rule}.nml"),
                                          out, f"fig10_{rule}", {"hdf5": ".true."})))
    fig, ax = plt.subplots(figsize=(9, 4.2))
    reaction.plot(runs, ["bar on the base, accelerate (paper: dotted)",
                         "bar on the base, delay (paper: solid)",
                         "bar fixed in the base (paper: dashed)"], ax)
    ax.set_title("Fig. 10 - Example 3, case 1: base reaction, dx = h/19", fontsize=9)
    save(fig, os.path.join(out, "fig10.png"))


def fig11(exe, indir, out):
    deck = os.path.join(indir, "example3_case2", "accelerate_fragment_h19.nml")
    run = spbread.load(run_deck(exe, deck, out, "fig11_case2", {"hdf5": ".true."}))
    blocks = list(zip(run.profiles, run.fragments))[:6]
    fig, axes = plt.subplots(len(blocks), 1, figsize=(8, 1.6 * len(blocks) + 0.6), sharex=True)
    for ax, (p, f) in zip(np.atleast_1d(axes), blocks):
        for j in range(len(f["id"])):
            ax.axvspan(f["x_top"][j], f["x_bottom"][j], color=("0.85" if j % 2 else "0.7"),
                       lw=0)
        ax.step(p["x"] + p["u"], p["stress"] / 1e3, where="post", color="k", lw=0.9)
        ax.text(0.01, 0.8, f"t = {p['t']:.3f} s, {len(f['id'])} fragments",
                transform=ax.transAxes, fontsize=8)
        ax.set_ylabel("stress [kPa]", fontsize=8)
    np.atleast_1d(axes)[-1].set_xlabel("position x + u [m] (shaded spans: the fragments, "
                                       "alternately light and dark grey)")
    np.atleast_1d(axes)[0].set_title("Fig. 11 - Example 3, case 2: fragments and stress "
                                     "profiles (accelerate, fragment shifts, h/19)", fontsize=9)
    save(fig, os.path.join(out, "fig11.png"))


def fig12(exe, indir, out):
    d = os.path.join(indir, "example3_case2")
    half = spbread.load(run_deck(exe, os.path.join(d, "accelerate_fragment_h19.nml"), out,
                                 "fig12_half", {"hdf5": ".true."}))
    full = spbread.load(run_deck(exe, os.path.join(d, "fullmass_accelerate_fragment_h19.nml"),
                                 out, "fig12_full", {"hdf5": ".true."}))
    fig, ax = plt.subplots(figsize=(9, 4.2))
    reaction.plot([half, full], ["half-mass model (exact free ends)",
                                 "full-mass model (paper: dash-dotted)"], ax)
    ax.set_title("Fig. 12 - Example 3, case 2: base reaction, h/19, accelerate / fragment",
                 fontsize=9)
    save(fig, os.path.join(out, "fig12.png"))


def main():
    p = argparse.ArgumentParser(description="render the paper's figures")
    p.add_argument("--exe", required=True)
    p.add_argument("--input", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--only", nargs="*", help="a subset, e.g. fig10 fig12")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for fig in (fig07c, fig08b, fig10, fig11, fig12):
        if not args.only or fig.__name__ in args.only:
            fig(os.path.abspath(args.exe), os.path.abspath(args.input), os.path.abspath(args.out))


if __name__ == "__main__":
    main()
