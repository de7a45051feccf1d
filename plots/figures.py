"""Run the paper's examples and render its figures into OUT (the `figures` target):

  fig07c.png  Example 1: the one-cell splinter's translation and vibration velocities and
              its spring stress, model against the paper's closed forms (V^n, V~^n)
  fig08b.png  Example 2: x-t spall map (stress field, fractures, collisions)
  fig10.png   Example 3 case 1: base reaction, accelerate / delay / bar fixed in the base in
              panels of their own; the time shift between the two rules' contact phases
              (arrows, and against time) and the intervals between contact phases
  fig11.png   Example 3 case 2: fragment configurations with stress profiles
  fig12.png   Example 3 case 2: base reaction, half-mass vs full-mass model
  fig13.png   Example 3 case 2 under the admissible (default) event rules, what is and is not
              known: (a) ensembles of the default rules on h/19, h/95, h/190 (&sweep perturb
              = 'p0', --realizations per mesh): mean, mean +- std and min..max of the base
              impulse and of e_lost_w, each mesh's predictability horizon; (b) one run per
              timing x shift rule on h/95 and the band across them (delay/face drawn up to
              where the position guard stops it, exit 3); the caption's numbers read from
              the runs (doc/validation.md, "Case 2 answered")

usage: figures.py --exe SPALLBAR --input INPUT_DIR --out OUT_DIR [--only fig10 ...]
                  [--realizations R]

A figure whose runs have nothing to draw (a zero base reaction, no contact phase, no
profiles or fragments, no x-t field, no base impulse and no event loss) is still written: a
line 'figures.py: warning: nothing to draw: ...' on stderr says what is missing, and the exit
status stays 0 (the same rule as the other plot scripts; doc/outputs.md, "Plots"). Exit 1
when a run fails (a run the position guard stops, exit 3, is drawn up to its stop in fig13),
2 for a bad command line (an unknown name after --only).
"""
import argparse
import glob
import os
import shutil
import re
import subprocess
import sys
import textwrap

import numpy as np

from _common import View, nothing_to_draw, plt, save, spbread, stress_scale
import ensemble
import reaction
import xt


def run_deck(exe, deck, out_dir, name, overrides, mesh=None, sweep=None, statuses=(0,)):
    """Copy DECK with &run variables replaced (OVERRIDES; MESH: &mesh variables; a value None
    removes the variable, the program's default then applies), run it (cwd = the deck's
    folder, for table files), return the output prefix. The paper's figures are drawn with
    the paper's event rules (events = 'paper'; doc/method.md, "Admissible events") unless
    OVERRIDES say otherwise. SWEEP: a &sweep group appended and the copy run with --sweep
    (its outputs are PREFIX.sweep, PREFIX_sweep.h5, PREFIX.ens). STATUSES: the exit statuses
    taken (3: the runtime guard stopped the run; its outputs up to the stop, PREFIX.*.part,
    take their final names)."""
    lines = open(deck).read().splitlines()
    lines = _replace(lines, "run", {"events": "'paper'", **overrides})
    lines = _replace(lines, "mesh", mesh or {})
    copy = os.path.join(out_dir, name + ".nml")
    with open(copy, "w") as f:
        f.write("\n".join(lines) + "\n" + (sweep or ""))
    # file names in a deck are relative to the deck's folder: its load tables go beside the copy
    for table in glob.glob(os.path.join(os.path.dirname(os.path.abspath(deck)), "*.txt")):
        shutil.copy(table, out_dir)
    prefix = os.path.join(out_dir, name)
    cmd = [exe] + (["--sweep"] if sweep else []) + [copy, "--quiet", "--output", prefix]
    r = subprocess.run(cmd, cwd=os.path.dirname(os.path.abspath(deck)), stderr=subprocess.PIPE,
                       text=True)
    if r.returncode == 0 or r.returncode not in statuses:
        sys.stderr.write(r.stderr)
    if r.returncode not in statuses:
        raise subprocess.CalledProcessError(r.returncode, cmd)
    if r.returncode != 0:            # taken: say so on stdout, the program's message shortened
        print(f"{name}: exit {r.returncode}, its outputs up to the stop kept: "
              + " ".join(r.stderr.split())[:160] + " ...")
    for part in glob.glob(glob.escape(prefix) + ".*.part"):
        os.replace(part, part[:-len(".part")])
    return prefix


def _replace(lines, group, values):
    """LINES of a deck with the variables of VALUES set in &GROUP (one per line, first in
    the group; None: the variable left out)."""
    out, inside = [], False
    for line in lines:
        stripped = line.strip().lower()
        if re.match(rf"&{group}\b", stripped):
            inside = True
            out.append(line)
            out.extend(f"  {k} = {v}" for k, v in values.items() if v is not None)
            continue
        if inside and stripped.startswith("/"):
            inside = False
        if inside and any(re.match(rf"{k}\s*=", stripped) for k in values):
            continue
        out.append(line)
    return out


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


FIG13_MESHES = (19, 95, 190)          # cells per h of the ensembles
FIG13_RULE_CELLS = 95                  # the mesh of the rule band
FIG13_REALIZATIONS = 32                # per mesh (--realizations)
FIG13_SPREAD = 1.0e-3                  # p0 x (1 + spread u), u uniform in (-1, 1)
FIG13_COLORS = ("tab:blue", "tab:orange", "tab:green")
FIG13_TIMINGS = ("accelerate", "delay", "min")
FIG13_SHIFTS = ("above", "fragment", "face")
FIG13_SHIFT_COLORS = {"above": "tab:red", "fragment": "tab:purple", "face": "tab:brown"}
FIG13_TIMING_STYLES = {"accelerate": "-", "delay": "--", "min": ":"}


def fig13(exe, indir, out, realizations=FIG13_REALIZATIONS):
    """Example 3 case 2 under the admissible event rules: what is and is not known (doc/
    validation.md, "Case 2 answered"). Left: ensembles of the default rules on h/19, h/95,
    h/190 (p0 perturbed; mean, mean +- std, min..max, each mesh's predictability horizon);
    right: one unperturbed run per timing x shift rule on h/95 and the band across them.
    Rows: the base impulse I = -i_support, I minus the h/95 ensemble mean, e_lost_w."""
    deck = os.path.join(indir, "example3_case2", "accelerate_above_h19.nml")
    common = {"profile_times": None, "warnings": ".false."}
    sweep = (f"&sweep\n  perturb = 'p0'\n  spread = {FIG13_SPREAD!r}\n  realizations = "
             f"{realizations}\n  seed = 2026\n  ensemble_columns = 'reaction_bottom', "
             "'e_lost_w', 'i_support'\n/\n")
    ens = []
    for cells in FIG13_MESHES:      # the deck's rules left out: the program's defaults
        prefix = run_deck(exe, deck, out, f"fig13_ensemble_h{cells}",
                          {**common, "events": None, "timing": None, "shift": None,
                           "title": f"'case 2 ensemble, default rules, h/{cells}'"},
                          mesh={"cells": cells}, sweep=sweep)
        ens.append(ensemble.load(prefix))
    default = _fig13_default_rule(prefix)
    rules = []
    for timing in FIG13_TIMINGS:
        for shift in FIG13_SHIFTS:
            prefix = run_deck(exe, deck, out, f"fig13_rule_{timing}_{shift}",
                              {**common, "events": "'admissible'", "timing": f"'{timing}'",
                               "shift": f"'{shift}'"}, mesh={"cells": FIG13_RULE_CELLS},
                              statuses=(0, 3))
            rules.append((timing, shift, spbread.load(prefix)))
    ref = ens[FIG13_MESHES.index(FIG13_RULE_CELLS)]
    ref_t, ref_i = ref.t, -ref.stats["i_support"]["mean"]
    t_end = float(ref.t[-1]) if len(ref.t) else 0.0
    fig = plt.figure(figsize=(13, 12.5))
    grid = fig.add_gridspec(4, 2, height_ratios=[1.1, 1.2, 1.2, 0.62])
    axes = np.array([[fig.add_subplot(grid[r, c]) for c in range(2)] for r in range(3)])
    for r in range(3):
        if r != 1:                  # I - I_ref: each column its own scale
            axes[r, 1].sharey(axes[r, 0])
        for c in range(2):
            axes[r, c].sharex(axes[0, 0])
    left = _fig13_ensembles(axes[:, 0], ens, ref_t, ref_i)
    right = _fig13_rules(axes[:, 1], rules, ref, ref_t, ref_i, t_end)
    for ax in axes.flat:
        ax.axhline(0.0, color="0.6", lw=0.4)
        ax.set_xlim(0.0, t_end if t_end > 0 else None)
    for c in range(2):
        axes[2, c].set_xlabel("t [s]")
    for r in (0, 2):
        axes[r, 1].tick_params(labelleft=False)
    axes[0, 0].set_title(f"(a) default rules ({default}), ensembles of {realizations} "
                         "realizations on three meshes", fontsize=8, loc="left")
    axes[0, 1].set_title(f"(b) every timing x shift rule, one run each, h/{FIG13_RULE_CELLS}",
                         fontsize=8, loc="left")
    text = _fig13_caption(ens, left, right, realizations)
    cap = fig.add_subplot(grid[3, :])
    cap.axis("off")
    cap.text(0.0, 1.0, "\n".join(textwrap.fill(p, 180) for p in text.split("\n")), fontsize=8,
             va="top", ha="left", transform=cap.transAxes)
    fig.suptitle("Fig. 13 - Example 3, case 2 (zero tensile strength, admissible event rules): "
                 "the trajectory is known up to its horizon; beyond it only statistics",
                 fontsize=9)
    if not (left["drawn"] and right["drawn"]):
        nothing_to_draw("fig13: no base impulse and no event loss in any run (no base "
                        "contact, no event)")
    print("fig13: " + " ".join(text.split()))
    save(fig, os.path.join(out, "fig13.png"))


def _fig13_default_rule(prefix):
    """'timing/shift' that a deck without them gets (from PREFIX_sweep.h5 /deck/run)."""
    import h5py
    with h5py.File(prefix + "_sweep.h5", "r") as h:
        a = h["deck/run"].attrs
        return f"{spbread.deck_value(a['timing'])}/{spbread.deck_value(a['shift'])}"


def _fig13_horizon(e):
    """The predictability horizon of an ensemble [s]: its base reaction's (None: not
    reached, or no window)."""
    h = e.horizon.get("reaction_bottom")
    return h if h is not None and np.isfinite(h) else None


def _fig13_ensembles(axes, ens, ref_t, ref_i):
    """(a): per mesh the mean of I, of I - the reference and of e_lost_w, with the bands
    mean +- std (darker) and min..max (lighter), and the horizon (dotted)."""
    at_end, drawn = [], False
    for cells, e, color in zip(FIG13_MESHES, ens, FIG13_COLORS):
        s_i, s_e = e.stats["i_support"], e.stats["e_lost_w"]
        rows = {"I": (-s_i["mean"], s_i["std"], -s_i["max"], -s_i["min"]),
                "e": (s_e["mean"], s_e["std"], s_e["min"], s_e["max"])}
        shift = np.interp(e.t, ref_t, ref_i) if len(ref_t) else np.zeros(len(e.t))
        axes[0].plot(e.t, rows["I"][0], color=color, lw=0.9, label=f"h/{cells}")
        for ax, (mean, std, lo, hi), sub in ((axes[1], rows["I"], shift),
                                             (axes[2], rows["e"], 0.0)):
            ax.fill_between(e.t, lo - sub, hi - sub, color=color, alpha=0.12, lw=0)
            ax.fill_between(e.t, mean - std - sub, mean + std - sub, color=color, alpha=0.35,
                            lw=0)
            ax.plot(e.t, mean - sub, color=color, lw=0.8)
        h = _fig13_horizon(e)
        for ax in axes:
            if h is not None:
                ax.axvline(h, color=color, ls=":", lw=1.2)
        drawn = drawn or bool(np.any(rows["I"][0] != 0.0) or np.any(rows["e"][0] != 0.0))
        k = len(e.t) - 1
        at_end.append((cells, h, *(float(v[k]) + 0.0 if k >= 0 else float("nan")
                                   for v in (rows["I"][0], rows["I"][1], rows["e"][0],
                                             rows["e"][1]))))
    axes[0].set_ylabel("base impulse I = -i_support\n[kg/(m s)]", fontsize=8)
    axes[1].set_ylabel(f"I - I_ref [kg/(m s)]\n(I_ref: ensemble mean, h/{FIG13_RULE_CELLS})",
                       fontsize=8)
    axes[2].set_ylabel("e_lost_w: energy the events\nremove [J/m²]", fontsize=8)
    handles = [plt.Line2D([], [], color=c, lw=0.9, label=f"h/{n}: mean")
               for n, c in zip(FIG13_MESHES, FIG13_COLORS)]
    handles += [plt.matplotlib.patches.Patch(color="0.4", alpha=0.5, label="mean ± std"),
                plt.matplotlib.patches.Patch(color="0.4", alpha=0.15, label="min .. max"),
                plt.Line2D([], [], color="0.3", ls=":", lw=1.2,
                           label="horizon of each mesh (base reaction)")]
    axes[0].legend(handles=handles, fontsize=7, loc="upper left", ncol=2, framealpha=0.9)
    return dict(at_end=at_end, drawn=drawn)


def _fig13_rules(axes, rules, ref, ref_t, ref_i, t_end):
    """(b): I, I - the reference and e_lost_w of every rule (thin lines; rules whose runs
    agree in every row drawn once), the min..max band over the runs that reach t_end, the
    reference ensemble's mean +- std and horizon; a run the position guard stopped up to
    its stop (a cross)."""
    groups = []                     # [[(timing, shift), ...], run, timing, shift]
    for timing, shift, run in rules:
        h = run.history
        for g in groups:
            o = g[1].history
            if len(o["t"]) == len(h["t"]) and all(np.array_equal(o[c], h[c]) for c in
                                                  ("t", "i_support", "e_lost_w")):
                g[0].append((timing, shift))
                break
        else:
            groups.append([[(timing, shift)], run, timing, shift])
    full = [g for g in groups if len(g[1].history["t"]) and
            g[1].history["t"][-1] >= t_end * (1 - 1e-9)]
    band, stopped, drawn = {}, [], False
    for labels, run, timing, shift in groups:
        h = run.history
        t, i_base, e_lost = h["t"], -h["i_support"], h["e_lost_w"]
        shift_i = np.interp(t, ref_t, ref_i) if len(ref_t) else np.zeros(len(t))
        name = _fig13_rule_names(labels) + (" (identical)" if len(labels) > 1 else "")
        style = dict(color=FIG13_SHIFT_COLORS[shift], lw=0.8,
                     ls=FIG13_TIMING_STYLES[timing] if len(labels) == 1 else "-")
        ends = len(t) and t[-1] < t_end * (1 - 1e-9)
        if ends:
            name += f": stopped at {t[-1]:.3f} s (position guard, exit 3)"
            stopped.append((timing, shift, float(t[-1])))
        for ax, y in zip(axes, (i_base, i_base - shift_i, e_lost)):
            ax.plot(t, y, label=name if ax is axes[0] else None, **style)
            if ends:
                ax.plot(t[-1], y[-1], "x", color=style["color"], ms=6)
        drawn = drawn or bool(np.any(i_base != 0.0) or np.any(e_lost != 0.0))
    if full:
        t = full[0][1].history["t"]
        for key, values in (("I", [-g[1].history["i_support"] for g in full]),
                            ("e", [g[1].history["e_lost_w"] for g in full])):
            v = np.array([np.interp(t, g[1].history["t"], x) for g, x in zip(full, values)])
            band[key] = (v.min(axis=0), v.max(axis=0))
        sub = np.interp(t, ref_t, ref_i) if len(ref_t) else 0.0
        for ax, (lo, hi), s in ((axes[0], band["I"], 0.0), (axes[1], band["I"], sub),
                                (axes[2], band["e"], 0.0)):
            ax.fill_between(t, lo - s, hi - s, color="0.5", alpha=0.2, lw=0,
                            label=(f"min .. max over the {len(full)} distinct rules that "
                                   f"reach {t_end:.1f} s") if ax is axes[0] else None)
    std = ref.stats["i_support"]["std"]
    color = FIG13_COLORS[FIG13_MESHES.index(FIG13_RULE_CELLS)]
    axes[1].fill_between(ref_t, -std, std, color=color, alpha=0.35, lw=0,
                         label=f"default-rule ensemble h/{FIG13_RULE_CELLS}: ± std")
    axes[1].legend(fontsize=7, loc="lower left", framealpha=0.9)
    axes[1].set_ylabel("I - I_ref [kg/(m s)]", fontsize=8)
    h = _fig13_horizon(ref)
    for ax in axes:
        if h is not None:
            ax.axvline(h, color=color, ls=":", lw=1.2)
    axes[0].legend(fontsize=6.5, loc="lower right", framealpha=0.9,
                   title="timing / shift (lines: - accelerate, -- delay, : min)",
                   title_fontsize=6.5)
    k = {key: (float(lo[-1]) + 0.0, float(hi[-1]) + 0.0) for key, (lo, hi) in band.items()}
    merged = [_fig13_rule_names(g[0]) for g in groups if len(g[0]) > 1]
    return dict(band=k, stopped=stopped, drawn=drawn, distinct=len(groups), merged=merged)


def _fig13_rule_names(pairs):
    """'accelerate, delay / above' for rules of one shift, else 'accelerate/above, ...'."""
    if len({s for _, s in pairs}) == 1:
        return f"{', '.join(t for t, _ in pairs)} / {pairs[0][1]}"
    return ", ".join(f"{t}/{s}" for t, s in pairs)


def _fig13_caption(ens, left, right, realizations):
    """What the figure shows, with the numbers read from it."""
    per_mesh = "; ".join(
        f"h/{n}: horizon {'-' if h is None else f'{h:.3f} s'}, I {i:.0f} ± {si:.0f}, "
        f"e_lost_w {e:.1f} ± {se:.1f}" for n, h, i, si, e, se in left["at_end"])
    band = right["band"]
    i_lo, i_hi = band.get("I", (np.nan, np.nan))
    e_lo, e_hi = band.get("e", (np.nan, np.nan))
    notes = [f"{m}: identical in every row, one line" for m in right["merged"]]
    notes += [f"{tm}/{sh} is stopped by the position guard at {t:.3f} s (exit 3) and drawn "
              "up to there (a cross)" for tm, sh, t in right["stopped"]]
    i_all = np.array([v for _, _, v, _, _, _ in left["at_end"]] + [i_lo, i_hi])
    i_mean = float(np.mean(i_all))
    spread = (i_all.max() - i_all.min()) / i_mean * 100 if i_mean else np.nan
    i_std = max((si / i * 100 for _, _, i, si, _, _ in left["at_end"] if i), default=np.nan)
    return (
        f"(a) {realizations} realizations per mesh, p0 x (1 + {FIG13_SPREAD:g} u), u uniform "
        "in (-1, 1): line the ensemble mean, dark band mean ± std, light band min .. max "
        "(in (a) top the bands are thinner than the lines). Dotted: each mesh's "
        "predictability horizon, the start of the first 1 ms window in which the std over "
        "the realizations of the base reaction's window mean exceeds 1 % of its largest "
        "window mean (&sweep horizon_tol).  "
        f"(b) accelerate, delay, min x above, fragment, face, unperturbed, h/"
        f"{FIG13_RULE_CELLS}: {right['distinct']} distinct runs, grey band min .. max over "
        "them" + "".join(f"; {n}" for n in notes) + ".\n"
        f"At t_end: {per_mesh} (I in kg/(m s), e_lost_w in J/m²). Across the rules at h/"
        f"{FIG13_RULE_CELLS}: I {i_lo:.0f} .. {i_hi:.0f}, e_lost_w {e_lo:.1f} .. "
        f"{e_hi:.1f}.\n"
        "KNOWN: the trajectory up to the horizon (the base reaction over [0, 0.1 s] "
        "converges at order 1.3-1.9 from h/19 to h/760, ctest case2.order); beyond it only "
        f"the statistics: the base impulse at t_end to {spread:.1f} % across meshes and rules "
        f"(ensemble std at most {i_std:.2f} %). NOT KNOWN: the reaction's history beyond the "
        "horizon, and the energy the events remove - e_lost_w is set by the rule ('above' "
        "about 99 % of the load's work on every mesh, 'face' none), not by the continuum "
        "problem.")


FIGURES = (fig07c, fig08b, fig10, fig11, fig12, fig13)


def main():
    p = argparse.ArgumentParser(description="render the paper's figures")
    p.add_argument("--exe", required=True)
    p.add_argument("--input", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--only", nargs="*", choices=[f.__name__ for f in FIGURES],
                   help="a subset, e.g. fig10 fig12")
    p.add_argument("--realizations", type=int, default=FIG13_REALIZATIONS,
                   help=f"fig13's ensembles: realizations per mesh (default "
                   f"{FIG13_REALIZATIONS})")
    args = p.parse_args()
    if args.realizations < 1:
        p.error(f"--realizations must be at least 1, got {args.realizations}")
    os.makedirs(args.out, exist_ok=True)
    for fig in FIGURES:
        if not args.only or fig.__name__ in args.only:
            extra = {"realizations": args.realizations} if fig is fig13 else {}
            fig(os.path.abspath(args.exe), os.path.abspath(args.input), os.path.abspath(args.out),
                **extra)


if __name__ == "__main__":
    main()
