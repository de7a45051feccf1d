"""Shared bits of the plot scripts: headless matplotlib, the command line, saving."""
import argparse
import os
import sys

os.environ.setdefault("MPLBACKEND", "Agg")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import spbread  # noqa: E402,F401


def parser(doc):
    p = argparse.ArgumentParser(description=doc.strip().splitlines()[0])
    p.add_argument("prefix", nargs="+", help="run prefix (PREFIX.h5, else PREFIX.his/...)")
    p.add_argument("-o", "--output", required=True, help="PNG file to write")
    p.add_argument("--label", action="append", help="legend label per prefix")
    p.add_argument("--title", help="figure title (default: the run's title)")
    return p


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
    sys.stderr.write(f"{os.path.basename(sys.argv[0])}: warning: nothing to draw: {what}\n")


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print(f"wrote {path}")
