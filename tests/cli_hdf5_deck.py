#!/usr/bin/env python3
"""The deck's values in PREFIX.h5 with their types (issue 35; doc/outputs.md, "The deck's
values"), read back with h5py: reals float64 equal to the deck's, integers int32, logicals
bool, texts strings, lists 1-D arrays (one element or none too), a real not set absent
(its ':from' and ':units' kept); the checkpoint's /deck the same; plots/spbread.py reads
the typed values and, through deck_real, the strings of a file written before.

usage: cli_hdf5_deck.py SPALLBAR WORKDIR   (a Python with h5py and numpy: the project venv)
"""
import os
import shutil
import sys

import h5py
import numpy as np

from clitools import Checks, run_decks

# every kind of variable: reals, lists of reals, integers, logicals, texts, a keyword list,
# reals left unset (t_cut, the Weibull modulus and scale), an optional group (&gauges)
FULL = """&run
  title = 'typed deck values'
  t_end = 2.5e-4
  hdf5 = .true.
  warnings = .true.
  history_every = 3
  profile_times = 1.0e-4, 2.5e-4
  checkpoint = 'full.ck.h5'
/
&mesh cells = 10, fit = 'stretch' /
&segments
  n = 2
  length = 0.5, 0.25
  young = 35.0e9, 2.0e11
  density = 2350.0, 7850.0
  strength = 4.0e6, -1.0
  interface = 'dry'
  gap = 1.0e-3
/
&load kind = 'power', p0 = 1.0e7, t_k = 1.0e-5 /
&gauges x = 0.1, 0.6 /
"""
# one segment, no profile times: empty lists
SMALL = """&run t_end = 1.0e-4, hdf5 = .true. /
&mesh cells = 10 /
&segments n = 1, length = 0.5, young = 35.0e9, density = 2350.0 /
"""


def main():
    exe, work = (os.path.abspath(a) for a in sys.argv[1:3])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    if not run_decks(check, exe, work, (("full", FULL), ("small", SMALL))):
        return check.finish()

    def typed(attrs, name, kind, value, what):
        """attrs[name] has the dtype kind ('f', 'i', 'b', 'S') and equals value (exactly:
        the same decimal read by gfortran and Python is the same double)."""
        v = attrs.get(name)
        ok = v is not None and np.asarray(v).dtype.kind == kind and \
            np.array_equal(np.asarray(v), np.asarray(value))
        check(ok, f"{what} {name}: {v!r} ({np.asarray(v).dtype if v is not None else None}),"
                  f" expected {value!r} of kind {kind}")

    for path in ("full.h5", "full.ck.h5"):
        with h5py.File(os.path.join(work, path), "r") as f:
            d = f["deck"]
            typed(d["run"].attrs, "t_end", "f", 2.5e-4, path)
            check(np.asarray(d["run"].attrs["t_end"]).shape == (), f"{path}: t_end a scalar")
            typed(d["run"].attrs, "history_every", "i", 3, path)
            typed(d["run"].attrs, "hdf5", "b", True, path)
            typed(d["run"].attrs, "warnings", "b", True, path)
            typed(d["run"].attrs, "title", "S", b"typed deck values", path)
            typed(d["run"].attrs, "profile_times", "f", [1.0e-4, 2.5e-4], path)
            typed(d["mesh"].attrs, "cells", "i", 10, path)
            typed(d["mesh"].attrs, "fit", "S", b"stretch", path)
            typed(d["segments"].attrs, "n", "i", 2, path)
            typed(d["segments"].attrs, "length", "f", [0.5, 0.25], path)
            typed(d["segments"].attrs, "density", "f", [2350.0, 7850.0], path)
            typed(d["segments"].attrs, "strength", "f", [4.0e6, -1.0], path)
            typed(d["segments"].attrs, "area", "f", [1.0, 1.0], path)   # the default
            typed(d["segments"].attrs, "interface", "S", [b"dry"], path)
            typed(d["segments"].attrs, "gap", "f", [1.0e-3], path)
            typed(d["load"].attrs, "p0", "f", 1.0e7, path)
            typed(d["gauges"].attrs, "x", "f", [0.1, 0.6], path)
            for group, name in (("load", "t_cut"), ("strength_field", "modulus"),
                                ("strength_field", "scale")):
                a = d[group].attrs
                check(name not in a and a.get(name + ":from") == b"default" and
                      name + ":units" in a, f"{path}: {group} {name} not set: no value, "
                      f"':from' default: {dict(a)}")
            check(d["segments"].attrs["length:units"] == b"m" and
                  d["segments"].attrs["length:from"] == b"input", f"{path}: ':units', ':from'")
    with h5py.File(os.path.join(work, "small.h5"), "r") as f:
        d = f["deck"]
        for group, name, kind in (("segments", "gap", "f"), ("segments", "interface", "S"),
                                  ("run", "profile_times", "f")):
            v = np.asarray(d[group].attrs[name])
            check(v.shape == (0,) and v.dtype.kind == kind, f"small: {name} an empty list: "
                  f"{v!r}")
        typed(d["segments"].attrs, "length", "f", [0.5], "small (one element: a list)")
        typed(d["run"].attrs, "hdf5", "b", True, "small")
    # plots/spbread.py: typed values, and deck_real on the strings of an older file
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "plots"))
    import spbread
    full = spbread.load(os.path.join(work, "full"))
    check(full.deck["mesh"]["cells"] == 10 and isinstance(full.deck["mesh"]["cells"], int),
          f"spbread: cells {full.deck['mesh']['cells']!r}")
    check(full.deck["run"]["hdf5"] is True, f"spbread: hdf5 {full.deck['run']['hdf5']!r}")
    check(list(full.deck["segments"]["interface"]) == ["dry"], "spbread: interface")
    check(full.deck_real("segments", "young", 1) == 2.0e11, "spbread: deck_real young(2)")
    check(np.isnan(full.deck_real("load", "t_cut")), "spbread: deck_real of a real not set")
    old = os.path.join(work, "old")
    for ext in (".h5", ".his", ".evt", ".prf", ".frg"):
        shutil.copy(os.path.join(work, "full" + ext), old + ext)
    with h5py.File(old + ".h5", "r+") as f:      # the layout before issue 35
        f["deck/segments"].attrs["young"] = np.bytes_(b"35e9, 2e11")
        f["deck/load"].attrs["t_cut"] = np.bytes_(b"(not set)")
        f["deck/mesh"].attrs["cells"] = np.bytes_(b"10")
    before = spbread.load(old)
    check(before.deck_real("segments", "young", 1) == 2.0e11 and
          np.isnan(before.deck_real("load", "t_cut")) and
          before.deck_real("mesh", "cells") == 10.0, "spbread: deck_real of an older file")
    print(f"full.h5 /deck/segments: {dict(full.deck['segments'])}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
