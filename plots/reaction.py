"""Base (bottom support) reaction history of one or more runs, overlaid.

usage: reaction.py PREFIX [PREFIX ...] [--label L ...] -o reaction.png

When the reaction is 0 in every history row of every run (no support at the bottom, or
the bar never touches it) the figure is still written, with the line 'reaction.py:
warning: nothing to draw: ...' on stderr; the exit status stays 0.
"""
import numpy as np

from _common import nothing_to_draw, parser, plt, save, spbread, stress_scale

STYLES = ["-", ":", "--", "-."]


def plot(runs, labels, ax, column="reaction_bottom", scale=None, unit=None, colors=None,
         legend=True):
    """Overlay the runs' column; its unit (Pa, kPa, MPa, GPa) chosen by its largest value
    unless SCALE and UNIT are given; COLORS: one per run (default: the colour cycle)."""
    if not any(len(r.history.get(column, [])) for r in runs):
        nothing_to_draw(f"no history rows with {column}")
    elif not any(np.any(np.asarray(r.history[column]) != 0.0) for r in runs):
        nothing_to_draw(f"{column} is 0 in every row (no support at that end?)")
    if scale is None:
        scale, unit = stress_scale(np.concatenate([np.asarray(r.history.get(column, []), float)
                                                   for r in runs]))
    for k, (run, label) in enumerate(zip(runs, labels)):
        h = run.history
        if column not in h:
            continue
        style = dict(color=colors[k]) if colors else {}
        ax.plot(h["t"], h[column] / scale, STYLES[k % len(STYLES)], lw=0.9, label=label, **style)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(f"{column.replace('_', ' ')} [{unit}]")
    if legend:
        ax.legend(fontsize=8, loc="best", framealpha=0.85)


def main():
    args = parser(__doc__).parse_args()
    runs = [spbread.load(p) for p in args.prefix]
    labels = args.label or [r.title or r.prefix for r in runs]
    fig, ax = plt.subplots(figsize=(9, 4))
    plot(runs, labels, ax)
    ax.set_title(args.title or runs[0].title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
