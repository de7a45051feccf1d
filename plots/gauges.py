"""Gauge histories (&gauges: PREFIX.gau or /gauges of PREFIX.h5): one panel per quantity
(stress, velocity, displacement), one line per gauge labelled with its position x.

usage: gauges.py PREFIX [PREFIX ...] [--label L ...] -o gauges.png

Without gauges (no &gauges in the deck, or no rows) the figure is still written, with the
line 'gauges.py: warning: nothing to draw: ...' on stderr; the exit status stays 0.
"""
import numpy as np

from _common import nothing_to_draw, parser, plt, save, spbread, stress_scale

STYLES = ["-", ":", "--", "-."]
# quantity, divisor, axis label; the stress unit (Pa ... GPa) by the largest reading
PANELS = [("stress", None, "stress [{unit}] (compression > 0)"),
          ("velocity", 1.0, "velocity [m/s] (along +x, down)"),
          ("u", 1.0e-3, "u [mm]")]


def plot(runs, labels, axes):
    """Draw every gauge of every run; the number of lines drawn."""
    drawn = 0
    shown = [r for r, run in enumerate(runs) if run.gauges is not None
             and len(run.gauges["t"]) and len(run.gauges["x"])]
    stress, unit = stress_scale(np.concatenate([np.ravel(runs[r].gauges["stress"])
                                                for r in shown] or [[0.0]]))
    for r, (run, label) in enumerate(zip(runs, labels)):
        if r not in shown:
            continue
        g = run.gauges
        for k, x in enumerate(g["x"]):
            name = f"x = {x:g} m" if len(runs) == 1 else f"{label}: x = {x:g} m"
            for ax, (q, scale, _) in zip(axes, PANELS):
                ax.plot(g["t"], g[q][:, k] / (scale or stress), STYLES[r % len(STYLES)],
                        lw=0.9, color=f"C{k % 10}", label=name)
            drawn += 1
    for ax, (_, _, ylabel) in zip(axes, PANELS):
        ax.set_ylabel(ylabel.format(unit=unit))
    axes[-1].set_xlabel("t [s]")
    if drawn:
        axes[0].legend(fontsize=7, ncol=2)
    return drawn


def main():
    args = parser(__doc__).parse_args()
    runs = [spbread.load(p) for p in args.prefix]
    labels = args.label or [r.title or r.prefix for r in runs]
    fig, axes = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
    if plot(runs, labels, axes) == 0:
        nothing_to_draw("no gauges in " + ", ".join(args.prefix) +
                        " (give &gauges x = ... in the deck)")
    axes[0].set_title(args.title or runs[0].title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
