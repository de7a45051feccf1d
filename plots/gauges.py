"""Gauge histories (&gauges: PREFIX.gau or /gauges of PREFIX.h5): one panel per quantity
(stress, velocity, displacement), one line per gauge labelled with its position x.

usage: gauges.py PREFIX [PREFIX ...] [--label L ...] -o gauges.png
"""
import sys

from _common import parser, plt, save, spbread

STYLES = ["-", ":", "--", "-."]
PANELS = [("stress", 1.0e6, "stress [MPa] (compression > 0)"),
          ("velocity", 1.0, "velocity [m/s] (along +x, down)"),
          ("u", 1.0e-3, "u [mm]")]


def plot(runs, labels, axes):
    """Draw every gauge of every run; the number of lines drawn."""
    drawn = 0
    for r, (run, label) in enumerate(zip(runs, labels)):
        g = run.gauges
        if g is None or len(g["t"]) == 0 or len(g["x"]) == 0:
            continue
        for k, x in enumerate(g["x"]):
            name = f"x = {x:g} m" if len(runs) == 1 else f"{label}: x = {x:g} m"
            for ax, (q, scale, _) in zip(axes, PANELS):
                ax.plot(g["t"], g[q][:, k] / scale, STYLES[r % len(STYLES)], lw=0.9,
                        color=f"C{k % 10}", label=name)
            drawn += 1
    for ax, (_, _, ylabel) in zip(axes, PANELS):
        ax.set_ylabel(ylabel)
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
        print("gauges.py: warning: nothing to draw: no gauges in " + ", ".join(args.prefix) +
              " (give &gauges x = ... in the deck)", file=sys.stderr)
    axes[0].set_title(args.title or runs[0].title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
