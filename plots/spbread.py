"""Read a spallbar run: PREFIX.h5 when it exists, else the column text files.

    run = spbread.load("runs/example2")
    run.history["t"], run.history["reaction_bottom"]      numpy arrays
    run.events["t"], run.events["kind"] (names), ...      numpy arrays
    run.profiles   list of dict(t, x, u, v, stress)       half-node rows (doc/outputs.md)
    run.fragments  list of dict(t, id, x_top, x_bottom, mass, velocity, ...)
    run.xt         dict(t, x, u, v, stress) with arrays (snapshots, rows), or None
    run.gauges     dict(t, x, stress, velocity, u, end): t (rows), x (gauges), the others
                   arrays (rows, gauges), end per gauge 'top' or 'bottom' on an end node,
                   else ''; or None without &gauges (PREFIX.gau, /gauges)
    run.spall      dict of PREFIX.spl's columns (end as 'top'/'bottom'; NaN: no value), or
                   None (no /spall, no PREFIX.spl: a run before issue 35 or not complete)
    run.source     'hdf5' or 'text'
    run.deck       {group: {name: value}} from /deck of PREFIX.h5 (empty from the text files):
                   reals float, integers int, logicals bool, texts str, lists numpy arrays
                   (keywords as str); files written before issue 35 hold every value as
                   its echoed text (doc/migration.md)
    run.deck_real(group, name, k=0)   element k of a deck real as float from either
                   layout (NaN when not set or absent)

The HDF5 layout is in doc/outputs.md; h5py shows the Fortran x-t arrays (rows, snapshots)
as (snapshots, rows), which is the orientation returned here for both sources.
"""
import os

import numpy as np



def _text(value):
    return value.decode(errors="replace") if isinstance(value, bytes) else str(value)


def deck_value(value):
    """A /deck attribute as a Python value: a string as str, a number or a bool as its
    Python scalar, a list as a numpy array (strings decoded, dtype object)."""
    if isinstance(value, (bytes, np.bytes_, str)):
        return _text(value)
    a = np.asarray(value)
    if a.ndim == 0:
        return a.item()
    if a.dtype.kind in "SUO":
        return np.array([_text(x) for x in a], dtype=object)
    return a


def event_kinds(kind_codes):
    """The event kinds' names by code from the program's list of them, the /events
    attribute kind_codes (and the .evt header): "1 fracture, 2 collision, ..." -> {1:
    "fracture", 2: "collision", ...} (the list is src/model/spb_events.f90 event_kinds)."""
    kinds = {}
    for item in _text(kind_codes).split(","):
        code, _, name = item.strip().partition(" ")
        kinds[int(code)] = name.strip()
    return kinds


class Run:
    def __init__(self, prefix):
        self.prefix = prefix
        self.history, self.events, self.profiles, self.fragments = {}, {}, [], []
        self.xt, self.title, self.deck = None, "", {}
        self.gauges = None
        self.spall = None
        if os.path.exists(prefix + ".h5"):
            self._read_h5()
        else:
            self._read_text()

    def deck_real(self, group, name, k=0):
        """Element k (0 for a scalar) of the deck real group:name as a float, from typed
        attributes or the echoed text of older files; NaN when it is not set or absent."""
        value = self.deck.get(group, {}).get(name)
        if value is None:
            return float("nan")
        if isinstance(value, str):                    # before issue 35: '0.5, 0.5'
            words = [w.strip() for w in value.split(",")]
            try:
                return float(words[k])
            except (IndexError, ValueError):          # '(not set)'
                return float("nan")
        a = np.atleast_1d(value)
        return float(a[k]) if k < len(a) else float("nan")

    # ------------------------------------------------------------------ HDF5
    def _read_h5(self):
        import h5py
        self.source = "hdf5"
        with h5py.File(self.prefix + ".h5", "r") as f:
            self.title = _text(f.attrs.get("title", ""))
            for group in f["deck"]:
                self.deck[group] = {k: deck_value(v) for k, v in
                                    f["deck"][group].attrs.items() if ":" not in k}
            self.history = {k: f["history"][k][:] for k in f["history"]}
            self.events = {k: f["events"][k][:] for k in f["events"]}
            if "kind" in self.events:
                kinds = event_kinds(f["events"].attrs["kind_codes"])
                self.events["kind"] = np.array([kinds[int(k)] for k in self.events["kind"]],
                                               dtype=object)
            x_half = f["mesh"]["x_half"][:]
            for name in sorted(f["fields"]["profiles"]):
                g = f["fields"]["profiles"][name]
                self.profiles.append(dict(t=float(g.attrs["t"]), x=x_half, u=g["u"][:],
                                          v=g["v"][:], stress=g["stress"][:]))
            for name in sorted(f["fragments"]):
                g = f["fragments"][name]
                block = {k: g[k][:] for k in g}
                block["t"] = float(g.attrs["t"])
                self.fragments.append(block)
            if "xt" in f["fields"]:
                g = f["fields"]["xt"]
                self.xt = dict(t=g["t"][:], x=x_half, u=g["u"][:], v=g["v"][:],
                               stress=g["stress"][:])
            if "gauges" in f:
                g = f["gauges"]
                self.gauges = dict(t=g["t"][:], x=np.asarray(g.attrs["x"], dtype=float),
                                   stress=g["stress"][:], velocity=g["velocity"][:], u=g["u"][:])
                x = f["mesh"]["x"][:]
                tol = 1e-9 * (x[-1] - x[0]) / max(1, len(x) - 1)
                self.gauges["end"] = ["top" if gx <= x[0] + tol else
                                      "bottom" if gx >= x[-1] - tol else ""
                                      for gx in self.gauges["x"]]
            if "spall" in f:
                g = f["spall"]
                self.spall = {k: g[k][:] for k in g}
                self.spall["end"] = np.array([{1: "top", 2: "bottom"}[int(e)]
                                              for e in self.spall["end"]], dtype=object)

    # ------------------------------------------------------------------ text
    def _read_text(self):
        self.source = "text"
        self.history = _columns(self.prefix + ".his")
        self.events = _columns(self.prefix + ".evt", kinds=True)
        for t, rows in _blocks(self.prefix + ".prf"):
            # x u v stress, and t since the column-name first line (doc/migration.md)
            a = np.array(rows, dtype=float).reshape(len(rows), -1)
            self.profiles.append(dict(t=t, x=a[:, 0], u=a[:, 1], v=a[:, 2], stress=a[:, 3]))
        names = None
        with open(self.prefix + ".frg") as f:
            for line in f:
                if line.startswith("# id "):
                    names = line[2:].split()
        names = [n if n != "birth_t" else "birth_t" for n in names]
        for t, rows in _blocks(self.prefix + ".frg"):
            a = np.array(rows, dtype=float).reshape(-1, len(names))
            block = {n: a[:, k] for k, n in enumerate(names)}
            block["t"] = t
            self.fragments.append(block)
        with open(self.prefix + ".his") as f:
            for line in f:
                if line.startswith("# title:"):
                    self.title = line[len("# title:"):].strip()
                    break
        if os.path.exists(self.prefix + ".gau"):
            self.gauges = _gauges(self.prefix + ".gau")
        if os.path.exists(self.prefix + ".spl"):
            self.spall = _columns(self.prefix + ".spl", words=("end",))


def _gauges(path):
    """PREFIX.gau: t, the gauges' x (from the '# gauge k at x = X m' lines) and their columns."""
    cols = _columns(path)
    x, end = [], []
    for line in _lines(path):
        if not line.startswith("#"):
            break
        if line.startswith("# gauge ") and " at x = " in line:
            x.append(float(line.split(" at x = ")[1].split()[0]))
            end.append("top" if ", the top end" in line else
                       "bottom" if ", the bottom end" in line else "")
    n = len(x)
    out = dict(t=cols["t"], x=np.array(x), end=end)
    for q in ("stress", "velocity", "u"):
        out[q] = np.column_stack([cols[f"{q}_{k}"] for k in range(1, n + 1)]) if n else \
            np.zeros((len(cols["t"]), 0))
    return out


def _is_number(word):
    try:
        float(word)
    except ValueError:
        return False
    return True


def _lines(path):
    """The lines of a text output without its column-name first line (&run header =
    'names': the names again, without '#'; older outputs and header = 'comments' have none)."""
    with open(path) as f:
        for k, line in enumerate(f):
            if k == 0 and not line.startswith("#") and line.split() \
                    and not _is_number(line.split()[0]):
                continue
            yield line


def _columns(path, kinds=False, words=()):
    """Columns of a text table by the names on its last header line (kinds: .evt's kind
    column, and the columns named in words, as text)."""
    names, rows = None, []
    for line in _lines(path):
        if line.startswith("#"):
            names = line[1:].split()
            continue
        rows.append(line.split())
    out = {}
    for k, n in enumerate(names):
        col = [r[k] for r in rows]
        if (kinds and n == "kind") or n in words:
            out[n] = np.array(col, dtype=object)
        else:
            out[n] = np.array(col, dtype=float)
    return out


def _blocks(path):
    """(t, rows) for each '# t = T' block of a text file."""
    blocks, t, rows = [], None, []
    for line in _lines(path):
        if line.startswith("# t = "):
            if t is not None:
                blocks.append((t, rows))
            t, rows = float(line[6:]), []
        elif not line.startswith("#") and t is not None:
            rows.append(line.split())
    if t is not None:
        blocks.append((t, rows))
    return blocks


def load(prefix):
    return Run(prefix)
