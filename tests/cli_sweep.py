#!/usr/bin/env python3
"""Sweeps (issue 8): spallbar --sweep on 1 and 2 MPI ranks, static and dynamic, gives the
same PREFIX.sweep to the byte and the same PREFIX_sweep.h5 datasets; the realizations
differ; one realization re-run alone as an ordinary deck (its seed from the table) gives
its row; a run without mpirun does not start MPI (the same table); a case keeps no history rows (its max_excess and ledger_drift from the checks every
64 steps stay round-off) and the energy guard still stops a case (status 3, at the check
that sees it); bad &sweep input exits 2 with one line naming &sweep and writes nothing; a
signal while the cases are checked ends the sweep at once, exit 143, nothing written.

usage: cli_sweep.py SPALLBAR INPUT_DIR WORK_DIR MPIEXEC|-
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

from clitools import Checks, run

exe, indir, work, mpiexec = sys.argv[1:5]
check = Checks()
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
deck = os.path.join(indir, "sweeps", "weibull_spall.nml")
# a smaller copy for speed in the Debug build: 2 values x 6 realizations
small = open(deck).read().replace("values       = 1.6e8, 2.0e8, 3.0e8", "values = 1.6e8, 2.0e8")
small = small.replace("realizations = 32", "realizations = 6")
small_deck = os.path.join(work, "small.nml")
open(small_deck, "w").write(small)


def rows(prefix):
    data = [l.split() for l in open(prefix + ".sweep") if l.startswith(" ")]
    cols = [l for l in open(prefix + ".sweep") if l.startswith("# id ")][0][2:].split()
    return cols, data


def sweep(tag, ranks, extra_deck_text=None):
    d = small_deck
    if extra_deck_text:
        d = os.path.join(work, tag + ".nml")
        open(d, "w").write(small.replace("&sweep", "&sweep\n" + extra_deck_text))
    prefix = os.path.join(work, tag)
    if ranks == 0:
        cmd = [exe, "--sweep", d, "-o", prefix]
    else:
        cmd = [mpiexec, "--oversubscribe", "-np", str(ranks), exe, "--sweep", d, "-o", prefix]
    p = subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=600,
                       stdin=subprocess.DEVNULL)
    check(p.returncode == 0, f"{tag}: exit {p.returncode}: {p.stderr.strip()[:400]}")
    print(f"{tag}: {p.stdout.strip()}")
    said[tag] = p.stdout
    return prefix


said = {}


# -- the same table for any number of ranks and either distribution
ref = sweep("serial", 0)
cols, ref_rows = rows(ref)
check(len(ref_rows) == 12, f"12 cases, got {len(ref_rows)}")
check(cols[:5] == ["id", "fragments", "mean_fragment_length", "max_reaction_bottom",
                   "first_fracture_t"], f"doc/sweeps.md's first columns: {cols[:5]}")
# the experiment diagnostics of each end, last (doc/sweeps.md; -1 where an end has none):
# every case of this spall sweep has a spall plane and a pull-back at the bottom end
spall_cols = ["sigma_novikov_top", "spall_x_top", "scab_thickness_top", "sigma_novikov_bottom",
              "spall_x_bottom", "scab_thickness_bottom"]
check(cols[-6:] == spall_cols, f"the spall columns last: {cols[-6:]}")
bottom = [[float(r[cols.index(n)]) for r in ref_rows] for n in spall_cols[3:]]
check(all(x > 0 for x in np.ravel(bottom)) and all(0 < x < 1 for x in bottom[1]),
      f"a spall plane and sigma_novikov at the bottom of every case: {bottom}")
others = []
if mpiexec != "-":
    others = [sweep("np1", 1), sweep("np2_static", 2),
              sweep("np2_dynamic", 2, "distribution = 'dynamic'"),
              sweep("np3_dynamic", 3, "distribution = 'dynamic'")]
    # a process no launcher started runs alone without starting MPI (its singleton start
    # took 0.3 s of wall clock); under mpirun, even with one rank, MPI runs it
    check("(serial, MPI not started: no launcher)" in said["serial"],
          f"serial: the done line {said['serial']!r}")
    check("(serial, MPI)" in said["np1"], f"np1: the done line {said['np1']!r}")
else:
    print("no mpiexec: MPI runs skipped (serial build)")
ref_text = [l for l in open(ref + ".sweep") if l.startswith(" ")]
for p in others:
    text = [l for l in open(p + ".sweep") if l.startswith(" ")]
    check(text == ref_text, f"{os.path.basename(p)}.sweep rows equal the serial ones")
    with h5py.File(ref + "_sweep.h5") as a, h5py.File(p + "_sweep.h5") as b:
        for name in a["cases"]:
            check(np.array_equal(a["cases"][name][()], b["cases"][name][()]),
                  f"{os.path.basename(p)}_sweep.h5 /cases/{name} equal")
        check(np.array_equal(a["histogram/counts"][()], b["histogram/counts"][()]),
              f"{os.path.basename(p)}_sweep.h5 histograms equal")

# -- an MPI sweep stopped by SIGTERM (doc/sweeps.md, "Stopped by a signal"): to mpirun, which
# forwards it to the ranks 1 s later; to the ranks only. The ranks write the table (cases
# not run: status -1) and exit 143; OpenMPI's mpirun exits 1 when it was signalled itself,
# else with the ranks' 143.
def ranks_of(pid):
    """The processes mpirun started (its children; one node)."""
    kids = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat") as f:
                    if int(f.read().rsplit(")", 1)[1].split()[1]) == pid:
                        kids.append(int(d))
            except (OSError, ValueError, IndexError):
                pass
    return kids


def stopped_sweep(tag, to_ranks):
    d = os.path.join(work, "stop.nml")
    # 900 cases of 100 ms of bar time: far longer than the 2.5 s (+ 1 s of mpirun) before the
    # signal, in the Release build too
    open(d, "w").write(open(deck).read().replace("realizations = 32", "realizations = 300")
                       .replace("t_end = 1.0e-3", "t_end = 1.0e-1"))
    prefix = os.path.join(work, tag)
    proc = subprocess.Popen([mpiexec, "--oversubscribe", "-np", "2", exe, "--sweep", d, "-o",
                             prefix, "-q"], cwd=work, stdin=subprocess.DEVNULL,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(2.5)
    ranks = ranks_of(proc.pid)
    if to_ranks:
        for r in ranks:
            os.kill(r, signal.SIGTERM)
    else:
        proc.send_signal(signal.SIGTERM)
    t0 = time.time()
    _, err = proc.communicate(timeout=120)
    expect = 143 if to_ranks else 1
    check(len(ranks) == 2, f"{tag}: mpirun started 2 ranks ({ranks})")
    check(proc.returncode == expect, f"{tag}: mpirun exits {expect}, got {proc.returncode}: "
          f"{err.strip()[:600]}")
    check("spallbar: sweep: stopped by signal 15 with" in err, f"{tag}: the message: {err!r}")
    _, data = rows(prefix)
    status = [int(r[k["status"]]) for r in data]
    check([int(r[0]) for r in data] == list(range(1, 901)), f"{tag}: 900 rows in case order")
    check(status.count(-1) > 0 and status.count(0) > 0 and set(status) <= {0, 143, -1},
          f"{tag}: cases done (0), cut (143), not run (-1): {sorted(set(status))}")
    with h5py.File(prefix + "_sweep.h5") as h:
        check(np.array_equal(h["cases/status"][()].astype(int), status),
              f"{tag}: {tag}_sweep.h5 holds the same status column")
    print(f"{tag}: mpirun exit {proc.returncode} {time.time() - t0:.1f} s after SIGTERM; "
          f"{status.count(0)} done, {status.count(-1)} not run")


# -- the HDF5 file holds the table
with h5py.File(ref + "_sweep.h5") as h:
    for k, name in enumerate(cols):
        col = np.array([float(r[k]) for r in ref_rows])
        # the text keeps 13 significant digits (ES20.12)
        check(np.allclose(h["cases"][name][()].astype(float), col, rtol=1e-12, atol=0),
              f"h5 /cases/{name} = text")
    counts = h["histogram/counts"][()]
    edges = h["histogram/edges"][()]
    check(counts.shape == (12, 50) and edges.shape == (51,), f"histogram shapes {counts.shape}")
    check(np.array_equal(counts.sum(axis=1), h["cases/fragments"][()]),
          "each case's histogram counts its fragments")
    check(abs(edges[-1] - 1.0) < 1e-12, f"histogram range = bar length 1 m, got {edges[-1]}")

# -- realizations differ; seeds are distinct; each value is the one asked
k = {c: i for i, c in enumerate(cols)}
seeds = [int(r[k["seed"]]) for r in ref_rows]
check(len(set(seeds)) == 6 and seeds[:6] == seeds[6:], "6 distinct seeds, the same for each value")
outcomes = {(r[k["fragments"]], r[k["first_fracture_t"]]) for r in ref_rows[:6]}
check(len(outcomes) > 1, f"realizations give different results: {outcomes}")
check([float(r[k["value"]]) for r in ref_rows] == [1.6e8] * 6 + [2.0e8] * 6, "values in order")
check(all(r[k["status"]] == "0" for r in ref_rows), "every case done")

# -- one realization alone as an ordinary deck gives its row
r = ref_rows[3]
alone = re.sub(r"&sweep.*?/", "", small, flags=re.S).replace(
    "scale   = 1.5e8", f"scale   = 1.5e8\n  seed = {r[k['seed']]}").replace(
    "p0       = 2.0e8", "p0       = 1.6e8")
open(os.path.join(work, "alone.nml"), "w").write(alone)
p = run(exe, ["alone.nml", "-q"], work)
check(p.returncode == 0, f"alone: exit {p.returncode} {p.stderr}")
his = [l.split() for l in open(os.path.join(work, "alone.his")) if l.startswith(" ")]
evt = [l.split() for l in open(os.path.join(work, "alone.evt")) if l.startswith(" ")]
check(his[-1][3] == r[k["fragments"]], f"fragments alone {his[-1][3]} = row {r[k['fragments']]}")
first = [e for e in evt if e[2] == "fracture"]
check(first and float(first[0][0]) == float(r[k["first_fracture_t"]]),
      "first fracture time alone = row")
check(sum(1 for e in evt if e[2] == "fracture") == int(r[k["fractures"]]), "fracture count alone = row")

# -- a case keeps no history rows (doc/sweeps.md, "What a case computes"): its summary's
# running values come from the checks every 64 steps and the end; they stay round-off, and
# the energy guard still stops a case (status 3) at the check that sees it
for r in ref_rows:
    scale = max(abs(float(r[k["w_ext_end"]])), abs(float(r[k["e_kin_end"]])))
    check(0.0 <= float(r[k["max_excess"]]) < 1e-12, f"case {r[0]}: max_excess {r[k['max_excess']]}")
    check(float(r[k["ledger_drift"]]) < 1e-12 * scale,
          f"case {r[0]}: ledger_drift {r[k['ledger_drift']]} of a scale {scale}")
# the case of cli_runtime.py: two one-cell bars meeting under the paper's rules, whose energy
# the wave measure sees grow to 2.25 times the impact's one step after they part (a run
# with rows at every step stops at step 3)
guard_deck = os.path.join(work, "guard.nml")
open(guard_deck, "w").write(
    "&run t_end = 2e-3, events = 'paper' /\n&mesh dt = 1e-5 /\n"
    "&segments n = 2, length = 0.01, 0.01, young = 2e9, 2e9, density = 2000, 2000,\n"
    "          strength = 0, 0, velocity = 1, -1 /\n"
    "&sweep vary = 'velocity(1)', values = 1.0, 2.0, 3.0 /\n")
p = run(exe, ["--sweep", guard_deck, "-o", os.path.join(work, "guard"), "-q"], work)
check(p.returncode == 3 and "3 of 3 cases went wrong" in p.stderr,
      f"the energy guard in a sweep: exit {p.returncode}, expected 3: {p.stderr.strip()[:300]}")
g_cols, g_rows = rows(os.path.join(work, "guard"))
gk = {c: i for i, c in enumerate(g_cols)}
check(len(g_rows) == 3 and all(int(x[gk["status"]]) == 3 for x in g_rows),
      f"every case stopped by the guard: {[x[gk['status']] for x in g_rows]}")
check(all(int(x[gk["steps"]]) == 64 for x in g_rows),
      f"each at the first check, step 64: {[x[gk['steps']] for x in g_rows]}")

# -- bad input: exit 2, one line naming &sweep (and the variable), no file
bad = {  # (what the &sweep group gets instead, the variable the message must name)
    "vary = 'nonsense'": "vary",
    "vary = 'velocity(7)'": "velocity(7)",
    "vary = 'young(1)'\n  values = 2.0e11, -1.0": "values(2)",
    "bins = 0": "bins",
    "distribution = 'random'": "distribution",
    "realizations = -3": "realizations",
    "realizations = 'x'": "realizations",
}
base_sweep = re.search(r"&sweep.*?/", small, flags=re.S).group(0)
for text, var in bad.items():
    name = "bad_" + re.sub(r"\W", "", text)
    d = os.path.join(work, name + ".nml")
    group = base_sweep
    for line in text.split("\n"):
        key = line.split("=")[0].strip()
        group = re.sub(rf"\n\s*{key}\s*=[^\n]*", "", group)
    group = group.replace("&sweep", "&sweep\n  " + text)
    open(d, "w").write(small.replace(base_sweep, group))
    before = set(os.listdir(work))
    p = run(exe, ["--sweep", d], work)
    lines = p.stderr.strip().splitlines()
    check(p.returncode == 2, f"{text}: exit {p.returncode}")
    check(len(lines) == 1 and lines[0].startswith("spallbar: &sweep: ") and var in lines[0],
          f"{text}: one line naming &sweep and {var}: {lines}")
    check(set(os.listdir(work)) - before == set(), f"{text}: no file left")
no_weibull = small.replace("kind    = 'weibull'", "kind    = 'uniform'")
open(os.path.join(work, "bad_uniform.nml"), "w").write(no_weibull)
p = run(exe, ["--sweep", "bad_uniform.nml"], work)
check(p.returncode == 2 and "realizations need &strength_field kind = 'weibull'" in p.stderr,
      f"realizations without a Weibull field: {p.returncode} {p.stderr.strip()}")
p = run(exe, [small_deck], work)
check(p.returncode == 2 and "spallbar --sweep" in p.stderr, f"a sweep deck without --sweep: {p.stderr}")
plain = os.path.join(indir, "example1.nml")
p = run(exe, ["--sweep", plain, "-o", os.path.join(work, "plain")], work)
check(p.returncode == 2 and "&sweep: required group is missing" in p.stderr,
      f"--sweep without &sweep: {p.stderr}")
# the table's temporary is a folder: found before any case runs (issue 19), exit 2, one
# line, nothing created (a table that cannot be written after the cases ran, a full disk,
# is exit 3: cli_faults.py)
os.makedirs(os.path.join(work, "blocked.sweep.part"))
before = set(os.listdir(work))
p = run(exe, ["--sweep", small_deck, "-o", os.path.join(work, "blocked"), "-q"], work)
lines = p.stderr.strip().splitlines()
check(p.returncode == 2 and len(lines) == 1 and "cannot write" in lines[0] and
      "blocked.sweep.part" in lines[0] and "folder" in lines[0],
      f"the table's temporary is a folder: exit {p.returncode} {p.stderr.strip()}")
check(set(os.listdir(work)) - before == set(), "the table's temporary is a folder: files made")
# -- a signal while the cases are checked (a perturbed sweep builds every realization's mesh
# before any runs: 2000 meshes of 2e5 cells, seconds): exit 143 at once, one line, nothing
# written (0.6.3 went on checking, then wrote a table of 2000 cases not run)
sig_dir = os.path.join(work, "signal_checks")
os.makedirs(sig_dir)
open(os.path.join(sig_dir, "p.nml"), "w").write(
    "&run t_end = 1e-6, title = 'perturbed', warnings = .false. /\n&mesh cells = 200000 /\n"
    "&segments n = 1, length = 1.0, young = 2e11, density = 8000, strength = 1e9 /\n"
    "&load kind = 'power', p0 = 1e6, t_k = 1e-4 /\n"
    "&sweep perturb = 'p0', spread = 1.0e-3, realizations = 2000 /\n")
proc = subprocess.Popen([exe, "--sweep", "p.nml", "-q", "-o", "pp"], cwd=sig_dir,
                        stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                        text=True)
time.sleep(1.5)
t0 = time.time()
proc.send_signal(signal.SIGTERM)
_, err = proc.communicate(timeout=600)
waited = time.time() - t0
lines = err.strip().splitlines()
check(proc.returncode == 143 and len(lines) == 1 and "stopped by signal 15 while its cases "
      "were checked" in lines[0] and "nothing written" in lines[0],
      f"a signal while the cases are checked: exit {proc.returncode} {err.strip()[:400]!r}")
check(sorted(os.listdir(sig_dir)) == ["p.nml"],
      f"a signal while the cases are checked: files {sorted(os.listdir(sig_dir))}")
check(waited < 1.0, f"a signal while the cases are checked: exit {waited:.2f} s after it")
print(f"a signal while the cases are checked: exit {proc.returncode} {waited:.2f} s after it; "
      f"{lines[0] if lines else ''}")

if mpiexec != "-":
    stopped_sweep("stop_mpirun", False)
    stopped_sweep("stop_ranks", True)

sys.exit(check.finish())
