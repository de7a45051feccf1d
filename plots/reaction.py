"""Base (bottom support) reaction history of one or more runs, overlaid.

usage: reaction.py PREFIX [PREFIX ...] [--label L ...] -o reaction.png
"""
from _common import parser, plt, save, spbread

STYLES = ["-", ":", "--", "-."]


def plot(runs, labels, ax, column="reaction_bottom", scale=1.0e3, unit="kPa"):
    for k, (run, label) in enumerate(zip(runs, labels)):
        h = run.history
        ax.plot(h["t"], h[column] / scale, STYLES[k % len(STYLES)], lw=0.9, label=label)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(f"{column.replace('_', ' ')} [{unit}]")
    ax.legend(fontsize=8)


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
