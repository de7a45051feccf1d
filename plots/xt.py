"""x-t diagram of a run: the stress field (PREFIX.h5 with field_every > 0) and the events
(fractures, collisions, separations, base collisions) at their sections and times.

usage: xt.py PREFIX -o xt.png

Without an x-t field (&run hdf5 = .true. with field_every = N) only the events are drawn,
and without events either nothing is; either way the figure is written, with the line
'xt.py: warning: nothing to draw: ...' on stderr, and the exit status stays 0.
"""
import numpy as np

from _common import nothing_to_draw, parser, plt, save, spbread, stress_scale

MARKERS = {"fracture": ("x", "k"), "collision": ("o", "tab:red"),
           "separation": ("^", "tab:blue"), "base-collision": ("s", "tab:green")}


def plot(run, ax):
    events = len(run.events.get("t", []))
    if run.xt is None or len(run.xt["t"]) <= 1:
        nothing_to_draw("no x-t stress field (run with &run hdf5 = .true., field_every = N)"
                        + (": only the events are drawn" if events else ", and no events"))
    else:
        s = run.xt["stress"]
        lim = np.max(np.abs(s)) or 1.0
        scale, unit = stress_scale([lim])
        mesh = ax.pcolormesh(run.xt["x"], run.xt["t"] * 1e3, s / scale, cmap="RdBu_r",
                             vmin=-lim / scale, vmax=lim / scale, shading="nearest")
        plt.colorbar(mesh, ax=ax, label=f"stress [{unit}] (compression > 0)")
    ev = run.events
    if events:
        for kind, (m, c) in MARKERS.items():
            sel = np.array([k == kind for k in ev["kind"]], dtype=bool)
            if sel.any():
                style = dict(c=c) if m == "x" else dict(facecolors="none", edgecolors=c)
                ax.scatter(ev["x"][sel], ev["t"][sel] * 1e3, marker=m, s=14, linewidths=0.8,
                           label=f"{kind} ({sel.sum()})", **style)
        # below the axes, off the field and the markers
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.1),
                  ncol=len(MARKERS), frameon=False)
    ax.set_xlabel("x [m] (from the top end)")
    ax.set_ylabel("t [ms]")


def main():
    args = parser(__doc__).parse_args()
    run = spbread.load(args.prefix[0])
    fig, ax = plt.subplots(figsize=(8, 6))
    plot(run, ax)
    ax.set_title(args.title or run.title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
