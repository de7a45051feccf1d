"""Run the paper's examples and render its figures into OUT (the `figures` target):

  fig07c.png  Example 1: the one-cell splinter's translation and vibration velocities and
              its spring stress, model against the paper's closed forms (V^n, V~^n)
  fig08b.png  Example 2: x-t spall map (stress field, fractures, collisions)
  fig10.png   Example 3 case 1: base reaction, accelerate / delay / bar fixed in the base in
              panels of their own; the time shift between the two rules' contact phases
              (arrows, and against time) and the intervals between contact phases
  fig11.png   Example 3 case 2: fragment configurations with stress profiles
  fig12.png   Example 3 case 2: base reaction, half-mass vs full-mass model

usage: figures.py --exe SPALLBAR --input INPUT_DIR --out OUT_DIR [--only fig10 ...]

A figure whose runs have nothing to draw (a zero base reaction, no contact phase, no
profiles or fragments, no x-t field) is still written: a line 'figures.py: warning: nothing
to draw: ...' on stderr says what is missing, and the exit status stays 0 (the same rule as
the other plot scripts; doc/outputs.md, "Plots"). Exit 1 when a run fails, 2 for a bad
command line (an unknown name after --only).
"""
import argparse
import glob
import os
import shutil
import re
import subprocess

import numpy as np

from _common import View, nothing_to_draw, plt, save, spbread, stress_scale
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
    a1.legend(fontsize=7, ncol=2, loc="lower center", bbox_to_anchor=(0.5, 1.0))  # off the data
    fig.suptitle("Fig. 7c - Example 1: one-cell splinter at the free end", fontsize=9)
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


def contact_phases(run, min_steps=5):
    """Starts [s] of the main contact phases of a run: runs of positive base reaction
    longer than MIN_STEPS steps, the first one (static contact) starting at t = 0 - the
    definition of tests/test_example3_case1.pf (its history has a row every step)."""
    t, r = run.history["t"], run.history["reaction_bottom"]
    dt = float(np.median(np.diff(t))) if len(t) > 1 else 0.0
    starts, on, start = [], True, 0.0
    for k in range(1, len(t)):
        if r[k] > 0.0 and not on:
            on, start = True, t[k]
        elif not r[k] > 0.0 and on:
            on = False
            if t[k] - start > min_steps * dt * (1.0 + 1e-9):
                starts.append(start)
    return np.array(starts), dt


def pair_phases(a, d):
    """Mutually nearest phase starts of A and D: [(i, j)], and the index of the first phase
    of A without a partner (len(a) when every one has one)."""
    pairs, first_lost = [], len(a)
    for i, x in enumerate(a):
        j = int(np.argmin(np.abs(d - x))) if len(d) else -1
        if j >= 0 and int(np.argmin(np.abs(a - d[j]))) == i:
            pairs.append((i, j))
        elif first_lost == len(a):
            first_lost = i
    return pairs, first_lost


def cv(x):
    """Coefficient of variation (population standard deviation over the mean)."""
    return float(np.std(x) / np.mean(x)) if len(x) else float("nan")


def fig10(exe, indir, out):
    """Example 3, case 1. (a)-(c) the three base reactions in panels of their own on the same
    scales, the starts of their main contact phases marked; (d) accelerate and delay
    overlaid while their phases correspond, the time shift between corresponding phase
    starts as arrows; (e) that shift against time; (f) the intervals between the phase
    starts against 4h/a (the paper: a growing time shift between the two rules, aperiodic
    contact phases on the base unlike the fixed bar)."""
    rules = ("accelerate", "delay", "fixed")
    runs = [spbread.load(run_deck(exe, os.path.join(indir, f"example3_case1_{rule}.nml"),
                                  out, f"fig10_{rule}", {"hdf5": ".true."})) for rule in rules]
    phases = [contact_phases(r) for r in runs]
    fig = plt.figure(figsize=(9, 12.8))
    grid = fig.add_gridspec(6, 2, height_ratios=[1, 1, 1, 1.3, 1.5, 0.38])
    scale, unit = stress_scale(np.concatenate([r.history["reaction_bottom"] for r in runs]))
    _fig10_traces(fig, grid, runs, phases, scale, unit)
    a, d, f, dt = phases[0][0], phases[1][0], phases[2][0], phases[0][1]
    pairs, lost = pair_phases(a, d)
    t_lost = a[lost] if lost < len(a) else np.inf
    _fig10_zoom(fig.add_subplot(grid[3, :]), runs, a, d, dt, pairs, t_lost, scale, unit)
    shift = _fig10_shift(fig.add_subplot(grid[4, 0]), fig.add_subplot(grid[5, 0]), a, d, dt,
                         pairs, t_lost)
    fixed = runs[2]
    period = 4.0 * fixed.deck_real("segments", "length") / np.sqrt(   # 4h/a of the fixed bar
        fixed.deck_real("segments", "young") / fixed.deck_real("segments", "density"))
    _fig10_intervals(fig.add_subplot(grid[4, 1]), fig.add_subplot(grid[5, 1]), phases, period)
    fig.suptitle("Fig. 10 - Example 3, case 1: base reaction R, dx = h/19", fontsize=9)
    if min(len(a), len(d)) < 2:
        nothing_to_draw("fig10: fewer than two main contact phases of the bar on the base: "
                        "no time shift and no interval to draw")
    print(f"fig10: delay - accelerate, corresponding phases [steps] {shift['good']}, they stop "
          f"pairing up at {t_lost:.4f} s; nearest after {shift['late']}; k-th vs k-th, mean "
          f"|shift| {shift['early']:.1f} steps over phases 2-4, {shift['later']:.1f} over 5-8; "
          f"interval variation accelerate {cv(np.diff(a)):.3f}, delay {cv(np.diff(d)):.3f}, "
          f"fixed {cv(np.diff(f)[1:]):.3f}; 4h/a = {period * 1e3:.2f} ms")
    save(fig, os.path.join(out, "fig10.png"))


FIG10_COLORS = ("tab:blue", "tab:orange", "tab:green")
SECONDS = View(time="s")     # the paper's Figs. 10 and 12 draw seconds


def _fig10_traces(fig, grid, runs, phases, scale, unit):
    """(a)-(c): one run per panel, shared axes, main contact phases as triangles below."""
    labels = ["(a) bar on the base, timing accelerate (the paper's dotted curve)",
              "(b) bar on the base, timing delay (the paper's solid curve)",
              "(c) bar fixed in the base (the paper's dashed curve)"]
    top = None
    for k, (run, label, color, (starts, _)) in enumerate(zip(runs, labels, FIG10_COLORS,
                                                             phases)):
        ax = fig.add_subplot(grid[k, :], sharex=top, sharey=top)
        top = top or ax
        reaction.plot([run], [label], ax, scale=scale, unit=unit, colors=[color], legend=False,
                      view=SECONDS)
        ax.plot(starts, np.full(len(starts), -0.05), "^", transform=ax.get_xaxis_transform(),
                clip_on=False, ms=4, color=color, mec="k", mew=0.4)
        ax.set_title(f"{label}; triangles: starts of the main contact phases", fontsize=8,
                     loc="left")
        ax.set_ylabel(f"R [{unit}]")
        ax.set_xlabel("t [s]" if k == len(runs) - 1 else "")
        ax.tick_params(labelbottom=(k == len(runs) - 1))
        ax.axhline(0.0, color="0.6", lw=0.4)
    top.set_xlim(0.0, float(runs[0].history["t"][-1]))


def _fig10_zoom(ax, runs, a, d, dt, pairs, t_lost, scale, unit):
    """(d): accelerate and delay overlaid up to t_lost, arrows from each accelerate phase
    start to the corresponding delay one, labelled with the shift in steps."""
    t_zoom = min(t_lost + 0.01, float(runs[0].history["t"][-1]))
    peak = 0.0
    for run, color, style in zip(runs[:2], FIG10_COLORS, ("-", "--")):
        h = run.history
        sel = h["t"] <= t_zoom
        ax.plot(h["t"][sel], h["reaction_bottom"][sel] / scale, style, lw=0.9, color=color)
        peak = max(peak, float(np.max(h["reaction_bottom"][sel], initial=0.0)) / scale)
    top_y = 1.12 * peak if peak > 0 else 1.0
    for i, j in pairs:
        if a[i] >= t_lost or a[i] == 0.0:
            continue
        ax.annotate("", xy=(d[j], top_y), xytext=(a[i], top_y),
                    arrowprops=dict(arrowstyle="->", lw=0.8, color="k", shrinkA=0, shrinkB=0))
        ax.plot([a[i], a[i]], [0, top_y], ":", lw=0.6, color=FIG10_COLORS[0])
        ax.plot([d[j], d[j]], [0, top_y], ":", lw=0.6, color=FIG10_COLORS[1])
        ax.text(0.5 * (a[i] + d[j]), top_y * 1.03, f"{(d[j] - a[i]) / dt:+.0f}", ha="center",
                va="bottom", fontsize=7)
    ax.set_xlim(0.0, t_zoom)
    ax.set_ylim(top=top_y * 1.2)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(f"R [{unit}]")
    ax.set_title("(d) accelerate (solid blue) and delay (dashed orange) while their contact "
                 "phases correspond; arrows: from an accelerate\nphase start to the "
                 "corresponding delay one, the shift in steps", fontsize=8, loc="left")


def _fig10_shift(ax, legend_ax, a, d, dt, pairs, t_lost):
    """(e): delay - accelerate phase start [steps] against time; the numbers drawn."""
    good = [(i, j) for i, j in pairs if a[i] < t_lost]
    late = [(i, j) for i, j in pairs if a[i] >= t_lost]
    ax.plot([a[i] for i, _ in good], [(d[j] - a[i]) / dt for i, j in good], "o-", ms=4,
            color=FIG10_COLORS[1], mec="k", mew=0.4, label="corresponding phases: delay lags")
    partners = {j for _, j in pairs}
    extra = [x for j, x in enumerate(d) if x < t_lost and j not in partners]
    ax.plot(extra, np.zeros(len(extra)), "|", ms=12, mew=1.5, color=FIG10_COLORS[1],
            label="delay phase with no accelerate partner ("
                  + ", ".join(f"{x:.3f} s" for x in extra) + ")")
    k_max = min(8, len(a), len(d))
    early = np.mean(np.abs(d[1:4] - a[1:4])) / dt if k_max >= 4 else float("nan")
    later = np.mean(np.abs(d[4:8] - a[4:8])) / dt if k_max >= 8 else float("nan")
    ax.plot(a[1:k_max], (d[1:k_max] - a[1:k_max]) / dt, "x", ms=5, color="k",
            label=f"k-th against k-th phase, k = 2-{k_max}: mean |shift| {early:.1f} steps "
                  f"over 2-4, {later:.1f} over 5-8")
    if np.isfinite(t_lost):
        ax.axvline(t_lost, color="0.5", lw=0.6, ls=":",
                   label=f"{t_lost:.3f} s: the first accelerate phase with no partner")
    ax.plot([a[i] for i, _ in late], [(d[j] - a[i]) / dt for i, j in late], "o", ms=4,
            mfc="none", color="0.5", label="nearest phases after that (no correspondence)")
    ax.axhline(0.0, color="0.6", lw=0.4)
    ax.set_xlabel("t [s] (start of the accelerate phase)")
    ax.set_ylabel(f"delay - accelerate [steps of {dt * 1e3:.2f} ms]", fontsize=8)
    ax.set_title("(e) time shift between the rules' contact phases", fontsize=8, loc="left")
    _legend_below(ax, legend_ax)
    return dict(good=[round(float((d[j] - a[i]) / dt), 1) for i, j in good],
                late=[round(float((d[j] - a[i]) / dt), 1) for i, j in late],
                early=early, later=later)


def _fig10_intervals(ax, legend_ax, phases, period):
    """(f): intervals between successive main contact phase starts, and 4h/a."""
    for (starts, _), color, marker, name in zip(phases, FIG10_COLORS, "os^",
                                               ("accelerate", "delay", "fixed")):
        gaps = np.diff(starts)
        # the fixed bar's first interval runs from the static contact at t = 0
        ax.plot(starts[1:], gaps * 1e3, marker, ms=3.5, color=color, mec="k", mew=0.3,
                label=f"{name}: coefficient of variation "
                      f"{cv(gaps[1:] if name == 'fixed' else gaps):.3f}")
    if np.isfinite(period):
        ax.axhline(period * 1e3, color="k", lw=0.6, ls="--", zorder=0,
                   label=f"4h/a = {period * 1e3:.1f} ms")
    ax.set_xlabel("t [s] (start of the later phase)")
    ax.set_ylabel("interval between phase starts [ms]", fontsize=8)
    ax.set_title("(f) intervals: aperiodic on the base, 4h/a when fixed", fontsize=8,
                 loc="left")
    _legend_below(ax, legend_ax)


def _legend_below(ax, legend_ax):
    """AX's legend in LEGEND_AX (a row of its own, no axes drawn): off the data."""
    legend_ax.axis("off")
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        legend_ax.legend(handles, labels, fontsize=6.5, loc="upper center", framealpha=0.9)


def fig11(exe, indir, out):
    deck = os.path.join(indir, "example3_case2", "accelerate_fragment_h19.nml")
    run = spbread.load(run_deck(exe, deck, out, "fig11_case2", {"hdf5": ".true."}))
    blocks = list(zip(run.profiles, run.fragments))[:6]
    if not blocks:
        nothing_to_draw("fig11: no profile and fragment blocks (&run profile_times)")
    scale, unit = stress_scale(np.concatenate([p["stress"] for p, _ in blocks] or [[0.0]]))
    rows = max(len(blocks), 1)
    fig, axes = plt.subplots(rows, 1, figsize=(8, 1.6 * rows + 0.6), sharex=True)
    for ax, (p, f) in zip(np.atleast_1d(axes), blocks):
        for j in range(len(f["id"])):
            ax.axvspan(f["x_top"][j], f["x_bottom"][j], color=("0.85" if j % 2 else "0.7"),
                       lw=0)
        ax.step(p["x"] + p["u"], p["stress"] / scale, where="post", color="k", lw=0.9)
        n = len(f["id"])
        ax.set_title(f"t = {p['t']:.3f} s, {n} {'fragment' if n == 1 else 'fragments'}",
                     fontsize=8, loc="left", pad=2)
        ax.set_ylabel(f"stress [{unit}]", fontsize=8)
    np.atleast_1d(axes)[-1].set_xlabel("position x + u [m] (shaded spans: the fragments, "
                                       "alternately light and dark grey)")
    fig.suptitle("Fig. 11 - Example 3, case 2: fragments and stress profiles (accelerate, "
                 "fragment shifts, h/19)", fontsize=9)
    save(fig, os.path.join(out, "fig11.png"))


def fig12(exe, indir, out):
    d = os.path.join(indir, "example3_case2")
    half = spbread.load(run_deck(exe, os.path.join(d, "accelerate_fragment_h19.nml"), out,
                                 "fig12_half", {"hdf5": ".true."}))
    full = spbread.load(run_deck(exe, os.path.join(d, "fullmass_accelerate_fragment_h19.nml"),
                                 out, "fig12_full", {"hdf5": ".true."}))
    fig, ax = plt.subplots(figsize=(9, 4.2))
    reaction.plot([half, full], ["half-mass model (exact free ends)",
                                 "full-mass model (paper: dash-dotted)"], ax, view=SECONDS)
    ax.set_title("Fig. 12 - Example 3, case 2: base reaction, h/19, accelerate / fragment",
                 fontsize=9)
    save(fig, os.path.join(out, "fig12.png"))


FIGURES = (fig07c, fig08b, fig10, fig11, fig12)


def main():
    p = argparse.ArgumentParser(description="render the paper's figures")
    p.add_argument("--exe", required=True)
    p.add_argument("--input", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--only", nargs="*", choices=[f.__name__ for f in FIGURES],
                   help="a subset, e.g. fig10 fig12")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for fig in FIGURES:
        if not args.only or fig.__name__ in args.only:
            fig(os.path.abspath(args.exe), os.path.abspath(args.input), os.path.abspath(args.out))


if __name__ == "__main__":
    main()
