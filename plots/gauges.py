"""Gauge histories (&gauges: PREFIX.gau or /gauges of PREFIX.h5): one panel per quantity
(stress, velocity, displacement), one line per gauge labelled with its position x.

usage: gauges.py PREFIX [PREFIX ...] [--label L ...] [--t-min T] [--t-max T]
                 [--units ms,MPa] [--gauges 1,3] -o gauges.png

--gauges picks gauges by their number in PREFIX.gau (stress_1 is gauge 1; a number beyond
the run's gauges is an error, exit 2); the time axis
is in ms unless --units says otherwise (the options: doc/outputs.md, "Plots"). Without
gauges (no &gauges in the deck, or no rows in the time window) the figure is still
written, with the line 'gauges.py: warning: nothing to draw: ...' on stderr; the exit
status stays 0.
"""
import numpy as np

from _common import View, fail, load_runs, nothing_to_draw, parse, parser, plt, save

STYLES = ["-", ":", "--", "-."]
# quantity, divisor, axis label; the stress unit (Pa ... GPa) by the largest reading
PANELS = [("stress", None, "stress [{unit}] (compression > 0)"),
          ("velocity", 1.0, "velocity [m/s] (along +x, down)"),
          ("u", 1.0e-3, "u [mm]")]


def chosen(run, view):
    """The run's gauges to draw (0-based) and its rows in the time window."""
    g = run.gauges
    if g is None:
        return [], np.zeros(0, dtype=bool)
    ks = range(len(g["x"])) if view.gauges is None else \
        [k - 1 for k in view.gauges if k <= len(g["x"])]
    return list(ks), view.keep(g["t"])


def plot(runs, labels, axes, view=None):
    """Draw the chosen gauges of every run; the number of lines drawn."""
    view = view or View()
    drawn = 0
    picks = [chosen(run, view) for run in runs]
    shown = [r for r, (ks, rows) in enumerate(picks) if ks and rows.any()]
    stress, unit = view.stress_scale(np.concatenate(
        [np.ravel(runs[r].gauges["stress"][picks[r][1]][:, picks[r][0]]) for r in shown]
        or [[0.0]]))
    for r, (run, label) in enumerate(zip(runs, labels)):
        if r not in shown:
            continue
        g, (ks, rows) = run.gauges, picks[r]
        for k in ks:
            x = g["x"][k]
            name = f"gauge {k + 1}: x = {x:g} m" if len(runs) == 1 else \
                f"{label}: gauge {k + 1}, x = {x:g} m"
            for ax, (q, scale, _) in zip(axes, PANELS):
                ax.plot(view.t(g["t"][rows]), g[q][rows, k] / (scale or stress),
                        STYLES[r % len(STYLES)], lw=0.9, color=f"C{k % 10}", label=name)
            drawn += 1
    for ax, (_, _, ylabel) in zip(axes, PANELS):
        ax.set_ylabel(ylabel.format(unit=unit))
    axes[-1].set_xlabel(view.t_label())
    view.t_limits(axes[-1])
    if drawn:
        axes[0].legend(fontsize=7, ncol=2)
    return drawn


def main():
    args = parse(parser(__doc__, gauges=True))
    runs, labels = load_runs(args)
    most = max([len(r.gauges["x"]) for r in runs if r.gauges is not None] or [0])
    if args.gauges and most and max(args.gauges) > most:
        fail(f"--gauges {max(args.gauges)}: {', '.join(args.prefix)} "
             f"{'has' if len(runs) == 1 else 'have'} {most} gauge{'s' if most > 1 else ''}")
    fig, axes = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
    if plot(runs, labels, axes, args.view) == 0:
        if any(r.gauges is not None and len(r.gauges["x"]) for r in runs):
            nothing_to_draw("no gauge rows of " + ", ".join(args.prefix) + " in the chosen "
                            "gauges and time window")
        else:
            nothing_to_draw("no gauges in " + ", ".join(args.prefix) +
                            " (give &gauges x = ... in the deck)")
    axes[0].set_title(args.title or runs[0].title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
