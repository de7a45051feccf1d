"""Stress profiles of a run at its profile times (the discrete stairs, half-node rows).

usage: profiles.py PREFIX [--t-min T] [--t-max T] [--units us,MPa] -o profiles.png

--t-min/--t-max keep the profiles whose times lie between them; the legend gives the times
in ms unless --units says otherwise (the options: doc/outputs.md, "Plots"). Without
profiles (no &run profile_times, or none in the time window) the figure is written empty,
with the line 'profiles.py: warning: nothing to draw: ...' on stderr; the exit status stays
0.
"""
import numpy as np

from _common import View, load, nothing_to_draw, parse, parser, plt, save


def plot(run, ax, scale=None, unit=None, view=None):
    """The run's profiles in the view's time window; the unit (Pa, kPa, MPa, GPa) the view's
    or by their largest stress unless given."""
    view = view or View()
    profiles = [p for p in run.profiles if view.keep(p["t"])]
    if not run.profiles:
        nothing_to_draw("no stress profiles (give &run profile_times in the deck)")
    elif not profiles:
        nothing_to_draw(f"none of the {len(run.profiles)} stress profiles in the time window")
    if scale is None:
        scale, unit = view.stress_scale(np.concatenate([p["stress"] for p in profiles]
                                                       or [[0.0]]))
    cmap = plt.get_cmap("viridis")
    n = max(1, len(profiles) - 1)
    for k, p in enumerate(profiles):
        ax.step(p["x"], p["stress"] / scale, where="post", color=cmap(k / n), lw=1.0,
                label=f"t = {view.t(p['t']):.4g} {view.time_unit}")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("x [m] (from the top end)")
    ax.set_ylabel(f"stress [{unit}] (compression > 0)")
    if profiles:
        ax.legend(fontsize=7, ncol=2)


def main():
    args = parse(parser(__doc__))
    run = load(args.prefix[0])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    plot(run, ax, view=args.view)
    ax.set_title(args.title or run.title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
