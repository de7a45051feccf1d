"""Base (bottom support) reaction history of one or more runs, overlaid.

usage: reaction.py PREFIX [PREFIX ...] [--label L ...] [--t-min T] [--t-max T]
                   [--units s,kPa] -o reaction.png

The time axis is in ms unless --units says otherwise (the options: doc/outputs.md,
"Plots"). When the reaction is 0 in every history row of every run (no support at the
bottom, or the bar never touches it) the figure is still written, with the line
'reaction.py: warning: nothing to draw: ...' on stderr; the exit status stays 0.
"""
import numpy as np

from _common import View, load_runs, nothing_to_draw, parse, parser, plt, save

STYLES = ["-", ":", "--", "-."]


def plot(runs, labels, ax, column="reaction_bottom", scale=None, unit=None, colors=None,
         legend=True, view=None):
    """Overlay the runs' column over the view's time window; its unit (Pa, kPa, MPa, GPa)
    the view's or chosen by its largest value unless SCALE and UNIT are given; COLORS: one
    per run (default: the colour cycle)."""
    view = view or View()
    rows = [view.keep(r.history.get("t", [])) if column in r.history else None for r in runs]
    values = [np.asarray(r.history[column], float)[k] for r, k in zip(runs, rows)
              if k is not None]
    if not any(len(v) for v in values):
        nothing_to_draw(f"no history rows with {column}"
                        + (" in the time window" if any(len(r.history.get(column, []))
                                                        for r in runs) else ""))
    elif not any(np.any(v != 0.0) for v in values):
        nothing_to_draw(f"{column} is 0 in every row (no support at that end?)")
    if scale is None:
        scale, unit = view.stress_scale(np.concatenate(values or [[]]))
    for k, (run, label) in enumerate(zip(runs, labels)):
        h = run.history
        if column not in h:
            continue
        style = dict(color=colors[k]) if colors else {}
        ax.plot(view.t(h["t"][rows[k]]), h[column][rows[k]] / scale, STYLES[k % len(STYLES)],
                lw=0.9, label=label, **style)
    ax.set_xlabel(view.t_label())
    ax.set_ylabel(f"{column.replace('_', ' ')} [{unit}]")
    view.t_limits(ax)
    if legend:
        ax.legend(fontsize=8, loc="best", framealpha=0.85)


def main():
    args = parse(parser(__doc__))
    runs, labels = load_runs(args)
    fig, ax = plt.subplots(figsize=(9, 4))
    plot(runs, labels, ax, view=args.view)
    ax.set_title(args.title or runs[0].title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
