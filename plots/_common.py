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


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print(f"wrote {path}")
