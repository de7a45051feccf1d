"""A striking mass's blows: its contact force and its velocity over time (&impactor).

usage: blows.py PREFIX [PREFIX ...] [--label L ...] [--t-min T] [--t-max T]
                [--units ms,kPa] -o blows.png

Top panel: f_impactor (the contact force's mean over each step: N, or Pa when every area
is 1), with the impacts (triangles) and releases (circles) of PREFIX.evt; bottom panel:
v_impactor (m/s along +x, down). A run without a striking mass (or one that never
strikes) still gets its figure, with the line 'blows.py: warning: nothing to draw: ...' on
stderr; the exit status stays 0. The time axis is in ms unless --units says otherwise; a
stress unit of --units (kPa, MPa, ...) gives a force its prefix (kN, MN, ...) (the options:
doc/outputs.md, "Plots").
"""
import os
import re

import numpy as np

from _common import View, load_runs, nothing_to_draw, parse, parser, plt, save


def force_unit(prefix):
    """'N' where f_impactor is a force (some area is not 1), else 'Pa': the unit the run
    wrote for it (/history/f_impactor's units attribute, or the '# units:' line)."""
    if os.path.exists(prefix + ".h5"):
        import h5py
        with h5py.File(prefix + ".h5", "r") as f:
            if "history/f_impactor" in f:
                unit = f["history/f_impactor"].attrs.get("units", b"")
                return "N" if (unit.decode() if isinstance(unit, bytes) else str(unit)) == "N" \
                    else "Pa"
        return "Pa"
    with open(prefix + ".his") as f:
        for line in f:
            m = re.search(r"f_impactor \[([^]]*)\]", line) if line.startswith("# units") else None
            if m:
                return "N" if m.group(1) == "N" else "Pa"
    return "Pa"

STYLES = ["-", ":", "--", "-."]


def plot(runs, labels, axes, view=None):
    """The blows of every run on the two axes (force, velocity), over the view's window."""
    view = view or View()
    ax_f, ax_v = axes
    rows = [view.keep(r.history.get("t", [])) for r in runs]
    forces = [np.asarray(r.history.get("f_impactor", []), float)[k] if "f_impactor" in
              r.history else np.zeros(0) for r, k in zip(runs, rows)]
    if not any(len(f) and np.any(f != 0.0) for f in forces):
        nothing_to_draw("f_impactor is 0 in every row (no &impactor, or it never strikes)")
    scale, unit = view.stress_scale(np.concatenate(forces) if forces else [])
    if all(force_unit(r.prefix) == "N" for r in runs):
        unit = unit.replace("Pa", "N")   # forces: N, kN, MN, GN by the same steps
    for k, (run, label) in enumerate(zip(runs, labels)):
        h = run.history
        if "f_impactor" not in h:
            continue
        t = view.t(h["t"][rows[k]])
        line, = ax_f.plot(t, np.asarray(h["f_impactor"])[rows[k]] / scale,
                          STYLES[k % len(STYLES)], lw=0.9, label=label)
        ax_v.plot(t, np.asarray(h["v_impactor"])[rows[k]], STYLES[k % len(STYLES)], lw=0.9,
                  color=line.get_color())
        ev = run.events
        if "kind" in ev and len(ev["kind"]):
            for kind, marker in (("impact", "v"), ("release", "o")):
                t = np.asarray(ev["t"])[np.asarray(ev["kind"]) == kind]
                t = t[view.keep(t)]
                if len(t):
                    ax_f.plot(view.t(t), np.zeros_like(t), marker, ms=4, mfc="none",
                              color=line.get_color())
    ax_f.set_ylabel(f"f impactor [{unit}]")
    ax_v.set_ylabel("v impactor [m/s]")
    ax_v.set_xlabel(view.t_label())
    view.t_limits(ax_v)
    ax_f.legend(fontsize=8, loc="best", framealpha=0.85)


def main():
    args = parse(parser(__doc__))
    runs, labels = load_runs(args)
    fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    plot(runs, labels, axes, args.view)
    axes[0].set_title(args.title or runs[0].title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
