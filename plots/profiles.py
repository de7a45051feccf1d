"""Stress profiles of a run at its profile times (the discrete stairs, half-node rows).

usage: profiles.py PREFIX -o profiles.png

Without profiles (no &run profile_times) the figure is written empty, with the line
'profiles.py: warning: nothing to draw: ...' on stderr; the exit status stays 0.
"""
import numpy as np

from _common import nothing_to_draw, parser, plt, save, spbread, stress_scale


def plot(run, ax, scale=None, unit=None):
    """The run's profiles; the unit (Pa, kPa, MPa, GPa) by their largest stress unless given."""
    if not run.profiles:
        nothing_to_draw("no stress profiles (give &run profile_times in the deck)")
    if scale is None:
        scale, unit = stress_scale(np.concatenate([p["stress"] for p in run.profiles] or [[0.0]]))
    cmap = plt.get_cmap("viridis")
    n = max(1, len(run.profiles) - 1)
    for k, p in enumerate(run.profiles):
        ax.step(p["x"], p["stress"] / scale, where="post", color=cmap(k / n), lw=1.0,
                label=f"t = {p['t'] * 1e3:.4g} ms")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("x [m] (from the top end)")
    ax.set_ylabel(f"stress [{unit}] (compression > 0)")
    if run.profiles:
        ax.legend(fontsize=7, ncol=2)


def main():
    args = parser(__doc__).parse_args()
    run = spbread.load(args.prefix[0])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    plot(run, ax)
    ax.set_title(args.title or run.title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
