"""Rear-face velocity of a spall test with its peak and pull-back marked (PREFIX.spl, and a
gauge on the end node: &gauges x = L for the bottom end, x = 0 for the top).

usage: spall.py PREFIX [PREFIX ...] [--label L ...] [--t-min T] [--t-max T] [--units us]
                -o spall.png

For every end that has a row in PREFIX.spl (or /spall of PREFIX.h5) and a gauge on its
node, the end's velocity along its outward normal (as PREFIX.spl gives it: v at the bottom,
-v at the top; doc/outputs.md, "PREFIX.spl"), with the peak (triangle) and the pull-back
(circle) marked and the Novikov strength, the spall plane and the scab's velocity in the
legend; the pull-back's Delta v as a vertical bar. The time axis is in ms unless --units
says otherwise (the options: doc/outputs.md, "Plots"). With no such end (no gauge on an end
node, a run before issue 35, or no rows in the time window) the figure is still written,
with the line 'spall.py: warning: nothing to draw: ...' on stderr; the exit status stays 0.
"""
import math

import numpy as np

from _common import View, load_runs, nothing_to_draw, parse, parser, plt, save

STYLES = ["-", "--", ":", "-."]


def ends_to_draw(run, view):
    """(end, gauge index, row of .spl, rows in the window) of each end the run can show."""
    out = []
    if run.spall is None or run.gauges is None:
        return out
    rows = view.keep(run.gauges["t"])
    for k, end in enumerate(run.spall["end"]):
        if end in run.gauges["end"] and rows.any():
            out.append((end, run.gauges["end"].index(end), k, rows))
    return out


def number(x, fmt):
    """A value of PREFIX.spl for the legend ('none' for NaN)."""
    return "none" if math.isnan(x) else format(x, fmt)


def plot(runs, labels, ax, view=None):
    """Draw each run's ends; the number of curves drawn."""
    view = view or View()
    drawn = 0
    for r, (run, label) in enumerate(zip(runs, labels)):
        for end, g, k, rows in ends_to_draw(run, view):
            sign = 1.0 if end == "bottom" else -1.0
            t = run.gauges["t"][rows]
            w = sign * run.gauges["velocity"][rows, g]
            s = {name: float(col[k]) for name, col in run.spall.items() if name != "end"}
            color = f"C{drawn % 10}"
            name = f"{end} end" if len(runs) == 1 else f"{label}: {end} end"
            ax.plot(view.t(t), w, STYLES[r % len(STYLES)], lw=1.0, color=color,
                    label=f"{name}: sigma_Novikov {number(s['sigma_novikov'] / 1e6, '.3g')} "
                          f"MPa, spall plane x = {number(s['spall_x'], '.4g')} m, scab "
                          f"{number(s['scab_velocity'], '.3g')} m/s")
            for tk, vk, mark, what in ((s["t_peak"], s["v_peak"], "^", "peak"),
                                       (s["t_pullback"], s["v_pullback"], "o", "pull-back")):
                if not math.isnan(tk) and view.keep([tk])[0]:
                    ax.plot(view.t([tk]), [vk], mark, ms=7, mfc="none", color=color,
                            label=f"{name}: {what} {vk:.3g} m/s")
            if not math.isnan(s["t_pullback"]) and view.keep([s["t_pullback"]])[0]:
                ax.vlines(view.t([s["t_pullback"]]), s["v_pullback"], s["v_peak"],
                          colors=color, linestyles=":", lw=0.8)
            drawn += 1
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel(view.t_label())
    ax.set_ylabel("velocity of the end, outward [m/s]")
    view.t_limits(ax)
    if drawn:
        ax.legend(fontsize=7)
    return drawn


def main():
    args = parse(parser(__doc__))
    runs, labels = load_runs(args)
    fig, ax = plt.subplots(figsize=(9, 5))
    if plot(runs, labels, ax, args.view) == 0:
        if all(r.spall is None for r in runs):
            nothing_to_draw("no PREFIX.spl or /spall in " + ", ".join(args.prefix) +
                            " (a run before issue 35, or one that did not complete)")
        else:
            nothing_to_draw("no gauge on a free end's node in " + ", ".join(args.prefix) +
                            " with rows in the time window (give &gauges x = 0 or the bar's "
                            "length)")
    ax.set_title(args.title or runs[0].title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
