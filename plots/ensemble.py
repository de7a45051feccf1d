"""An ensemble's columns over time (spallbar --sweep with &sweep ensemble_columns; doc/sweeps.md,
"Ensembles"): for each column the mean, the band mean +- std and the envelope min..max over
the realizations, and the predictability horizon (a dotted vertical line), one panel per
column; several sweeps are overlaid, one colour each.

usage: ensemble.py PREFIX [PREFIX ...] [--label L ...] [--t-min T] [--t-max T]
                   [--units s,kPa] -o ensemble.png

PREFIX is the sweep's --output (PREFIX_sweep.h5 is read, else PREFIX.ens; either file itself
is taken as its prefix). The time axis is in ms unless --units says otherwise; a stress
column (unit Pa) in the stress unit asked for or chosen by its largest value, the others
in their own unit. A sweep without an ensemble, or one that cannot be read, ends with one
line 'ensemble.py: error: ...' (exit 2); no rows in the time window: the figure is still
written, with 'ensemble.py: warning: nothing to draw: ...' on stderr.
"""
import os

import numpy as np

from _common import fail, nothing_to_draw, parse, parser, plt, save

STATS = ("mean", "std", "min", "max")


class Ensemble:
    """One sweep's ensemble: t [s], per column its statistics, unit and horizon [s] (None:
    not reached)."""

    def __init__(self, prefix):
        self.prefix, self.title = prefix, ""
        self.t, self.columns, self.stats, self.units, self.horizon = None, [], {}, {}, {}


def _from_h5(ens, path):
    import h5py
    with h5py.File(path, "r") as h:
        if "ensemble" not in h:
            fail(f"{path} has no /ensemble: the sweep had no &sweep ensemble_columns")
        g = h["ensemble"]
        title = h.attrs.get("title", b"")
        ens.title = title.decode() if isinstance(title, bytes) else str(title)
        ens.columns = [c.decode() if isinstance(c, bytes) else str(c) for c in g.attrs["columns"]]
        ens.t = g["t"][()]
        hz = g["horizon"][()]
        for k, c in enumerate(ens.columns):
            ens.stats[c] = {s: g[f"{c}_{s}"][()] for s in STATS}
            unit = g[f"{c}_mean"].attrs.get("units", b"")
            ens.units[c] = unit.decode() if isinstance(unit, bytes) else str(unit)
            ens.horizon[c] = float(hz[k]) if hz[k] >= 0 else None


def _from_text(ens, path):
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("# title: "):
                ens.title = line[9:].strip()
            elif line.startswith("# horizon ") and ":" in line:
                name, rest = line[10:].split(":", 1)
                words = rest.split()
                try:
                    ens.horizon[name] = float(words[0])
                except (ValueError, IndexError):
                    ens.horizon[name] = None
            elif line.startswith("# units: "):
                for part in line[9:].split(";"):
                    if "_* [" in part:
                        name, unit = part.strip().split("_* [", 1)
                        ens.units[name] = unit.rstrip("]")
            elif line.startswith("#"):
                names = line[1:].split()
            elif line.startswith(" ") and line.strip():
                rows.append([float(x) for x in line.split()])
    if not names or names[0] != "t":
        fail(f"{path} is not an ensemble table (PREFIX.ens)")
    data = np.array(rows, dtype=float).reshape(len(rows), len(names))
    ens.t = data[:, 0]
    ens.columns = [n[:-5] for n in names if n.endswith("_mean")]
    for c in ens.columns:
        ens.stats[c] = {s: data[:, names.index(f"{c}_{s}")] for s in STATS}


def load(prefix):
    """The ensemble of a sweep: PREFIX_sweep.h5's /ensemble, else PREFIX.ens; one-line error
    (exit 2) when neither can be read."""
    for ext in ("_sweep.h5", ".ens"):
        if prefix.endswith(ext) and os.path.isfile(prefix):
            prefix = prefix[:-len(ext)]
    ens = Ensemble(prefix)
    h5, text = prefix + "_sweep.h5", prefix + ".ens"
    if not (os.path.isfile(h5) or os.path.isfile(text)):
        fail(f"no ensemble output {prefix}: neither {h5} nor {text} exists (PREFIX is what "
             "spallbar --sweep --output was given, without an extension)")
    try:
        if os.path.isfile(h5):
            _from_h5(ens, h5)
        else:
            _from_text(ens, text)
    except SystemExit:
        raise
    except OSError as e:
        fail(f"cannot read the ensemble {prefix}: {e.strerror or e}"
             + (f": {e.filename}" if getattr(e, "filename", None) else ""))
    except Exception as e:       # a damaged or foreign file: say so on one line
        fail(f"cannot read the ensemble {prefix}: {type(e).__name__}: {e}")
    return ens


def plot(ensembles, labels, axes, view):
    """One panel per column (the first sweep's columns) of AXES: each sweep's mean, mean +-
    std (a band), min..max (dashed) and horizon (dotted) over the view's window. The number
    of rows drawn."""
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    drawn = 0
    for j, (ax, c) in enumerate(zip(axes, ensembles[0].columns)):
        keep = [view.keep(e.t) if c in e.stats else None for e in ensembles]
        unit = ensembles[0].units.get(c, "")
        scale = 1.0
        if unit == "Pa":
            values = np.concatenate([e.stats[c]["max"][k] for e, k in zip(ensembles, keep)
                                     if k is not None] + [[]])
            scale, unit = view.stress_scale(np.abs(values))
        for k, (e, label) in enumerate(zip(ensembles, labels)):
            if keep[k] is None or not np.any(keep[k]):
                continue
            s, t = e.stats[c], view.t(e.t[keep[k]])
            col = colors[k % len(colors)]
            name = f"{label}: " if len(ensembles) > 1 else ""
            mean, std = s["mean"][keep[k]] / scale, s["std"][keep[k]] / scale
            ax.fill_between(t, mean - std, mean + std, color=col, alpha=0.3, lw=0,
                            label=f"{name}mean ± std" if j == 0 else None)
            ax.plot(t, mean, "-", color=col, lw=0.9)
            ax.plot(t, s["min"][keep[k]] / scale, "--", color=col, lw=0.5,
                    label=f"{name}min, max" if j == 0 else None)
            ax.plot(t, s["max"][keep[k]] / scale, "--", color=col, lw=0.5)
            h = e.horizon.get(c)
            if h is not None and view.keep([h])[0]:
                ax.axvline(view.t(h), color=col, ls=":", lw=1.0,
                           label=f"{name}horizon" if j == 0 else None)
            drawn += int(np.count_nonzero(keep[k]))
        ax.set_ylabel(f"{c.replace('_', ' ')} [{unit}]", fontsize=8)
        view.t_limits(ax)
    axes[-1].set_xlabel(view.t_label())
    if drawn:
        axes[0].legend(fontsize=7, loc="best", framealpha=0.85)
    return drawn


def main():
    args = parse(parser(__doc__))
    ensembles = [load(p) for p in args.prefix]
    labels = args.label or [e.title or e.prefix for e in ensembles]
    n = max(1, len(ensembles[0].columns))
    fig, axes = plt.subplots(n, 1, figsize=(9, 2.6 * n + 0.6), sharex=True, squeeze=False)
    axes = axes[:, 0]
    if not ensembles[0].columns:
        nothing_to_draw("the ensemble has no columns")
    elif plot(ensembles, labels, axes, args.view) == 0:
        nothing_to_draw("no ensemble rows" + (" in the time window"
                                              if len(ensembles[0].t) else ""))
    axes[0].set_title(args.title or ensembles[0].title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
