#!/usr/bin/env python3
"""Faults around a run (issue 19): no exit 0 with outputs that are not the full run, nothing
lost, nothing half made.

  * a full disk (a 64 KiB tmpfs; skipped with a message where mounting is not allowed):
    a run, a sweep and a run on a disk full from the start exit 3 (or 2 when not even
    an empty output can be made) with one line naming the file; a sweep never renames a
    cut table;
  * an output that is a folder: exit 2, one line, no other output created or truncated;
  * two runs on the same PREFIX at once: the second exits 2 at once and touches nothing,
    the first finishes with exit 0 and outputs identical to a run alone;
  * a checkpoint that is the deck, an output of the run or a folder: exit 2, deck intact;
  * an output (or the lock) that is one of the run's inputs (issue 32): the deck named
    PREFIX.his, a load table named PREFIX.prf or PREFIX.lock, an output that is a symbolic or
    a hard link to the deck, a sweep deck named PREFIX.sweep: exit 2, one line, the
    inputs intact, no output made;
  * deck reals that the "not given" marker would swallow, or whose products overflow:
    exit 2 naming the variable;
  * memory: a mesh, an x-t buffer or a sweep table beyond the limit (SPALLBAR_MEMORY_LIMIT,
    ulimit -v) is refused before it is allocated (exit 2 naming the variable, nothing
    written); the x-t buffer shrinks first, with the same fields; a bar (a run, a sweep's
    cases) the characteristic steps would serve takes every step on the lattice where their
    arrays do not fit, the outputs bit for bit SPALLBAR_STEPPING=lattice's, with a note;
    the lattice's steps between rows far apart run in blocks up to the next check, under a
    small address space; a cgroup's memory limit (Slurm's --mem) is a limit too (a child
    cgroup of 100 MB; skipped with a message where none can be made);
  * a Weibull field whose draws overflow (or underflow) is refused before it is drawn;
  * a sweep's output that is a folder: exit 2 before any case runs, nothing created;
  * issue 32: a reader holding PREFIX.h5 does not stop a rerun (temporaries, renamed at the
    end); a failing rerun leaves the previous outputs byte for byte; the checkpoint under
    the lock discipline (two runs with one checkpoint, a checkpoint that is another run's
    PREFIX.h5): the second refused at start, exit 2.

usage: cli_faults.py SPALLBAR WORKDIR
"""
import os
import shutil
import stat
import subprocess
import sys
import time

from clitools import Checks, run

SLOW = """&run t_end = 4.0e-3, title = 'faults' /
&mesh cells = 4000 /
&segments n = 1, length = 1.0, young = 1e9, density = 1000 /
&load kind = 'power', p0 = 1e6, t_k = 1e-4 /
"""

SMALL = """&run t_end = 2.0e-4, title = 'small', profile_times = 1e-4, 2e-4 /
&mesh cells = 200 /
&segments n = 2, length = 0.1, 0.1, young = 2*1e9, density = 2*1000, strength = 1e5, -1 /
&load kind = 'power', p0 = 1e6, t_k = 1e-4 /
"""

SWEEP = SMALL + """&sweep vary = 'p0', values = 1e6, 2e6, 3e6, 4e6, 5e6, 6e6, 7e6, 8e6 /
"""


def one_line(r):
    return r.stderr.strip().splitlines()


def full_disk(exe, work, check):
    mnt = os.path.join(work, "full")
    os.makedirs(mnt)
    m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", mnt],
                       capture_output=True, text=True)
    if m.returncode != 0:
        print(f"skip full disk: cannot mount a tmpfs here ({m.stderr.strip()})")
        return
    try:
        with open(os.path.join(mnt, "big.nml"), "w") as f:
            f.write(SMALL.replace("t_end = 2.0e-4", "t_end = 2.0e-3"))
        r = run(exe, ["big.nml", "--quiet"], mnt)
        lines = one_line(r)
        check(r.returncode == 3, f"full disk during the run: exit {r.returncode}, expected 3")
        # the cause named from statvfs (issue 32, item 9): not a guess between full and quota
        check(len(lines) == 1 and "big.his" in lines[0] and "reached the disk" in lines[0] and
              "(the disk is full (or over quota))" in lines[0],
              f"full disk during the run: stderr {r.stderr!r}")
        print(f"ok   full disk during the run: exit {r.returncode}: {lines[0] if lines else ''}")
        for f in os.listdir(mnt):
            if f != "big.nml":
                os.remove(os.path.join(mnt, f))

        with open(os.path.join(mnt, "sw.nml"), "w") as f:
            f.write(SWEEP)
        with open(os.path.join(mnt, "filler"), "wb") as f:
            f.write(b"\0" * 40 * 1024)
        r = run(exe, ["--sweep", "sw.nml", "--quiet"], mnt)
        lines = one_line(r)
        check(r.returncode == 3, f"full disk, sweep: exit {r.returncode}, expected 3")
        check(len(lines) == 1 and "sw" in lines[0] and ("reached the disk" in lines[0] or
                                                        "HDF5" in lines[0]),
              f"full disk, sweep: {r.stderr!r}")
        table = os.path.join(mnt, "sw.sweep")
        rows = [l for l in open(table) if l.startswith(" ")] if os.path.exists(table) else []
        check(not os.path.exists(table) or len(rows) == 8,
              f"a cut sweep table was renamed ({len(rows)} of 8 rows)")
        print(f"ok   full disk, sweep: exit {r.returncode}: {lines[0] if lines else ''}")

        # HDF5 output and a checkpoint on a full disk: the message, then exit 3 (HDF5 1.10
        # crashed in its exit handler after a failed close)
        os.remove(os.path.join(mnt, "filler"))
        for f in os.listdir(mnt):
            if f.startswith("sw"):
                os.remove(os.path.join(mnt, f))
        for name, extra in (("h5", "hdf5 = .true., field_every = 1"),
                            ("ck", "checkpoint = 'ck.h5', checkpoint_every = 10")):
            with open(os.path.join(mnt, name + ".nml"), "w") as f:
                f.write(SMALL.replace("t_end = 2.0e-4", "t_end = 2.0e-3, " + extra))
            r = run(exe, [name + ".nml", "--quiet"], mnt)
            lines = one_line(r)
            check(r.returncode == 3 and len(lines) == 1,
                  f"full disk, {name}: exit {r.returncode}, {r.stderr!r}")
            print(f"ok   full disk, {name}: exit {r.returncode}: {lines[0] if lines else ''}")
            for f in os.listdir(mnt):
                if f.startswith(name + ".") and f != name + ".nml":
                    os.remove(os.path.join(mnt, f))

        # the disk full before the run starts
        with open(os.path.join(mnt, "filler2"), "wb") as f:
            try:
                f.write(b"\0" * 64 * 1024)
            except OSError:
                pass
        r = run(exe, ["big.nml", "--quiet"], mnt)
        lines = one_line(r)
        check(r.returncode in (2, 3), f"disk full from the start: exit {r.returncode}")
        check(len(lines) == 1 and ("reached the disk" in lines[0] or "cannot" in lines[0]),
              f"disk full from the start: {r.stderr!r}")
        print(f"ok   disk full from the start: exit {r.returncode}: {lines[0] if lines else ''}")
        # a read-only file system: named as such (the kernel refuses to remount a file
        # system read-only while a run writes on it, so this is the start of a run)
        ro = os.path.join(work, "ro")
        os.makedirs(ro)
        m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", ro],
                           capture_output=True, text=True)
        if m.returncode == 0:
            with open(os.path.join(ro, "big.nml"), "w") as f:
                f.write(SMALL)
            subprocess.run(["mount", "-o", "remount,ro", ro], check=True)
            r = run(exe, ["big.nml", "--quiet"], ro)
            lines = one_line(r)
            check(r.returncode == 2 and len(lines) == 1 and "Read-only file system" in lines[0],
                  f"read-only file system: exit {r.returncode}, {r.stderr!r}")
            print(f"ok   read-only file system: {lines[0] if lines else ''}")
            subprocess.run(["umount", ro], capture_output=True)
    finally:
        subprocess.run(["umount", mnt], capture_output=True)


def output_is_folder(exe, work, check):
    d = os.path.join(work, "folder")
    os.makedirs(os.path.join(d, "run.prf"))
    with open(os.path.join(d, "run.nml"), "w") as f:
        f.write(SMALL)
    with open(os.path.join(d, "run.his"), "w") as f:
        f.write("old result\n")
    r = run(exe, ["run.nml", "--quiet"], d)
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "run.prf" in lines[0] and "folder" in lines[0],
          f"output is a folder: exit {r.returncode}, {r.stderr!r}")
    check(open(os.path.join(d, "run.his")).read() == "old result\n",
          "output is a folder: an existing output was truncated")
    for ext in (".evt", ".frg"):
        check(not os.path.exists(os.path.join(d, "run" + ext)), f"output is a folder: made {ext}")
    print(f"ok   output is a folder: {lines[0] if lines else ''}")

    r = run(exe, ["run.nml", "--quiet", "--output", "."], d)
    check(r.returncode == 2 and "is a folder" in r.stderr, f"--output . : {r.returncode} {r.stderr!r}")


def concurrent(exe, work, check):
    d = os.path.join(work, "twice")
    os.makedirs(d)
    with open(os.path.join(d, "slow.nml"), "w") as f:
        f.write(SLOW)
    alone = os.path.join(work, "alone")
    os.makedirs(alone)
    shutil.copy(os.path.join(d, "slow.nml"), alone)
    r = run(exe, ["slow.nml", "--quiet"], alone)
    check(r.returncode == 0, f"slow deck alone: exit {r.returncode} {r.stderr!r}")
    first = subprocess.Popen([exe, "slow.nml", "--quiet"], cwd=d, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    # wait until the first run holds its lock and has made its outputs
    for _ in range(200):
        if os.path.exists(os.path.join(d, "slow.his.part")):
            break
        time.sleep(0.01)
    r = run(exe, ["slow.nml", "--quiet"], d)
    out, err = first.communicate()
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "in use by another spallbar run" in lines[0],
          f"second run on the same PREFIX: exit {r.returncode}, {r.stderr!r}")
    check(first.returncode == 0, f"first run: exit {first.returncode} {err!r}")
    for ext in (".his", ".prf", ".evt", ".frg"):
        a = open(os.path.join(alone, "slow" + ext)).read()
        b = open(os.path.join(d, "slow" + ext)).read()
        check(a == b, f"concurrent runs: slow{ext} differs from a run alone")
    print(f"ok   second run on the same PREFIX: {lines[0] if lines else ''}")


def checkpoint_paths(exe, work, check):
    d = os.path.join(work, "ckpaths")
    os.makedirs(d)
    for name, value, expect in (("deck", "ck.nml", "is the deck itself"),
                                ("output", "ck.his", "is an output of this run"),
                                ("output_h5", "./sub/../ck.evt", "is an output of this run"),
                                ("folder", ".", "is a folder")):
        text = SMALL.replace("title = 'small'", f"title = 'small', checkpoint = '{value}'")
        with open(os.path.join(d, "ck.nml"), "w") as f:
            f.write(text)
        os.makedirs(os.path.join(d, "sub"), exist_ok=True)
        r = run(exe, ["ck.nml", "--quiet"], d)
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and expect in lines[0],
              f"checkpoint = {value!r}: exit {r.returncode}, {r.stderr!r}")
        check(open(os.path.join(d, "ck.nml")).read() == text, f"checkpoint = {value!r}: deck changed")
        check(not os.path.exists(os.path.join(d, "ck.his")), f"checkpoint = {value!r}: wrote ck.his")
        print(f"ok   checkpoint {name}: {lines[0] if lines else ''}")


def outputs_over_inputs(exe, work, check):
    d = os.path.join(work, "over_inputs")
    os.makedirs(d)
    with open(os.path.join(d, "x.prf"), "w") as f:
        f.write("0 0\n1e-4 1e6\n2e-4 0\n")
    shutil.copy(os.path.join(d, "x.prf"), os.path.join(d, "y.lock"))
    table = SMALL.replace("kind = 'power', p0 = 1e6, t_k = 1e-4", "kind = 'table', table = 'x.prf'")
    with open(os.path.join(d, "a.nml"), "w") as f:
        f.write(table)
    with open(os.path.join(d, "b.nml"), "w") as f:
        f.write(table.replace("'x.prf'", "'y.lock'"))
    for name in ("foo.his", "d.nml"):
        with open(os.path.join(d, name), "w") as f:
            f.write(SMALL)
    os.symlink("d.nml", os.path.join(d, "s.his"))
    os.link(os.path.join(d, "d.nml"), os.path.join(d, "h.evt"))
    inputs = ("x.prf", "y.lock", "foo.his", "d.nml", "a.nml", "b.nml")
    before = {n: open(os.path.join(d, n), "rb").read() for n in inputs}
    cases = (("table_prf", "a.nml", "x", "'x.prf' is the load table of this deck"),
             ("table_lock", "b.nml", "y", "'y.lock' is the load table of this deck"),
             ("deck_his", "foo.his", "foo", "'foo.his' is the deck itself"),
             ("symlink", "d.nml", "s", "'s.his' is the deck itself"),
             ("hard_link", "d.nml", "h", "'h.evt' is the deck itself"))
    for name, deck, prefix, expect in cases:
        left = set(os.listdir(d))
        r = run(exe, [deck, "--quiet", "--output", prefix], d)
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and expect in lines[0],
              f"output over input {name}: exit {r.returncode}, {r.stderr!r}")
        check(set(os.listdir(d)) == left, f"output over input {name}: files made "
              f"{sorted(set(os.listdir(d)) - left)}")
        print(f"ok   output over input {name}: {lines[0] if lines else ''}")
    # a checkpoint written as CK.part, renamed at the end: CK.part the deck
    with open(os.path.join(d, "ck.h5.part"), "w") as f:
        f.write(SMALL.replace("title = 'small'", "title = 'small', checkpoint = 'ck.h5'"))
    deck_text = open(os.path.join(d, "ck.h5.part")).read()
    r = run(exe, ["ck.h5.part", "--quiet", "--output", "ckp"], d)
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "written as 'ck.h5.part'" in lines[0]
          and "is the deck itself" in lines[0]
          and open(os.path.join(d, "ck.h5.part")).read() == deck_text
          and not os.path.exists(os.path.join(d, "ckp.his")),
          f"output over input, checkpoint.part: exit {r.returncode}, {r.stderr!r}")
    print(f"ok   output over input checkpoint.part: {lines[0] if lines else ''}")
    # a sweep's table named like its deck
    sweep = SMALL + "&sweep vary = 'p0', values = 1e6, 2e6 /\n"
    with open(os.path.join(d, "z.sweep"), "w") as f:
        f.write(sweep)
    r = run(exe, ["--sweep", "z.sweep", "--quiet", "--output", "z"], d)
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "'z.sweep' is the deck itself" in lines[0]
          and open(os.path.join(d, "z.sweep")).read() == sweep,
          f"output over input, sweep: exit {r.returncode}, {r.stderr!r}")
    print(f"ok   output over input sweep: {lines[0] if lines else ''}")
    for n in inputs:
        check(open(os.path.join(d, n), "rb").read() == before[n], f"output over input: {n} changed")


def deck_reals(exe, work, check):
    d = os.path.join(work, "reals")
    os.makedirs(d)
    cases = [
        ("t_cut", "t_k = 1e-4", "t_k = 1e-4, t_cut = -1e308", "&load: t_cut = -1e308"),
        ("t_k", "t_k = 1e-4", "t_k = -1e308", "&load: t_k = -1e308"),
        ("gap", "strength = 1e5, -1", "strength = 1e5, -1, interface = 'dry', gap = -1e308",
         "&segments: gap(1) = -1e308"),
        ("profile", "profile_times = 1e-4, 2e-4", "profile_times = -1e308",
         "&run: profile_times(1) = -1e308"),
        ("velocity", "strength = 1e5, -1", "strength = 1e5, -1, velocity = -1e308",
         "&segments: velocity(1) = -1e308"),
        ("velocity_huge", "strength = 1e5, -1",
         "strength = 1e5, -1, velocity = 2*-1.7976931348623157e308", "&segments: velocity(1)"),
        ("dt", "cells = 200", "dt = 1e308", "&mesh: dt = 1e308"),
        ("young_denormal", "young = 2*1e9", "young = 1e-310, 1e9", "&segments: young(1)"),
        ("modulus_tiny", "t_k = 1e-4 /", "t_k = 1e-4 /\n&strength_field kind = 'weibull', "
         "modulus = 1e-300, scale = 1e6 /", "&strength_field: modulus = 1e-300"),
        ("p0_nan_unused", "kind = 'power', p0 = 1e6, t_k = 1e-4", "kind = 'none', p0 = NaN",
         "&load: p0 must be a finite number"),
        ("modulus_nan_uniform", "t_k = 1e-4 /", "t_k = 1e-4 /\n&strength_field modulus = NaN /",
         "&strength_field: modulus must be a finite number"),
    ]
    for name, old, new, expect in cases:
        text = SMALL.replace(old, new, 1)
        check(text != SMALL, f"{name}: the case does not change the deck")
        with open(os.path.join(d, name + ".nml"), "w") as f:
            f.write(text)
        r = run(exe, [name + ".nml", "--quiet"], d)
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and expect in lines[0],
              f"{name}: exit {r.returncode}, {r.stderr!r}, expected {expect!r}")
        check(not os.path.exists(os.path.join(d, name + ".his")), f"{name}: wrote {name}.his")
        print(f"ok   {name}: {lines[0] if lines else ''}")


def load_tables(exe, work, check):
    """A load table row is two numbers and nothing else: a '/' (which a list-directed read
    takes for "keep the previous value"), a repeat count, a third word, a row cut at the
    buffer's length are refused with the line number."""
    d = os.path.join(work, "tables")
    os.makedirs(d)
    deck = SMALL.replace("kind = 'power', p0 = 1e6, t_k = 1e-4", "kind = 'table', table = 't.txt'")
    long_number = "0." + "0" * 1100 + "1"
    for name, rows, expect in (
            ("slash", "0 0\n1e-5 /\n2e-5 0\n", "line 2: expected two numbers"),
            ("repeat", "0 0\n1e-5 2*1\n", "line 2: expected two numbers"),
            ("third_word", "0 0\n1e-5 1e5 junk\n2e-5 0\n", "line 2: expected two numbers"),
            ("long_line", f"0 0\n{long_number} 5\n2 0\n", "line 2: longer than 1024"),
            ("huge", "0 0\n1e-5 1e61\n", "line 2: values must be 0 or between"),
            ("nan", "0 0\n1e-5 nan\n", "line 2: expected two numbers")):
        with open(os.path.join(d, "t.txt"), "w") as f:
            f.write(rows)
        with open(os.path.join(d, name + ".nml"), "w") as f:
            f.write(deck)
        r = run(exe, [name + ".nml", "--quiet"], d)
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and expect in lines[0],
              f"table {name}: exit {r.returncode}, {r.stderr!r}, expected {expect!r}")
        print(f"ok   table {name}: {lines[0] if lines else ''}")
    with open(os.path.join(d, "t.txt"), "w") as f:
        f.write("0 0\n1.5D-5, +2.e4\n3e-5\t0\n")
    r = run(exe, ["slash.nml", "--quiet"], d)
    check(r.returncode == 0, f"table with d exponent, comma and tab: exit {r.returncode} {r.stderr!r}")


def tampered_checkpoints(exe, work, check):
    """A checkpoint whose state, summary or counts were changed after it was written (one
    bit flipped, a count made negative, an array's bound moved) is refused with exit 2; the
    untouched one restarts. Needs h5py (the project venv)."""
    try:
        import h5py
        import numpy as np
    except ImportError:
        print("skip tampered checkpoints: no h5py")
        return
    d = os.path.join(work, "tamper")
    os.makedirs(d)
    full = SMALL.replace("t_end = 2.0e-4", "t_end = 4.0e-4")
    short = SMALL.replace("title = 'small'", "title = 'small', checkpoint = 'ck.h5'")
    with open(os.path.join(d, "full.nml"), "w") as f:
        f.write(full)
    with open(os.path.join(d, "short.nml"), "w") as f:
        f.write(short)
    r = run(exe, ["short.nml", "--output", "run", "--quiet"], d)
    check(r.returncode == 0, f"checkpointed run: exit {r.returncode} {r.stderr!r}")
    shutil.copy(os.path.join(d, "ck.h5"), os.path.join(d, "good.h5"))

    def flip_bit(f):
        a = f["state/ua"][...]
        a.view(np.int64)[len(a) // 2] ^= 1 << 20
        f["state/ua"][...] = a

    def negative_split(f):
        f["state"].attrs["n_split"] = np.int32(-5)

    def negative_rows(f):
        f["outputs"].attrs["rows_history"] = np.int32(-3)

    def moved_bound(f):
        f["state"].attrs["s:lbound"] = np.int32(7)

    def huge_count(f):
        f["outputs"].attrs["rows_events"] = np.int32(1000000000)

    for name, damage in (("bit", flip_bit), ("n_split", negative_split),
                         ("rows", negative_rows), ("lbound", moved_bound),
                         ("rows_events", huge_count)):
        for ext in (".his", ".prf", ".evt", ".frg"):
            shutil.copy(os.path.join(d, "run" + ext), os.path.join(d, "t_" + name + ext))
        path = os.path.join(d, name + ".h5")
        shutil.copy(os.path.join(d, "good.h5"), path)
        with h5py.File(path, "r+") as f:
            damage(f)
        r = run(exe, ["full.nml", "--output", "t_" + name, "--restart", name + ".h5", "--quiet"], d)
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and ("damaged" in lines[0] or
                                                        "cannot be read" in lines[0]),
              f"tampered checkpoint ({name}): exit {r.returncode}, {r.stderr!r}")
        print(f"ok   tampered checkpoint {name}: {lines[0] if lines else ''}")
    r = run(exe, ["full.nml", "--output", "run", "--restart", "good.h5", "--quiet"], d)
    check(r.returncode == 0, f"untouched checkpoint restarts: exit {r.returncode} {r.stderr!r}")


def special_files(exe, work, check):
    """A FIFO (or a device) is never a deck, a load table or a checkpoint: a FIFO deck hung
    in open, or was read once by the scan only; a checkpoint renamed over a device or the
    load table replaced it (issue 19). Exit 2, one line, nothing written."""
    d = os.path.join(work, "special")
    os.makedirs(d)
    os.mkfifo(os.path.join(d, "fifo"))
    with open(os.path.join(d, "t.txt"), "w") as f:
        f.write("0 0\n1e-4 1e6\n2e-4 0\n")
    table = SMALL.replace("kind = 'power', p0 = 1e6, t_k = 1e-4", "kind = 'table', table = 't.txt'")
    cases = (("deck_fifo", None, "fifo", "deck: 'fifo' is not a regular file"),
             ("table_fifo", table.replace("'t.txt'", "'fifo'"), "d.nml",
              "&load: table = 'fifo': not a regular file"),
             ("checkpoint_table", table.replace("title = 'small'",
                                                "title = 'small', checkpoint = 't.txt'"),
              "d.nml", "&run: checkpoint = 't.txt' is the load table of this deck"),
             ("checkpoint_fifo", SMALL.replace("title = 'small'",
                                               "title = 'small', checkpoint = 'fifo'"),
              "d.nml", "&run: checkpoint = 'fifo' is not a regular file"))
    for name, text, deck, expect in cases:
        if text is not None:
            with open(os.path.join(d, deck), "w") as f:
                f.write(text)
        before = open(os.path.join(d, "t.txt")).read()
        try:
            r = subprocess.run([exe, deck, "--quiet", "--output", "out"], cwd=d, timeout=20,
                               capture_output=True, text=True, stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired:
            check(False, f"{name}: hangs")
            continue
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and expect in lines[0],
              f"{name}: exit {r.returncode}, {r.stderr!r}")
        check(open(os.path.join(d, "t.txt")).read() == before, f"{name}: the load table changed")
        check(stat.S_ISFIFO(os.stat(os.path.join(d, "fifo")).st_mode), f"{name}: the FIFO replaced")
        check(not any(os.path.exists(os.path.join(d, "out" + e))
                      for e in (".his", ".prf", ".evt", ".frg", ".h5")), f"{name}: wrote outputs")
        print(f"ok   {name}: {lines[0] if lines else ''}")


MEM_DECK = """&run t_end = {t_end}, title = 'memory'{extra} /
&mesh cells = {cells} /
&segments n = 1, length = 1.0, young = 2e11, density = 8000, strength = 1e9 /
&load kind = 'power', p0 = 1e6, t_k = 1e-4 /
"""


def run_env(exe, args, cwd, env=None, limit_as=None):
    """Run spallbar with extra environment variables and an address-space limit (bytes)."""
    full = dict(os.environ)
    full.update(env or {})

    def limit():
        if limit_as:
            import resource
            resource.setrlimit(resource.RLIMIT_AS, (limit_as, limit_as))
    return subprocess.run([exe] + args, cwd=cwd, capture_output=True, text=True,
                          errors="replace", timeout=600, stdin=subprocess.DEVNULL,
                          env=full, preexec_fn=limit)


def only_deck(d, name):
    """Files in folder d other than the decks."""
    return sorted(f for f in os.listdir(d) if not f.endswith(".nml"))


def memory_limits(exe, work, check):
    """What a deck needs is checked against the memory before anything large is allocated
    (SPALLBAR_MEMORY_LIMIT lowers the machine's limit; ulimit -v is the address space)."""
    d = os.path.join(work, "memory")
    os.makedirs(d)
    def mesh_refused(name, extra, mb, words):
        """The 1e6-cell deck NAME under a limit of MB megabytes: exit 2, one line naming
        &mesh cells, the limit and words, nothing written."""
        with open(os.path.join(d, name + ".nml"), "w") as f:
            f.write(MEM_DECK.format(t_end="2e-9", cells=1000000, extra=extra))
        r = run_env(exe, [name + ".nml", "--quiet"], d,
                    {"SPALLBAR_MEMORY_LIMIT": str(mb * 10**6)})
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and "&mesh: cells = 1000000" in lines[0]
              and words in lines[0] and f"{mb}.0 MB" in lines[0],
              f"{name}, 1e6 cells under {mb} MB: exit {r.returncode} {r.stderr!r}")
        check(only_deck(d, name) == [], f"{name} under {mb} MB wrote {only_deck(d, name)}")
        print(f"ok   {name}, 1e6 cells, limit {mb} MB: {lines[0] if lines else ''}")

    mesh_refused("big", "", 50, "memory")

    # a bar the characteristic steps would serve (rows every 1e6 steps) needs their arrays
    # too (about 80 bytes a cell: 1e6 cells ~304 MB, ~224 MB on the lattice): under 280 MB
    # they do not fit, and every step is the lattice's, with a note (0.6.3 refused the run;
    # a sweep's cases went over the limit unchecked): the outputs are the lattice's, bit
    # for bit, where without the limit the rings serve the deck (some bit differs)
    def outputs(prefix, exts):
        return {e: open(os.path.join(d, prefix + e)).read().replace(prefix, "PREFIX")
                for e in exts}
    with open(os.path.join(d, "ringbig.nml"), "w") as f:
        f.write(MEM_DECK.format(t_end="1e-8", cells=1000000, extra=", history_every = 1000000"))
    limited = {"SPALLBAR_MEMORY_LIMIT": str(280 * 10**6)}
    r = run_env(exe, ["ringbig.nml", "--quiet", "--output", "lim"], d, limited)
    notes = [l for l in r.stderr.splitlines() if l.strip()]
    check(r.returncode == 0 and len(notes) == 1 and notes[0].startswith("spallbar: note: ")
          and "characteristic steps" in notes[0] and "280.0 MB" in notes[0]
          and "lattice" in notes[0],
          f"ringbig, 1e6 cells under 280 MB: exit {r.returncode} {r.stderr!r}")
    r_lat = run_env(exe, ["ringbig.nml", "--quiet", "--output", "lat"], d,
                    {"SPALLBAR_STEPPING": "lattice"})
    r_free = run_env(exe, ["ringbig.nml", "--quiet", "--output", "free"], d)
    exts = (".his", ".evt", ".prf", ".frg", ".imp", ".spl")
    if r.returncode == 0 and r_lat.returncode == 0 and r_free.returncode == 0:
        check(outputs("lim", exts) == outputs("lat", exts),
              "ringbig under 280 MB: outputs differ from SPALLBAR_STEPPING=lattice")
        check(outputs("free", exts) != outputs("lat", exts),
              "ringbig without a limit: the rings did not serve it (every bit as the lattice)")
        check(r_free.stderr.strip() == "", f"ringbig without a limit said {r_free.stderr!r}")
        print(f"ok   ringbig, 1e6 cells, limit 280 MB: the lattice's outputs; {notes[0]}")
    else:
        check(False, f"ringbig: exit {r.returncode}, lattice {r_lat.returncode}, "
              f"free {r_free.returncode}: {r_lat.stderr!r} {r_free.stderr!r}")
    # a restart holds the checkpoint's state beside the run's (200 bytes a cell): under a
    # limit the uninterrupted run's rings fitted (1e5 cells, 60 MB) the restart's do not,
    # and its note says that it is then bit-identical only to a run on the lattice
    for t, name in (("5e-7", "short"), ("1e-6", "long")):
        with open(os.path.join(d, f"rs_{name}.nml"), "w") as f:
            f.write(MEM_DECK.format(t_end=t, cells=100000, extra=", history_every = 50, "
                                    f"checkpoint = 'rs_{name}.ck.h5'"))
    small_limit = {"SPALLBAR_MEMORY_LIMIT": str(60 * 10**6)}
    r = run_env(exe, ["rs_short.nml", "--quiet", "--output", "rs"], d, small_limit)
    check(r.returncode == 0 and r.stderr.strip() == "",
          f"1e5 cells under 60 MB (the rings fit): exit {r.returncode} {r.stderr!r}")
    r = run_env(exe, ["rs_long.nml", "--quiet", "--output", "rs", "--restart", "rs_short.ck.h5"],
                d, small_limit)
    notes = [l for l in r.stderr.splitlines() if l.strip()]
    check(r.returncode == 0 and len(notes) == 1 and "do not fit" in notes[0] and
          "a restart is then bit-identical only to a run that took its steps on the lattice"
          in notes[0], f"its restart under 60 MB: exit {r.returncode} {r.stderr!r}")
    if r.returncode == 0:
        print("ok   a restart whose rings do not fit beside the checkpoint says so")
    for f in os.listdir(d):
        if f.startswith("rs"):
            os.remove(os.path.join(d, f))
    # a sweep's cases the same: its table the lattice's, row for row
    with open(os.path.join(d, "ringsweep.nml"), "w") as f:
        f.write(MEM_DECK.format(t_end="1e-8", cells=1000000, extra="") +
                "&strength_field kind = 'weibull', modulus = 6.0, scale = 1e9 /\n"
                "&sweep realizations = 2, seed = 1 /\n")

    def table(prefix):
        return [l for l in open(os.path.join(d, prefix + ".sweep")) if not l.startswith("#")]
    rs = run_env(exe, ["--sweep", "ringsweep.nml", "--quiet", "--output", "slim"], d, limited)
    rs_lat = run_env(exe, ["--sweep", "ringsweep.nml", "--quiet", "--output", "slat"], d,
                     {"SPALLBAR_STEPPING": "lattice"})
    check(rs.returncode == 0 and rs_lat.returncode == 0 and len(table("slim")) == 3 and
          table("slim") == table("slat"),
          f"a sweep of 1e6-cell cases under 280 MB: exit {rs.returncode} {rs.stderr!r}, "
          f"lattice {rs_lat.returncode}")
    if rs.returncode == 0:
        print("ok   a sweep of 1e6-cell cases under 280 MB: the lattice's table")
    for f in only_deck(d, "ringbig"):      # (the folder holds only decks for the checks below)
        os.remove(os.path.join(d, f))
    for f in ("ringbig.nml", "ringsweep.nml"):
        os.remove(os.path.join(d, f))

    # the largest mesh the deck reader takes, under ulimit -v 3 GB: refused, not
    # "Error allocating"
    with open(os.path.join(d, "huge.nml"), "w") as f:
        f.write(MEM_DECK.format(t_end="2e-11", cells=50000000, extra=""))
    r = run_env(exe, ["huge.nml", "--quiet"], d, limit_as=3 * 2**30)
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "&mesh: cells = 50000000" in lines[0]
          and "GB of memory" in lines[0],
          f"5e7 cells under ulimit -v 3 GB: exit {r.returncode} {r.stderr!r}")
    check(only_deck(d, "huge") == [], "5e7 cells under ulimit -v: wrote files")
    print(f"ok   5e7 cells, ulimit -v 3 GB: {lines[0] if lines else ''}")

    # hdf5 x-t rows: 1e5 cells need ~42 MB before the buffer and 6.4 MB per buffered time
    xt = MEM_DECK.format(t_end="4e-8", cells=100000, extra=", hdf5 = .true., field_every = 1")
    with open(os.path.join(d, "xt.nml"), "w") as f:
        f.write(xt)
    r = run_env(exe, ["xt.nml", "--quiet", "--output", "xt_full"], d)
    check(r.returncode == 0, f"x-t run: exit {r.returncode} {r.stderr!r}")
    r = run_env(exe, ["xt.nml", "--quiet", "--output", "xt_short"], d,
                {"SPALLBAR_MEMORY_LIMIT": str(60 * 10**6)})
    check(r.returncode == 0, f"x-t run under 60 MB (a smaller buffer): exit {r.returncode} "
          f"{r.stderr!r}")
    same = r.returncode == 0 and all(
        open(os.path.join(d, "xt_full" + e), "rb").read().replace(b"xt_full", b"")
        == open(os.path.join(d, "xt_short" + e), "rb").read().replace(b"xt_short", b"")
        for e in (".his", ".evt"))
    check(same, "x-t run under 60 MB: history or events differ from the full buffer's")
    h5diff = shutil.which("h5diff")
    if h5diff and r.returncode == 0:
        c = subprocess.run([h5diff, "xt_full.h5", "xt_short.h5", "/fields/xt", "/fields/xt"],
                           cwd=d, capture_output=True, text=True)
        check(c.returncode == 0, f"x-t run under 60 MB: /fields/xt differs: {c.stdout[-300:]!r}")
        print("ok   x-t fields with a smaller buffer equal the full buffer's (h5diff)")
    else:
        print("skip comparing the x-t fields: no h5diff here")
    r = run_env(exe, ["xt.nml", "--quiet", "--output", "xt_refused"], d,
                {"SPALLBAR_MEMORY_LIMIT": str(45 * 10**6)})
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "&run: field_every = 1" in lines[0]
          and "memory" in lines[0], f"x-t under 45 MB: exit {r.returncode} {r.stderr!r}")
    check(not any(f.startswith("xt_refused") for f in os.listdir(d)),
          "x-t under 45 MB: wrote files")
    print(f"ok   x-t rows, limit 45 MB: {lines[0] if lines else ''}")

    # a sweep whose table and histograms do not fit
    with open(os.path.join(d, "sw.nml"), "w") as f:
        f.write(SMALL + "&strength_field kind = 'weibull', modulus = 6, scale = 1e5 /\n"
                "&sweep realizations = 1000000, bins = 100000 /\n")
    r = run_env(exe, ["--sweep", "sw.nml", "--quiet"], d,
                {"SPALLBAR_MEMORY_LIMIT": str(10**9)})
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and lines[0].startswith("spallbar: &sweep: ")
          and "realizations = 1000000" in lines[0] and "bins = 100000" in lines[0]
          and "GB of memory" in lines[0], f"huge sweep table: exit {r.returncode} {r.stderr!r}")
    check(not any(f.startswith("sw.") and f != "sw.nml" or f.startswith("sw_")
                  for f in os.listdir(d)), "huge sweep table: wrote files")
    print(f"ok   sweep table beyond the memory: {lines[0] if lines else ''}")

    # a normal deck under a generous limit runs as before
    with open(os.path.join(d, "small.nml"), "w") as f:
        f.write(SMALL)
    r = run_env(exe, ["small.nml", "--quiet", "--output", "lim"], d,
                {"SPALLBAR_MEMORY_LIMIT": str(2 * 10**9)})
    r0 = run_env(exe, ["small.nml", "--quiet", "--output", "nolim"], d)
    check(r.returncode == 0 and r0.returncode == 0,
          f"small deck under 2 GB: exit {r.returncode} {r.stderr!r}")
    check(r.returncode == 0 and open(os.path.join(d, "lim.his")).read().replace("lim", "") ==
          open(os.path.join(d, "nolim.his")).read().replace("nolim", ""),
          "small deck under 2 GB: history differs")
    print("ok   a small deck under a 2 GB limit runs as without it")

    # a bar the characteristic steps do not serve (four layers of 10 cells: their rings
    # would cost more a step than the lattice) and rows far apart: the lattice takes the
    # steps between checks (every 64), not the whole 8e6 steps to the next row in one call
    # with a record of each (1.1 GB in 0.6.1, which broke under this limit)
    with open(os.path.join(d, "layers.nml"), "w") as f:
        f.write("&run t_end = 4.0, history_every = 1000000000, warnings = .false. /\n"
                "&mesh dt = 5.0e-7 /\n&segments n = 4, length = 4*0.025, "
                "young = 2e11, 1e11, 2e11, 1e11, density = 8000, 4000, 8000, 4000 /\n"
                "&load kind = 'power', p0 = 1e6, t_k = 1e-5 /\n")
    r = run_env(exe, ["layers.nml", "--quiet", "--output", "layers"], d,
                limit_as=384 * 2**20)
    check(r.returncode == 0 and os.path.exists(os.path.join(d, "layers.his")),
          f"8e6 lattice steps between rows under 384 MB: exit {r.returncode} "
          f"{r.stderr[-300:]!r}")
    if r.returncode == 0:
        print("ok   8e6 lattice steps between two rows run under a 384 MB address space")


def make_cgroup(limit):
    """A child cgroup of this process's own with a memory limit (bytes): (the file a
    process joins it through, the folder), or (None, why) where cgroups cannot be made
    here (not root, no writable hierarchy, no memory controller). The hierarchies are
    found in /proc/self/mountinfo (cgroup with the memory option: v1; cgroup2: v2), and a
    folder made there counts only when the kernel gave it its limit file (a real cgroup, not
    a folder of a tmpfs); the root cgroup's controls are never written."""
    try:
        paths = {}
        for line in open("/proc/self/cgroup").read().splitlines():
            hid, ctrl, path = line.split(":", 2)
            if hid == "0" and ctrl == "":
                paths["v2"] = path
            elif "memory" in ctrl.split(","):
                paths["v1"] = path
        mounts = []
        for line in open("/proc/self/mountinfo").read().splitlines():
            head, _, tail = line.partition(" - ")
            f, t = head.split(), tail.split()
            if len(f) < 5 or len(t) < 3:
                continue
            if t[0] == "cgroup" and "memory" in t[2].split(","):
                mounts.append(("v1", f[3], f[4]))
            elif t[0] == "cgroup2":
                mounts.append(("v2", f[3], f[4]))
    except (OSError, ValueError) as e:
        return None, f"cannot read /proc/self ({e})"
    name = f"spallbar-test-{os.getpid()}"
    for version, root, mount in mounts:
        path = paths.get(version)
        if path is None or not (root == "/" or (path + "/").startswith(root + "/")):
            continue
        own = os.path.join(mount, path[len(root):].lstrip("/") if root != "/" else
                           path.lstrip("/"))
        limit_file = "memory.limit_in_bytes" if version == "v1" else "memory.max"
        folder = os.path.join(own, name)
        try:
            if version == "v2" and os.path.realpath(own) != os.path.realpath(mount):
                with open(os.path.join(own, "cgroup.subtree_control"), "w") as f:
                    f.write("+memory")
            os.mkdir(folder)
        except OSError:
            continue
        if not os.path.exists(os.path.join(folder, limit_file)):
            os.rmdir(folder)
            continue
        try:
            with open(os.path.join(folder, limit_file), "w") as f:
                f.write(str(limit))
            return os.path.join(folder, "cgroup.procs"), folder
        except OSError:
            os.rmdir(folder)
    return None, "no writable cgroup memory hierarchy"


def cgroup_limit(exe, work, check):
    """A cgroup's memory limit (Slurm's --mem, a container's) is a limit like ulimit -v: a
    deck beyond it is refused, exit 2 naming &mesh cells and the limit, nothing written
    (0.6.3 ran it and the kernel killed it without a word, exit 137); a deck within it
    runs. Skipped with a message where no cgroup can be made."""
    d = os.path.join(work, "cgroup")
    os.makedirs(d)
    procs, folder = make_cgroup(100 * 10**6)
    if procs is None:
        print(f"skip cgroup memory limit: {folder}")
        return

    def join():
        with open(procs, "w") as f:
            f.write(str(os.getpid()))
    try:
        with open(os.path.join(d, "big.nml"), "w") as f:
            f.write(MEM_DECK.format(t_end="2e-9", cells=1000000, extra=""))
        with open(os.path.join(d, "small.nml"), "w") as f:
            f.write(SMALL)
        r = subprocess.run([exe, "big.nml", "--quiet"], cwd=d, capture_output=True, text=True,
                           timeout=600, stdin=subprocess.DEVNULL, preexec_fn=join)
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and "&mesh: cells = 1000000" in lines[0]
              and "the limit here is 100.0 MB" in lines[0],
              f"1e6 cells in a 100 MB cgroup: exit {r.returncode} {r.stderr!r}")
        check(only_deck(d, "big") == [], f"1e6 cells in a 100 MB cgroup wrote {only_deck(d, 'big')}")
        r2 = subprocess.run([exe, "small.nml", "--quiet"], cwd=d, capture_output=True,
                            text=True, timeout=600, stdin=subprocess.DEVNULL, preexec_fn=join)
        check(r2.returncode == 0, f"a small deck in a 100 MB cgroup: exit {r2.returncode} "
              f"{r2.stderr!r}")
        if r.returncode == 2 and r2.returncode == 0:
            print(f"ok   cgroup limit 100 MB ({folder}): {lines[0] if lines else ''}; a small "
                  "deck runs")
    finally:
        try:
            os.rmdir(folder)
        except OSError as e:
            print(f"note: cannot remove {folder}: {e}")


def weibull_overflow(exe, work, check):
    """A Weibull field whose largest draw overflows the deck's reals is refused before any
    strength is drawn (it was SIGFPE in the Debug build, Inf strengths in Release)."""
    d = os.path.join(work, "weibull")
    os.makedirs(d)
    with open(os.path.join(d, "w.nml"), "w") as f:
        f.write(SMALL + "&strength_field kind = 'weibull', modulus = 1e-3, scale = 3e6 /\n")
    r = run(exe, ["w.nml", "--quiet"], d)
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and
          lines[0].startswith("spallbar: &strength_field: modulus = ") and "overflow" in lines[0],
          f"weibull modulus 1e-3: exit {r.returncode} {r.stderr!r}")
    check(only_deck(d, "w") == [], "weibull modulus 1e-3: wrote files")
    print(f"ok   weibull modulus 1e-3: {lines[0] if lines else ''}")
    with open(os.path.join(d, "w.nml"), "w") as f:
        f.write(SMALL + "&strength_field kind = 'weibull', modulus = 0.02, scale = 1e-50 /\n")
    r = run(exe, ["w.nml", "--quiet"], d)
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "modulus = 0.02" in lines[0] and
          "underflow" in lines[0], f"weibull underflow: exit {r.returncode} {r.stderr!r}")
    with open(os.path.join(d, "w.nml"), "w") as f:
        f.write(SMALL + "&strength_field kind = 'weibull', modulus = 0.2, scale = 1e5 /\n")
    r = run(exe, ["w.nml", "--quiet"], d)
    check(r.returncode == 0, f"weibull modulus 0.2: exit {r.returncode} {r.stderr!r}")
    # a sweep over the modulus reaching the overflow is refused before any case runs
    with open(os.path.join(d, "s.nml"), "w") as f:
        f.write(SMALL + "&strength_field kind = 'weibull', modulus = 6, scale = 1e5 /\n"
                "&sweep vary = 'modulus', values = 6, 1e-3 /\n")
    r = run(exe, ["--sweep", "s.nml", "--quiet"], d)
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "&sweep: values(2)" in lines[0] and
          "overflow" in lines[0], f"sweep to modulus 1e-3: exit {r.returncode} {r.stderr!r}")
    print(f"ok   sweep to modulus 1e-3: {lines[0] if lines else ''}")


def sweep_outputs_first(exe, work, check):
    """A sweep checks its outputs before any case runs: one that is a folder is exit 2 at
    once, one line, nothing created (it ran every case and exited 3 before)."""
    for name in ("out.sweep", "out_sweep.h5", "out.sweep.part", "out_sweep.h5.part", "out"):
        d = os.path.join(work, "sweep_" + name.replace(".", "_"))
        os.makedirs(os.path.join(d, name))
        with open(os.path.join(d, "sw.nml"), "w") as f:
            f.write(SWEEP)
        t0 = time.time()
        r = run(exe, ["--sweep", "sw.nml", "--quiet", "--output", "out"], d)
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and name in lines[0] and
              "folder" in lines[0], f"sweep, {name} a folder: exit {r.returncode} {r.stderr!r}")
        check(sorted(os.listdir(d)) == sorted([name, "sw.nml"]),
              f"sweep, {name} a folder: left {sorted(os.listdir(d))}")
        print(f"ok   sweep, {name} a folder ({time.time() - t0:.2f} s): "
              f"{lines[0] if lines else ''}")


def wait_for(path, proc, seconds=60):
    """Wait until path exists (or the process ended, or the time is up)."""
    t0 = time.monotonic()
    while not os.path.exists(path) and proc.poll() is None and time.monotonic() - t0 < seconds:
        time.sleep(0.01)


def snapshot_bytes(d, names):
    """The bytes of each existing file of names in d."""
    return {n: open(os.path.join(d, n), "rb").read() for n in names
            if os.path.exists(os.path.join(d, n))}


def reader_holds_h5(exe, work, check):
    """Issue 32, item 3: a reader holding PREFIX.h5 (HDF5 1.10 takes a flock on a file it
    opens, as h5py and ParaView do: a shared lock here) does not cost a rerun or the previous
    results: the rerun writes temporaries and renames them, exit 0; the reader goes on
    reading the previous file. A run that fails (the energy guard, exit 3) leaves the previous
    set byte for byte and its own as PREFIX.*.part, named in its message."""
    import fcntl
    d = os.path.join(work, "reader")
    os.makedirs(d)
    deck = SLOW.replace("&run t_end = 4.0e-3,", "&run t_end = 1.0e-3, hdf5 = .true., field_every = 50,")
    with open(os.path.join(d, "run.nml"), "w") as f:
        f.write(deck)
    r = run(exe, ["run.nml", "--quiet"], d)
    check(r.returncode == 0, f"reader: first run exit {r.returncode} {r.stderr!r}")
    h5 = os.path.join(d, "run.h5")
    with open(h5, "rb") as held:
        fcntl.flock(held, fcntl.LOCK_SH)
        before = held.read()
        r = run(exe, ["run.nml", "--quiet"], d)
        check(r.returncode == 0 and not r.stderr,
              f"reader holds run.h5: rerun exit {r.returncode} {r.stderr!r} (was exit 3, "
              "h5fcreate_f failed, the text files cut)")
        held.seek(0)
        check(held.read() == before, "reader holds run.h5: what it reads changed under it")
    left = sorted(f for f in os.listdir(d) if f.endswith(".part"))
    check(not left, f"reader holds run.h5: temporaries left {left}")
    check(os.path.getsize(h5) > 0 and open(os.path.join(d, "run.xmf")).read().count("run.h5") > 0,
          "reader holds run.h5: the new run.h5 and run.xmf are whole")
    print("ok   a reader holding PREFIX.h5: the rerun exits 0, the reader keeps its file")
    # a run that fails on the same prefix
    names = ["run" + e for e in (".his", ".prf", ".evt", ".frg", ".h5", ".xmf")]
    kept = snapshot_bytes(d, names)
    with open(os.path.join(d, "bad.nml"), "w") as f:
        f.write("&run t_end = 2e-3, events = 'paper', history_every = 1, hdf5 = .true. /\n"
                "&mesh dt = 1e-5 /\n&segments n = 2, length = 0.01, 0.01, young = 2e9, 2e9,\n"
                "  density = 2000, 2000, strength = 0, 0, velocity = 1, -1 /\n")
    r = run(exe, ["bad.nml", "--quiet", "--output", "run"], d)
    lines = one_line(r)
    check(r.returncode == 3 and len(lines) == 1 and
          "this run's outputs are run.*.part, the previous run.* are as they were" in lines[0],
          f"a failing rerun: exit {r.returncode}, {r.stderr!r}")
    check(snapshot_bytes(d, names) == kept, "a failing rerun: the previous outputs changed")
    check(os.path.getsize(os.path.join(d, "run.his.part")) > 0, "a failing rerun: no run.his.part")
    print(f"ok   a failing rerun keeps the previous outputs: {lines[0] if lines else ''}")


def checkpoint_locks(exe, work, check):
    """Issue 32, item 4: the checkpoint under the lock discipline of PREFIX. The same deck
    (with a checkpoint) run twice at once on two prefixes: the second is refused at start
    (exit 2, one line), the first ends with exit 0 (it died mid-run on the checkpoint's
    .part). A checkpoint that is the HDF5 output of a running prefix, in either order:
    refused at start, the running one untouched."""
    d = os.path.join(work, "cklock")
    os.makedirs(d)
    deck = SLOW.replace("&run t_end = 4.0e-3,", "&run t_end = 4.0e-3, checkpoint = 'run.ck.h5', "
                        "checkpoint_every = 200,")
    with open(os.path.join(d, "run.nml"), "w") as f:
        f.write(deck)
    first = subprocess.Popen([exe, "run.nml", "--quiet", "--output", "a"], cwd=d,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_for(os.path.join(d, "run.ck.h5.lock"), first)
    time.sleep(0.05)
    r = run(exe, ["run.nml", "--quiet", "--output", "b"], d)
    lines = one_line(r)
    check(r.returncode == 2 and len(lines) == 1 and "&run: checkpoint = 'run.ck.h5'" in lines[0]
          and "in use by another spallbar run" in lines[0],
          f"one checkpoint, two runs: second exit {r.returncode}, {r.stderr!r}")
    check(not os.path.exists(os.path.join(d, "b.his")) and
          not os.path.exists(os.path.join(d, "b.his.part")), "one checkpoint, two runs: b written")
    _, err = first.communicate(timeout=600)
    check(first.returncode == 0, f"one checkpoint, two runs: first exit {first.returncode} {err!r}")
    print(f"ok   one checkpoint, two runs: {lines[0] if lines else ''}")
    # checkpoint = 'b.h5' beside a run with --output b and HDF5, both orders
    with open(os.path.join(d, "h5.nml"), "w") as f:
        f.write(SLOW.replace("&run t_end = 4.0e-3,", "&run t_end = 4.0e-3, hdf5 = .true.,"))
    with open(os.path.join(d, "ck.nml"), "w") as f:
        f.write(SLOW.replace("&run t_end = 4.0e-3,", "&run t_end = 4.0e-3, checkpoint = 'b.h5',"))
    for running, second, needle in (
            (["h5.nml", "--quiet", "--output", "b"], ["ck.nml", "--quiet", "--output", "c"],
             "is an output of another spallbar run on the prefix 'b'"),
            (["ck.nml", "--quiet", "--output", "c"], ["h5.nml", "--quiet", "--output", "b"],
             "'b.h5' is the checkpoint of another spallbar run")):
        for f in os.listdir(d):
            if f.startswith(("b.", "c.")):
                os.remove(os.path.join(d, f))
        first = subprocess.Popen([exe] + running, cwd=d, stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True)
        wait_for(os.path.join(d, running[3] + ".his.part"), first)
        r = run(exe, second, d)
        lines = one_line(r)
        check(r.returncode == 2 and len(lines) == 1 and needle in lines[0],
              f"checkpoint b.h5 beside --output b ({running[0]} first): exit {r.returncode}, "
              f"{r.stderr!r}")
        _, err = first.communicate(timeout=600)
        check(first.returncode == 0, f"checkpoint b.h5 beside --output b: the running one "
                                     f"exit {first.returncode} {err!r}")
        print(f"ok   checkpoint b.h5 beside --output b ({running[0]} first): "
              f"{lines[0] if lines else ''}")


def main():
    exe, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    full_disk(exe, work, check)
    output_is_folder(exe, work, check)
    concurrent(exe, work, check)
    checkpoint_paths(exe, work, check)
    outputs_over_inputs(exe, work, check)
    deck_reals(exe, work, check)
    load_tables(exe, work, check)
    tampered_checkpoints(exe, work, check)
    special_files(exe, work, check)
    memory_limits(exe, work, check)
    cgroup_limit(exe, work, check)
    weibull_overflow(exe, work, check)
    sweep_outputs_first(exe, work, check)
    reader_holds_h5(exe, work, check)
    checkpoint_locks(exe, work, check)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
