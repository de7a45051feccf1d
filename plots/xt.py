"""x-t diagram of a run: the stress field (PREFIX.h5 with field_every > 0) and the events
(fractures, collisions, separations, base collisions) at their sections and times.

usage: xt.py PREFIX [--t-min T] [--t-max T] [--units us,MPa] -o xt.png

The time axis is in ms unless --units says otherwise (the options: doc/outputs.md,
"Plots"). Without an x-t field (&run hdf5 = .true. with field_every = N) only the events are
drawn, and without events either nothing is; either way the figure is written, with the
line 'xt.py: warning: nothing to draw: ...' on stderr, and the exit status stays 0.
"""
import numpy as np

from _common import View, load, nothing_to_draw, parse, parser, plt, save

MARKERS = {"fracture": ("x", "k"), "collision": ("o", "tab:red"),
           "separation": ("^", "tab:blue"), "base-collision": ("s", "tab:green")}


def plot(run, ax, view=None):
    view = view or View()
    ev = run.events
    in_window = view.keep(ev.get("t", []))
    events = int(in_window.sum())
    rows = view.keep(run.xt["t"]) if run.xt is not None else np.zeros(0, dtype=bool)
    if rows.sum() <= 1:
        nothing_to_draw("no x-t stress field (run with &run hdf5 = .true., field_every = N)"
                        + (" in the time window" if run.xt is not None and len(run.xt["t"]) > 1
                           else "")
                        + (": only the events are drawn" if events else ", and no events"))
    else:
        s = run.xt["stress"][rows]
        lim = np.max(np.abs(s)) or 1.0
        scale, unit = view.stress_scale([lim])
        mesh = ax.pcolormesh(run.xt["x"], view.t(run.xt["t"][rows]), s / scale, cmap="RdBu_r",
                             vmin=-lim / scale, vmax=lim / scale, shading="nearest")
        plt.colorbar(mesh, ax=ax, label=f"stress [{unit}] (compression > 0)")
    if events:
        for kind, (m, c) in MARKERS.items():
            sel = np.array([k == kind for k in ev["kind"]], dtype=bool) & in_window
            if sel.any():
                style = dict(c=c) if m == "x" else dict(facecolors="none", edgecolors=c)
                ax.scatter(ev["x"][sel], view.t(ev["t"][sel]), marker=m, s=14, linewidths=0.8,
                           label=f"{kind} ({sel.sum()})", **style)
        # below the axes, off the field and the markers
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.1),
                  ncol=len(MARKERS), frameon=False)
    ax.set_xlabel("x [m] (from the top end)")
    ax.set_ylabel(view.t_label())
    view.t_limits(ax, "y")


def main():
    args = parse(parser(__doc__))
    run = load(args.prefix[0])
    fig, ax = plt.subplots(figsize=(8, 6))
    plot(run, ax, args.view)
    ax.set_title(args.title or run.title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
