#!/usr/bin/env python3
"""Interrupted runs (issue 9): nothing written is lost.

A long run (a 400-cell bar, history every step, x-t fields, HDF5 on) is stopped twice:

  * SIGTERM: spallbar ends the step, writes the last history row, closes every file and
    exits with 128 + 15 = 143 and one message naming the step. Every text row is complete,
    the last one is that step, and PREFIX.h5 holds exactly the same rows.
  * SIGKILL: nothing can run. The files are flushed (text and HDF5) every 1024 steps when
    half a second has passed: every text line but possibly the last is a complete row,
    PREFIX.h5 opens and holds at least the first flush (1024 rows), and each of its rows
    equals the text row of the same index.

Since issue 32 a run writes PREFIX.ext.part and renames them at its end: a run stopped by a
signal (no checkpoint) leaves a previous set of PREFIX outputs as it was, and its own rows are
in the .part files, which the SIGTERM message names.

usage: cli_interrupt.py SPALLBAR WORKDIR    (needs h5py)
"""
import os
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

from clitools import Checks

DECK = """&run
  title = 'interrupted run'
  t_end = 10.0
  warnings = .false.   ! long on purpose (25000 transits): it is stopped by a signal
  history_every = 1
  hdf5 = .true.
  field_every = 100
/
&mesh
  cells = 400
/
&segments
  n = 1
  length = 2.0
  young = 200e9
  density = 8000
/
&load
  kind = 'power'
  p0 = 1.0e8
  t_k = 1.0e-4
  exponent = 1.0
  t_cut = 1.0e-4
/
"""


PREVIOUS = b"# the previous run's results: a run stopped by a signal leaves them (issue 32)\n"


def start(exe, work, name):
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(DECK)
    # a previous set of outputs on the same prefix
    for ext in (".his", ".prf", ".evt", ".frg", ".h5", ".xmf"):
        with open(os.path.join(work, name + ext), "wb") as f:
            f.write(PREVIOUS)
    p = subprocess.Popen([exe, name + ".nml", "-q"], cwd=work, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    his = os.path.join(work, name + ".his.part")   # the temporaries, until the run ends
    t0 = time.monotonic()
    # wait for a few thousand rows and more than one flush interval
    while time.monotonic() - t0 < 60:
        time.sleep(0.2)
        if os.path.exists(his) and os.path.getsize(his) > 3000 * 500 and time.monotonic() - t0 > 2.0:
            break
    time.sleep(0.7)
    return p


def text_rows(path):
    """Complete rows (as many numbers as the column line names) and whether a partial last
    line was left."""
    rows, partial = [], False
    with open(path) as f:
        lines = f.read().split("\n")
    tail = lines.pop()                  # after the last newline: '' when complete
    partial = tail != ""
    ncol = None
    for line in lines:
        if not line.startswith(" "):        # '#' lines, the column-name first line
            if line.startswith("# t ") or line.startswith("t "):
                ncol = len(line.lstrip("# ").split())
            continue
        vals = line.split()
        if len(vals) != ncol:
            return rows, partial, f"a row of {len(vals)} fields: {line[:80]!r}"
        rows.append([float(v) for v in vals])
    return rows, partial, None


def previous_kept(check, work, name, what):
    """The previous outputs of the prefix are as they were (issue 32, item 3)."""
    for ext in (".his", ".prf", ".evt", ".frg", ".h5", ".xmf"):
        with open(os.path.join(work, name + ext), "rb") as f:
            check(f.read() == PREVIOUS, f"{what}: the previous {name}{ext} was touched")


def h5_history(path):
    with h5py.File(path, "r") as f:
        return np.asarray(f["history/t"]), np.asarray(f["history/step"]), \
            np.asarray(f["history/e_kin"]), len(f["fields/xt/t"])


def main():
    exe, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()

    # SIGTERM
    p = start(exe, work, "term")
    p.send_signal(signal.SIGTERM)
    err = p.communicate(timeout=60)[1].decode()
    lines = err.splitlines()
    check(p.returncode == 143, f"SIGTERM: exit {p.returncode}, expected 143; {err!r}")
    check(len(lines) == 1 and "stopped by signal 15 at step" in lines[0] and
          "outputs are term.*.part, the previous term.* are as they were" in lines[0],
          f"SIGTERM: message {err!r}")
    previous_kept(check, work, "term", "SIGTERM")
    rows, partial, bad = text_rows(os.path.join(work, "term.his.part"))
    check(bad is None and not partial, f"SIGTERM: history text {bad}, partial {partial}")
    step = int(lines[0].split("at step ")[1].split()[0]) if lines else -1
    check(rows and int(rows[-1][10]) == step, f"SIGTERM: last row step {rows[-1][10]} vs {step}")
    t, st, ek, nxt = h5_history(os.path.join(work, "term.h5.part"))
    check(len(t) == len(rows), f"SIGTERM: {len(t)} HDF5 rows vs {len(rows)} text rows")
    txt = np.array(rows)
    n = min(len(t), len(rows))
    check(np.array_equal(st[:n], txt[:n, 10]), "SIGTERM: HDF5 steps differ from the text")
    check(np.allclose(ek[:n], txt[:n, 4], rtol=1e-12, atol=0), "SIGTERM: e_kin differs")
    check(nxt == step // 100 + 1, f"SIGTERM: {nxt} x-t rows for step {step}")
    for ext in ("evt", "prf", "frg"):
        with open(os.path.join(work, "term." + ext + ".part"), "rb") as f:
            data = f.read()
        check(data.endswith(b"\n"), f"SIGTERM: term.{ext} does not end with a full line")
    print(f"SIGTERM: exit {p.returncode}, stopped at step {step}; {len(rows)} text rows = "
          f"{len(t)} HDF5 rows; {nxt} x-t rows")

    # SIGKILL
    p = start(exe, work, "kill")
    p.send_signal(signal.SIGKILL)
    p.communicate(timeout=60)
    check(p.returncode == -signal.SIGKILL, f"SIGKILL: returncode {p.returncode}")
    previous_kept(check, work, "kill", "SIGKILL")
    rows, partial, bad = text_rows(os.path.join(work, "kill.his.part"))
    check(bad is None, f"SIGKILL: history text {bad}")
    try:
        t, st, ek, nxt = h5_history(os.path.join(work, "kill.h5.part"))
        ok = True
    except Exception as e:               # the check below reports it
        ok, t = False, []
        check(False, f"SIGKILL: kill.h5 does not open: {e}")
    if ok:
        n = min(len(t), len(rows))
        txt = np.array(rows)
        check(len(t) >= 1024, f"SIGKILL: only {len(t)} HDF5 rows")
        check(len(rows) >= len(t), f"SIGKILL: {len(rows)} text rows < {len(t)} HDF5 rows")
        check(n > 0 and np.array_equal(st[:n], txt[:n, 10]), "SIGKILL: steps differ")
        check(n > 0 and np.allclose(ek[:n], txt[:n, 4], rtol=1e-12, atol=0), "SIGKILL: e_kin differs")
        check(np.all(np.diff(t) > 0), "SIGKILL: HDF5 times not increasing")
        print(f"SIGKILL: {len(rows)} complete text rows (partial last line: {partial}), "
              f"{len(t)} HDF5 rows, {nxt} x-t rows, all readable and equal")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
