#!/usr/bin/env python3
"""Damaged checkpoints (issue 32, item 5): every restart from a damaged checkpoint either
continues the run exactly (exit 0, outputs identical to the uninterrupted run) or is refused
(exit 2, one line, the outputs as they were): never a crash, never other outputs.

  * the issue's reproducers: /outputs body.his = NaN (SIGFPE in Debug before); body.his and
    tail.his moved back one row (exit 0 and a .his one row short before); a root format =
    'spallbar checkpoint 1' (no checksum), alone and with split(1) = 10^6, with n_cut = 5 and
    junk in cut (full-mass run), with split unsorted (SIGSEGV in Release, other events
    before); each also with the format left at 3 (the checksum);
  * a format-2 checkpoint naming this program (a format-3 one relabelled: the marks would
    escape the checksum) is refused; under --restart-any-version one of another program is
    read and range-checked, and a body.his of NaN is still refused;
  * the marks and the identity changed and the checksum signed again (checkpoint_tools.py):
    the range checks behind the checksum refuse them (negative, NaN, huge, tail longer than
    its body, n_profiles without its times);
  * a seeded fuzz of N mutations (default 200) of the checkpoint's attributes and datasets:
    NaN, +-huge, negative, off by one, shuffled, truncated, one byte of a string changed;
    odd-numbered ones signed again. Counts: continued identical, refused; any crash (exit
    >= 128 or a backtrace), other exit status, more than one line, exit 0 with other
    outputs, or outputs touched by a refusal fails.

usage: cli_checkpoint_damage.py SPALLBAR WORKDIR [N_FUZZ]     (needs h5py)
"""
import hashlib
import os
import random
import shutil
import sys

import h5py
import numpy as np

from checkpoint_tools import resign
from clitools import Checks, run

EXTS = [".his", ".prf", ".evt", ".frg", ".imp"]

# the deck (item 1) with PREFIX.h5 and the x-t fields; the checkpoint at t = 0.15
DECK = """&run t_end = {t_end}, gravity = 9.81, history_every = 1, checkpoint = '{ck}',
     profile_times = {profiles}, hdf5 = .true., field_every = 7{model} /
&mesh cells = 20 /
&segments n = 1, length = 0.95, young = 20.0e6, density = 1765.8, strength = 2e4 /
&ends top = 'transmit', bottom = 'free' /
&load kind = 'power', face = 'top', p0 = 0.1e6, t_k = 0.05, exponent = 1 /
"""


def deck(t_end, ck, full_mass=False):
    """The deck to t_end (the checkpoint run: 0.15 s, profile 0.1 only)."""
    return DECK.format(t_end=t_end, ck=ck, profiles="0.1" if t_end < 0.2 else "0.1, 0.25",
                       model=", model = 'full-mass'" if full_mass else "")


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def h5_equal(a, b):
    """PREFIX.h5 files equal in every dataset (bit for bit) and attribute."""
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names_a, names_b = [], []
        fa.visit(names_a.append)
        fb.visit(names_b.append)
        if sorted(names_a) != sorted(names_b):
            return False
        for n in names_a:
            oa, ob = fa[n], fb[n]
            if isinstance(oa, h5py.Dataset):
                if not isinstance(ob, h5py.Dataset) or oa.shape != ob.shape:
                    return False
                if oa[()].tobytes() != ob[()].tobytes():
                    return False
            if set(oa.attrs) != set(ob.attrs):
                return False
            for k in oa.attrs:
                if np.asarray(oa.attrs[k]).tobytes() != np.asarray(ob.attrs[k]).tobytes():
                    return False
        return True


class Case:
    """A folder holding the checkpoint run's outputs (r.*), a damaged copy of its checkpoint
    (in.ck.h5) and the full deck; restart() runs it and classifies the outcome."""

    def __init__(self, exe, work, base, ref, name):
        self.exe, self.base, self.ref = exe, base, ref
        self.dir = os.path.join(work, name)
        shutil.rmtree(self.dir, ignore_errors=True)
        os.makedirs(self.dir)
        for e in EXTS + [".h5"]:
            shutil.copy(os.path.join(base["dir"], "c" + e), os.path.join(self.dir, "r" + e))
        self.ck = os.path.join(self.dir, "in.ck.h5")
        shutil.copy(base["ck"], self.ck)
        with open(os.path.join(self.dir, "full.nml"), "w") as f:
            f.write(deck(0.3, "run.ck.h5", base["full_mass"]))

    def restart(self, extra=()):
        """'identical', 'refused' or what went wrong."""
        before = {e: sha(os.path.join(self.dir, "r" + e)) for e in EXTS + [".h5"]}
        p = run(self.exe, ["full.nml", "--output", "r", "--restart", "in.ck.h5", "-q"]
                + list(extra), self.dir, timeout=300)
        lines = p.stderr.strip().splitlines()
        self.stderr = p.stderr.strip()
        if p.returncode == 2:
            if len(lines) != 1:
                return f"exit 2 with {len(lines)} lines: {p.stderr[:300]!r}"
            after = {e: sha(os.path.join(self.dir, "r" + e)) for e in EXTS + [".h5"]}
            leftover = [f for f in os.listdir(self.dir) if f.endswith(".restart")]
            if after != before or leftover:
                return f"refused but outputs touched ({leftover})"
            return "refused"
        if p.returncode != 0:
            return f"exit {p.returncode}: {p.stderr[-400:]!r}"
        for e in EXTS:
            if sha(os.path.join(self.dir, "r" + e)) != sha(os.path.join(self.ref, "u" + e)):
                return f"exit 0 with other outputs (r{e})"
        if not h5_equal(os.path.join(self.dir, "r.h5"), os.path.join(self.ref, "u.h5")):
            return "exit 0 with another PREFIX.h5"
        return "identical"


def prepare(check, exe, work, name, full_mass):
    """The uninterrupted run (u.*) and the checkpoint run (c.*, c.ck.h5) in work/name."""
    d = os.path.join(work, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    with open(os.path.join(d, "full.nml"), "w") as f:
        f.write(deck(0.3, "run.ck.h5", full_mass))
    with open(os.path.join(d, "short.nml"), "w") as f:
        f.write(deck(0.15, "c.ck.h5", full_mass))
    pu = run(exe, ["full.nml", "--output", "u", "-q"], d)
    pc = run(exe, ["short.nml", "--output", "c", "-q"], d)
    check(pu.returncode == 0 and pc.returncode == 0,
          f"{name}: the runs ({pu.returncode}, {pc.returncode}: {pu.stderr}{pc.stderr})")
    base = {"dir": d, "ck": os.path.join(d, "c.ck.h5"), "full_mass": full_mass}
    # the checkpoint restarts: the outputs are the uninterrupted run's
    c = Case(exe, work, base, d, name + "_clean")
    outcome = c.restart()
    check(outcome == "identical", f"{name}: an undamaged checkpoint restarts identically "
          f"({outcome})")
    return base


def relabel(path, n):
    """Root format = 'spallbar checkpoint N'; format 2's checksum is the field lists' only."""
    with h5py.File(path, "r+") as h:
        h.attrs["format"] = np.bytes_(f"spallbar checkpoint {n}".encode())
        if n == 2:
            h.attrs["checksum"] = np.bytes_(bytes(h.attrs["checksum"])[:16])


def set_attr(path, obj, name, value):
    with h5py.File(path, "r+") as h:
        h[obj].attrs[name] = value


def set_data(path, name, values):
    with h5py.File(path, "r+") as h:
        attrs = dict(h[name].attrs)
        del h[name]
        h[name] = np.asarray(values)
        for k, v in attrs.items():
            h[name].attrs[k] = v


def back_one_row(path):
    """/outputs body.his and tail.his as they were one history row earlier (as the issue
    did: the PREFIX.h5 row count left as it was)."""
    with h5py.File(path, "r+") as h:
        out = h["outputs"].attrs
        tail = bytes(out["tail.his"])
        cut = tail[:-1].rfind(b"\n") + 1          # the last row starts here
        row = len(tail) - cut
        out["body.his"] = float(out["body.his"]) - row
        # the 240 bytes before the end of the row before: the row's start moves into the tail
        out["tail.his"] = np.bytes_(tail[:cut])
        out["tail_bytes.his"] = np.int32(cut)


def reproducers(check, exe, work, base, mass):
    """The issue's reproducers: each refused with one line, the outputs untouched."""
    def case(name, damage, needle, extra=()):
        c = Case(exe, work, base, base["dir"], name)
        damage(c.ck)
        outcome = c.restart(extra)
        check(outcome == "refused" and needle in c.stderr,
              f"{name}: refused naming '{needle}' ({outcome}: {c.stderr[:300]!r})")

    def fmt(n):
        return lambda p: relabel(p, n)

    nan = np.float64("nan")
    case("body_nan", lambda p: set_attr(p, "outputs", "body.his", nan), "checksum")
    case("body_tail_back", back_one_row, "checksum")
    case("format_1", fmt(1), "spallbar checkpoint 1")
    other = lambda p: set_attr(p, "identity", "program", np.bytes_(b"spallbar 0.1.0"))
    case("format_2_this_program", fmt(2), "format 2")
    # format 2 leaves the marks outside its checksum: the range checks still refuse
    case("format_2_body_nan", lambda p: (fmt(2)(p), other(p),
         set_attr(p, "outputs", "body.his", nan)), "body.his", ["--restart-any-version"])
    if not mass:
        split_cases(check, exe, work, base, case, fmt, other)
        signed_cases(case)
    else:
        with h5py.File(base["ck"], "r") as h:
            n_cut = int(h["state"].attrs["n_cut"])
        check(n_cut >= 1, f"the full-mass checkpoint has cut cells ({n_cut})")

        def junk_cut(p):
            set_attr(p, "state", "n_cut", np.int32(5))
            set_attr(p, "state", "cut:size", np.int32(16))
            set_data(p, "state/cut", np.r_[np.int32([-3, 10 ** 7, 0, 99, 2 ** 30]),
                                           np.zeros(11, np.int32)])
        case("format_1_n_cut_junk", lambda p: (fmt(1)(p), junk_cut(p)), "spallbar checkpoint 1")
        case("n_cut_junk", junk_cut, "checksum")


def split_cases(check, exe, work, base, case, fmt, other):
    """The split list damaged: huge, unsorted; format 1 (refused as such) or 3, or format 2
    of another program (its checksum sums the state)."""
    with h5py.File(base["ck"], "r") as h:
        n_split = int(h["state"].attrs["n_split"])
        split = h["state/split"][()]
    check(n_split >= 2, f"the checkpoint has split nodes to damage ({n_split})")

    def split_huge(p):
        fmt(1)(p)
        s = split.copy()
        s[0] = 10 ** 6
        set_data(p, "state/split", s)
    case("format_1_split_huge", split_huge, "spallbar checkpoint 1")
    case("split_huge", lambda p: set_data(p, "state/split", np.r_[10 ** 6, split[1:]]),
         "checksum")

    def unsorted(p):
        s = split.copy()
        s[:n_split] = s[:n_split][::-1]
        set_data(p, "state/split", s)
    case("split_unsorted", unsorted, "checksum")
    case("format_1_unsorted", lambda p: (fmt(1)(p), unsorted(p)), "spallbar checkpoint 1")
    case("format_2_unsorted", lambda p: (fmt(2)(p), other(p), unsorted(p)),
         "checksum", ["--restart-any-version"])


def signed_cases(case):
    """Damage behind the checksum (signed again, checkpoint_tools.py): the range checks."""
    nan = np.float64("nan")
    # behind the checksum (signed again): the range checks
    signed = [
        ("signed_body_nan", lambda p: set_attr(p, "outputs", "body.his", nan), "body.his"),
        ("signed_body_negative", lambda p: set_attr(p, "outputs", "body.his", -80.0),
         "body.his"),
        ("signed_body_huge", lambda p: set_attr(p, "outputs", "body.his", 1e300), "body.his"),
        ("signed_body_beyond_file", lambda p: set_attr(p, "outputs", "body.his", 1e12),
         "bytes after its header"),
        ("signed_tail_longer", lambda p: set_attr(p, "outputs", "tail_bytes.his",
                                                  np.int32(100000)), "tail_bytes.his"),
        ("signed_tail_negative", lambda p: set_attr(p, "outputs", "tail_bytes.prf",
                                                    np.int32(-7)), "tail_bytes.prf"),
        ("signed_n_profiles", lambda p: set_attr(p, "identity", "n_profiles", np.int32(40)),
         "n_profiles"),
        ("signed_times_nan", lambda p: set_data(p, "identity/profile_times", [nan]),
         "profile_times"),
        ("signed_times_huge", lambda p: set_data(p, "identity/profile_times", [1e300]),
         "profile_times"),
        ("signed_cells", lambda p: set_attr(p, "identity", "cells", np.int32(-5)), "cells"),
    ]
    for name, damage, needle in signed:
        case(name, lambda p, d=damage: (d(p), resign(p)), needle)


def mutate(rng, path, k):
    """One random change of an attribute or dataset; returns what it did."""
    with h5py.File(path, "r+") as h:
        targets = []
        h.visititems(lambda n, o: targets.append(n) if isinstance(o, h5py.Dataset) else None)
        targets = [("d", n, None) for n in targets]
        for g in ["/", "identity", "state", "run", "outputs"]:
            targets += [("a", g, a) for a in h[g].attrs]
        kind, obj, attr = rng.choice(targets)
        if kind == "a":
            v = h[obj].attrs[attr]
            if isinstance(v, (bytes, np.bytes_)):
                b = bytearray(bytes(v))
                if b and rng.random() < 0.7:
                    i = rng.randrange(len(b))
                    b[i] = (b[i] + rng.randrange(1, 255)) % 256 or 1
                else:
                    b = b[:-1] if b else b"x"
                h[obj].attrs[attr] = np.bytes_(bytes(b))
                return f"{obj}:{attr} string"
            new, what = number_mutation(rng, np.asarray(v))
            h[obj].attrs[attr] = new
            return f"{obj}:{attr} {what}"
        a = h[obj][()]
        attrs = dict(h[obj].attrs)
        if rng.random() < 0.25 and a.size > 1:
            a = a[: rng.randrange(a.size)]
            what = "truncated"
        elif rng.random() < 0.25 and a.size > 1:
            a = a.copy()
            rng.shuffle(a)
            what = "shuffled"
        else:
            a = a.copy()
            i = rng.randrange(a.size) if a.size else None
            if i is None:
                return f"{obj} empty"
            new, what = number_mutation(rng, np.asarray(a.flat[i]))
            a.flat[i] = new
        del h[obj]
        h[obj] = a
        for key, val in attrs.items():
            h[obj].attrs[key] = val
        return f"{obj} {what}"


def number_mutation(rng, v):
    """A damaged number of v's type: NaN, +-huge, negative, off by one, zero."""
    ints = np.issubdtype(v.dtype, np.integer)
    choice = rng.choice(["nan", "huge", "-huge", "neg", "+1", "-1", "zero"])
    x = v.item() if v.shape == () else v.flat[0]
    if ints:
        val = {"nan": 2 ** 31 - 1, "huge": 2 ** 31 - 1, "-huge": -2 ** 31, "neg": -abs(x) - 1,
               "+1": x + 1, "-1": x - 1, "zero": 0}[choice]
        return np.asarray(val, dtype=v.dtype), choice
    val = {"nan": float("nan"), "huge": 1e308, "-huge": -1e308, "neg": -abs(x) - 1.0,
           "+1": x + 1.0, "-1": x - 1.0, "zero": 0.0}[choice]
    return np.asarray(val, dtype=v.dtype), choice


def fuzz(check, exe, work, base, n):
    rng = random.Random(3205)
    counts = {}
    bad = []
    for k in range(n):
        c = Case(exe, work, base, base["dir"], "fuzz")
        what = mutate(rng, c.ck, k)
        if k % 2 == 1:
            resign(c.ck)
            what += " (signed again)"
        outcome = c.restart()
        key = outcome if outcome in ("identical", "refused") else "wrong"
        counts[key] = counts.get(key, 0) + 1
        if key == "wrong":
            bad.append(f"{k}: {what}: {outcome}")
    print(f"fuzz: {n} mutations: {counts.get('identical', 0)} continued identically, "
          f"{counts.get('refused', 0)} refused (exit 2, one line), "
          f"{counts.get('wrong', 0)} wrong")
    for b in bad:
        print("  ", b)
    check(not bad, f"fuzz: every damaged checkpoint continues identically or is refused "
          f"({len(bad)} not)")
    check(counts.get("refused", 0) > n // 2, "fuzz: most mutations are refused")


def main():
    exe = os.path.abspath(sys.argv[1])
    work = os.path.abspath(sys.argv[2])
    n_fuzz = int(sys.argv[3]) if len(sys.argv) > 3 else 200
    os.makedirs(work, exist_ok=True)
    check = Checks()
    base = prepare(check, exe, work, "half", False)
    reproducers(check, exe, work, base, False)
    mass = prepare(check, exe, work, "mass", True)
    reproducers(check, exe, work, mass, True)
    fuzz(check, exe, work, base, n_fuzz)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
