"""Shared bits of the plot scripts: headless matplotlib, the command line and its options
(the time window, the units, the gauges: one parser for every script), reading the runs
with a one-line error, saving.

The options (doc/outputs.md, "Plots"):

  --t-min T, --t-max T   the time window: a number in seconds, or with its unit (2ms, 300us,
                         300µs, 0.5s); only what lies in it is drawn
  --units U[,U]          the time unit (s, ms, us or µs; default ms, the same in every
                         script) and/or the stress unit (Pa, kPa, MPa, GPa; default the
                         one that shows the largest value with 1-3 digits); a unit a plot
                         has no axis for is ignored
  --gauges K[,K]         (gauges.py) the gauges to draw, 1-based as the columns of PREFIX.gau
                         (stress_K ...); default all

A run that cannot be read (no PREFIX.h5 and no PREFIX.his, a missing or damaged file) ends
the script with one line 'SCRIPT.py: error: ...' on stderr and exit status 2.
"""
import argparse
import os
import re
import sys

os.environ.setdefault("MPLBACKEND", "Agg")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import spbread  # noqa: E402,F401

# unit: (seconds per unit, the name on the axes)
TIME_UNITS = {"s": (1.0, "s"), "ms": (1.0e-3, "ms"), "us": (1.0e-6, "µs"), "µs": (1.0e-6, "µs")}
STRESS_UNITS = {"Pa": 1.0, "kPa": 1.0e3, "MPa": 1.0e6, "GPa": 1.0e9}
DEFAULT_TIME_UNIT = "ms"     # every script's time axis and time labels unless --units says


def script_name():
    return os.path.basename(sys.argv[0]) or "plot"


def fail(message):
    """End the script with one line on stderr and exit status 2 (no traceback)."""
    text = " ".join(str(message).split())
    sys.stderr.write(f"{script_name()}: error: {text}\n")
    sys.exit(2)


def time_value(text):
    """A time of the command line in seconds: '0.002', '2e-3', '2ms', '300 us', '300µs'."""
    m = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(s|ms|us|µs)?\s*", text)
    if not m:
        raise argparse.ArgumentTypeError(f"'{text}' is not a time (seconds, or with a unit: "
                                         "2ms, 300us, 0.5s)")
    return float(m.group(1)) * TIME_UNITS[m.group(2) or "s"][0]


def gauge_list(text):
    """'1,3' -> [1, 3]: gauges by their 1-based number."""
    try:
        ks = [int(w) for w in text.replace(",", " ").split()]
    except ValueError:
        ks = []
    if not ks or min(ks) < 1:
        raise argparse.ArgumentTypeError(f"'{text}' is not a list of gauge numbers "
                                         "(1-based, e.g. 1,3)")
    return ks


class View:
    """What the command line asks to see: the time window [s], the time unit, the stress
    unit (None: chosen by the data), the gauges (None: all). The plot functions take one;
    View() is the default of every script."""

    def __init__(self, time=DEFAULT_TIME_UNIT, stress=None, t_min=None, t_max=None,
                 gauges=None):
        self.time_scale, self.time_unit = TIME_UNITS[time]
        self.stress = stress
        self.t_min, self.t_max = t_min, t_max
        self.gauges = gauges

    def t(self, t):
        """Times [s] in the time unit."""
        return np.asarray(t, dtype=float) / self.time_scale

    def keep(self, t):
        """Which of the times [s] lie in the window."""
        t = np.asarray(t, dtype=float)
        keep = np.ones(t.shape, dtype=bool)
        if self.t_min is not None:
            keep &= t >= self.t_min
        if self.t_max is not None:
            keep &= t <= self.t_max
        return keep

    def t_label(self, what="t"):
        return f"{what} [{self.time_unit}]"

    def t_limits(self, ax, axis="x"):
        """The window's given ends as the limits of the time axis."""
        lo = None if self.t_min is None else self.t_min / self.time_scale
        hi = None if self.t_max is None else self.t_max / self.time_scale
        if lo is not None or hi is not None:
            (ax.set_xlim if axis == "x" else ax.set_ylim)(lo, hi)

    def stress_scale(self, values):
        """(divisor, unit) of the stresses: the one asked for, else by their size."""
        if self.stress:
            return STRESS_UNITS[self.stress], self.stress
        return stress_scale(values)


def parser(doc, gauges=False):
    """The command line of a script that draws runs: PREFIX ..., -o PNG, --label, --title
    and the view options (the module's docstring); with gauges, --gauges too."""
    p = argparse.ArgumentParser(description=doc.strip().splitlines()[0])
    p.add_argument("prefix", nargs="+", help="run prefix (PREFIX.h5, else PREFIX.his/...; "
                   "PREFIX.h5 or PREFIX.his itself is taken as its prefix)")
    p.add_argument("-o", "--output", required=True, help="PNG file to write")
    p.add_argument("--label", action="append", help="legend label per prefix")
    p.add_argument("--title", help="figure title (default: the run's title)")
    p.add_argument("--t-min", type=time_value, metavar="T",
                   help="draw from this time on (seconds, or 2ms, 300us, ...)")
    p.add_argument("--t-max", type=time_value, metavar="T", help="draw up to this time")
    p.add_argument("--units", action="append", metavar="U[,U]",
                   help=f"time unit ({', '.join(TIME_UNITS)}; default {DEFAULT_TIME_UNIT}) "
                   f"and/or stress unit ({', '.join(STRESS_UNITS)}; default by the data)")
    if gauges:
        p.add_argument("--gauges", type=gauge_list, metavar="K[,K]",
                       help="the gauges to draw, 1-based as PREFIX.gau numbers them "
                       "(default all)")
    return p


def parse(p):
    """The arguments, with args.view (a View) from the options."""
    args = p.parse_args()
    time, stress = DEFAULT_TIME_UNIT, None
    for word in ",".join(args.units or []).split(","):
        word = word.strip()
        if not word:
            continue
        if word in TIME_UNITS:
            time = word
        elif word in STRESS_UNITS:
            stress = word
        else:
            p.error(f"--units: '{word}' is neither a time unit ({', '.join(TIME_UNITS)}) "
                    f"nor a stress unit ({', '.join(STRESS_UNITS)})")
    if args.t_min is not None and args.t_max is not None and args.t_max <= args.t_min:
        p.error(f"--t-max ({args.t_max:g} s) must be later than --t-min ({args.t_min:g} s)")
    args.view = View(time, stress, args.t_min, args.t_max, getattr(args, "gauges", None))
    return args


def load(prefix):
    """spbread.load(prefix), or the one-line error (exit 2) when the run cannot be read."""
    for ext in (".h5", ".his"):
        if prefix.endswith(ext) and os.path.isfile(prefix):
            prefix = prefix[:-len(ext)]
    if not (os.path.isfile(prefix + ".h5") or os.path.isfile(prefix + ".his")):
        fail(f"no run output {prefix}: neither {prefix}.h5 nor {prefix}.his exists "
             "(PREFIX is what spallbar --output was given, without an extension)")
    try:
        return spbread.load(prefix)
    except OSError as e:
        fail(f"cannot read the run {prefix}: {e.strerror or e}"
             + (f": {e.filename}" if getattr(e, "filename", None) else ""))
    except Exception as e:       # a damaged or foreign file: say so on one line
        fail(f"cannot read the run {prefix}: {type(e).__name__}: {e}")


def load_runs(args):
    """Every run of the command line, and their legend labels."""
    runs = [load(p) for p in args.prefix]
    return runs, args.label or [r.title or r.prefix for r in runs]


def stress_scale(values):
    """(divisor, unit) that shows stresses of this size with 1-3 digits before the point:
    Pa, kPa, MPa or GPa by the largest magnitude."""
    top = max((abs(float(v)) for v in values), default=0.0)
    for scale, unit in ((1.0e9, "GPa"), (1.0e6, "MPa"), (1.0e3, "kPa")):
        if top >= scale:
            return scale, unit
    return 1.0, "Pa"


def nothing_to_draw(what):
    """Say on stderr that a plot has nothing of what it is for (it still writes the figure)."""
    sys.stderr.write(f"{script_name()}: warning: nothing to draw: {what}\n")


def save(fig, path):
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=120)
    except OSError as e:
        fail(f"cannot write {path}: {e.strerror or e}")
    plt.close(fig)
    print(f"wrote {path}")
