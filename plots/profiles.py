"""Stress profiles of a run at its profile times (the discrete stairs, half-node rows).

usage: profiles.py PREFIX -o profiles.png
"""
import numpy as np

from _common import parser, plt, save, spbread


def plot(run, ax, scale=1.0e6, unit="MPa"):
    cmap = plt.get_cmap("viridis")
    n = max(1, len(run.profiles) - 1)
    for k, p in enumerate(run.profiles):
        ax.step(p["x"], p["stress"] / scale, where="post", color=cmap(k / n), lw=1.0,
                label=f"t = {p['t'] * 1e3:.4g} ms")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("x [m] (from the top end)")
    ax.set_ylabel(f"stress [{unit}] (compression > 0)")
    ax.legend(fontsize=7, ncol=2)


def main():
    args = parser(__doc__).parse_args()
    run = spbread.load(args.prefix[0])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    scale = 1.0e6 if max(np.max(np.abs(p["stress"])) for p in run.profiles) > 1e6 else 1.0e3
    plot(run, ax, scale, "MPa" if scale == 1.0e6 else "kPa")
    ax.set_title(args.title or run.title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
