#!/usr/bin/env python3
"""Restart (issue 8, item 3): a restarted run is bit-identical to an uninterrupted one.

For eleven decks (the paper's Examples 1-3 with a transmitting end and table loads, the
Goupillaud bar, the suspended bar, Example 3 case 2 with the delay rule and with the
full-mass model, a Weibull strength field, Example 2 with &gauges: PREFIX.gau and
/gauges, and with cohesive cracks open at the checkpoint the concrete spall test and the ZMR
bar between constant-velocity ends) with PREFIX.h5, x-t fields and a history stride that does not divide the step
count:

  * extension: a run to about 45 % of t_end writes a checkpoint at its end; the full deck
    restarted from it (--restart, same --output) gives .his .prf .evt .frg identical byte
    for byte (cmp) to the uninterrupted run, and PREFIX.h5 with every dataset and
    attribute equal bit for bit;
  * truncation: outputs that reach past the checkpoint (a complete later run) are cut back
    to it and continued: identical again;
  * SIGTERM: a run stopped by a signal writes its checkpoint; restarted, identical;
  * interrupted restart (issue 19): a --restart killed (SIGKILL) while it sets the outputs
    aside, rebuilds them or removes the set-aside copies is resumed by the next --restart,
    identical again: each crash state made on disk (renames half done, the copy cut,
    PREFIX.h5 cut, the removal half done), then real SIGKILLs at random times in the
    rebuild of a 6 MB history; a fresh run drops PREFIX.*.restart left behind;
  * refusals, each exit status 2 with one line naming what is wrong, the outputs left as
    they were and no PREFIX.*.restart left behind: another deck, another t_end before the
    checkpoint, other earlier profile_times, outputs missing or shorter than the
    checkpoint counts, a file that is no checkpoint or no HDF5, none at all, --restart
    without a file or with --sweep, a checkpoint path that cannot be written,
    checkpoint_every without checkpoint.
  * another program (issue 32): a checkpoint whose /identity program is not this one's is
    refused naming both; --restart-any-version restarts it and every header says so.

usage: cli_restart.py SPALLBAR WORKDIR INPUT_DIR     (needs h5py)
"""
import hashlib
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

from checkpoint_tools import resign
from clitools import Checks, run

EXTS = [".his", ".prf", ".evt", ".frg", ".imp"]
# written once at the end of a run (not set aside by a restart), compared all the same
DIAG_EXTS = [".spl"]

WEIBULL = """&run
  title = 'Weibull strength, restart'
  t_end = 3.0e-4
  history_every = 1
/
&mesh
  cells = 200
/
&segments
  n = 1
  length = 1.0
  young = 200e9
  density = 8000
  strength = 1.0e8
/
&ends
  top = 'free'
  bottom = 'free'
/
&load
  kind = 'power'
  face = 'top'
  p0 = 3.0e8
  t_k = 2.0e-5
  exponent = 1.0
  t_cut = 2.0e-5
/
&strength_field
  kind = 'weibull'
  modulus = 6.0
  scale = 1.0e8
  seed = 7
/
"""



def summary_events(stdout, prefix):
    """The run summary's lines on events and fractures (the prefix taken out)."""
    keep = ("  events:", "  fractures:", "    t = ", "    ... and")
    return [l.replace(prefix, "PREFIX") for l in stdout.splitlines() if l.startswith(keep)]

def set_run(text, **values):
    """Put name = value lines into &run (replacing those given in the deck)."""
    lines = text.splitlines()
    out, in_run = [], False
    for line in lines:
        stripped = line.strip().lower()
        if stripped.startswith("&run"):
            in_run = True
            out.append(line)
            for k, v in values.items():
                out.append(f"  {k} = {v}")
            continue
        if in_run and stripped.startswith("/"):
            in_run = False
        if in_run:
            name = stripped.split("=")[0].strip() if "=" in stripped else ""
            if name in values:
                continue
        out.append(line)
    return "\n".join(out) + "\n"


def run_value(text, name):
    m = re.search(r"^\s*" + name + r"\s*=\s*([^!\n]+)", text, re.M | re.I)
    return m.group(1).strip() if m else None


def short_deck(text, fraction, checkpoint):
    """The deck to fraction * t_end, profile times after it dropped."""
    t_end = float(run_value(text, "t_end"))
    t1 = fraction * t_end
    values = {"t_end": repr(t1), "checkpoint": f"'{checkpoint}'"}
    prof = run_value(text, "profile_times")
    if prof is not None:
        times = [float(x) for x in prof.replace(",", " ").split()]
        kept = [t for t in times if t <= t1]
        values["profile_times"] = ", ".join(repr(t) for t in kept) if kept else "-1.0"
    deck = set_run(text, **values)
    if prof is not None and not [t for t in times if t <= t1]:
        deck = re.sub(r"^\s*profile_times\s*=\s*-1.0\n", "", deck, flags=re.M)
    return deck


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def h5_differences(a_path, b_path):
    """Objects, attributes or dataset bytes that differ between two HDF5 files."""
    diffs = []
    with h5py.File(a_path, "r") as a, h5py.File(b_path, "r") as b:
        na, nb = [], []
        a.visit(na.append)
        b.visit(nb.append)
        if sorted(na) != sorted(nb):
            return [f"objects differ: {sorted(set(na) ^ set(nb))[:5]}"]
        for name in ["/"] + na:
            oa, ob = a[name], b[name]
            if sorted(oa.attrs) != sorted(ob.attrs):
                diffs.append(f"{name}: attribute names")
                continue
            for k in oa.attrs:
                if not np.array_equal(np.asarray(oa.attrs[k]), np.asarray(ob.attrs[k])):
                    diffs.append(f"{name}:{k}")
            if isinstance(oa, h5py.Dataset):
                x, y = oa[()], ob[()]
                if x.shape != y.shape or x.dtype != y.dtype or x.tobytes() != y.tobytes():
                    diffs.append(f"{name}: data")
    return diffs


def same_outputs(check, what, work, u, r, hdf5=True):
    exts = EXTS + [".gau"] if os.path.exists(os.path.join(work, u + ".gau")) else EXTS
    exts = exts + DIAG_EXTS
    for ext in exts:
        a, b = os.path.join(work, u + ext), os.path.join(work, r + ext)
        check(os.path.exists(b) and sha(a) == sha(b), f"{what}: {r}{ext} equals {u}{ext}")
    if hdf5:
        d = h5_differences(os.path.join(work, u + ".h5"), os.path.join(work, r + ".h5"))
        check(not d, f"{what}: {r}.h5 equals {u}.h5 ({d[:3]})")
    left = [f for f in os.listdir(work) if f.endswith(".restart")]
    check(not left, f"{what}: no .restart files left ({left})")

# a bar hanging from a fixed top, thrown onto the base, odd cell count, g = 5000: it lands and
# lifts off 42 times; at 0.45 t_end (step 1408/1409) it rests on the base holding a landing
# credit (doc/method.md, "A landing credit"), which the checkpoint must carry
CREDIT = """&run
  title = 'landing credit, restart'
  t_end = 3.13e-3
  gravity = 5000.0
  energy_guard = 0
/
&mesh
  dt = 1e-6
  fit = 'stretch'
/
&segments
  n = 2
  length = 0.0155, 0.0202
  young = 2e11, 7e10
  density = 7850, 2700
  strength = -1, -1
  velocity = 0.3, -0.2
/
&ends
  top = 'fixed'
  bottom = 'base'
  base_gap = 2e-8
/
"""


def main():
    exe, work, input_dir = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
    check = Checks()
    work = os.path.join(work, "restart")
    shutil.rmtree(work, ignore_errors=True)
    shutil.copytree(input_dir, work)

    decks = {
        "ex1": open(os.path.join(work, "example1.nml")).read(),
        "ex2": open(os.path.join(work, "example2.nml")).read(),
        "goupillaud": open(os.path.join(work, "goupillaud.nml")).read(),
        "suspended": open(os.path.join(work, "suspended_static.nml")).read(),
        "ex3c1": open(os.path.join(work, "example3_case1_delay.nml")).read(),
        "c2delay": open(os.path.join(work, "example3_case2", "delay_fragment_h95.nml")).read(),
        "c2full": open(os.path.join(work, "example3_case2",
                                    "fullmass_accelerate_fragment_h19.nml")).read(),
        "weibull": WEIBULL,
        "credit": CREDIT,
        # cohesive cracks open at the checkpoint (issue 31): the concrete spall test, and the
        # ZMR bar between two constant-velocity ends with a Weibull field
        "cohesive": open(os.path.join(work, "spall_cohesive.nml")).read(),
        "zmr": open(os.path.join(work, "zmr_bar.nml")).read(),
        # gauges on the top face, in a cell, on the interface and on the transmitting bottom,
        # every 4 steps (neither a divisor of the step count nor of history_every)
        # time-dependent fracture (issue 35): sections part damaged at the checkpoint
        "damage": open(os.path.join(work, "example2.nml")).read().replace(
            "  strength = 1.2e6, 0.6e6, 2.5e6\n",
            "  strength = 1.2e6, 0.6e6, 2.5e6\n  damage_integral = 5.0e7, 5.0e7, 5.0e7\n"),
        "gauges": open(os.path.join(work, "example2.nml")).read() +
        "&gauges\n  x = 0.0, 0.1, 0.84, 1.2, 2.89\n  every = 4\n/\n",
    }
    for name, text in decks.items():
        full = set_run(text, hdf5=".true.", field_every="7", history_every="3",
                       checkpoint=f"'{name}_end.ck.h5'", checkpoint_every="400")
        with open(os.path.join(work, name + "_full.nml"), "w") as f:
            f.write(full)
        with open(os.path.join(work, name + "_short.nml"), "w") as f:
            f.write(short_deck(full, 0.45, f"{name}.ck.h5"))
        p = run(exe, [name + "_full.nml", "--output", name + "_U"], work)
        check(p.returncode == 0, f"{name}: uninterrupted run exits 0 ({p.stderr.strip()})")
        told_u = summary_events(p.stdout, name + "_U")
        p = run(exe, [name + "_short.nml", "--output", name + "_R", "-q"], work)
        check(p.returncode == 0, f"{name}: short run exits 0 ({p.stderr.strip()})")
        check(os.path.exists(os.path.join(work, name + ".ck.h5")),
              f"{name}: the short run wrote its checkpoint")
        if name == "credit":
            with h5py.File(os.path.join(work, name + ".ck.h5"), "r") as ck:
                check(abs(ck["state"].attrs["u_credit"]) > 0.0,
                      f"{name}: the checkpoint holds the held bar's credit")
        if name == "damage":
            with h5py.File(os.path.join(work, name + ".ck.h5"), "r") as ck:
                d = ck["state"]["dmg_d"][()]
                check(np.any((d > 0.0) & (d < 1.0)),
                      f"{name}: the checkpoint holds sections part damaged "
                      f"({int(np.sum((d > 0.0) & (d < 1.0)))})")
        if name in ("cohesive", "zmr"):
            with h5py.File(os.path.join(work, name + ".ck.h5"), "r") as ck:
                check(ck["state"].attrs["coh_n_active"] > 0 and
                      float(np.max(ck["state"]["coh_dmax"][()])) > 0.0,
                      f"{name}: the checkpoint holds open cohesive cracks "
                      f"({ck['state'].attrs['coh_n_active']})")
        p = run(exe, [name + "_full.nml", "--output", name + "_R", "--restart", name + ".ck.h5"],
                work)
        check(p.returncode == 0, f"{name}: restart exits 0 ({p.stderr.strip()})")
        check("restart from" in p.stdout, f"{name}: restart says where it starts")
        told_r = summary_events(p.stdout, name + "_R")
        check(told_r == told_u and told_u, f"{name}: the summary's events and first fractures "
              f"after the restart = uninterrupted:\n{told_r}\n{told_u}")
        same_outputs(check, f"{name} extended", work, name + "_U", name + "_R")
        # the checkpoint at t_end is the same whichever way the run got there
        with h5py.File(os.path.join(work, name + "_end.ck.h5"), "r") as ck:
            check(ck.attrs["format"].decode() == "spallbar checkpoint 3" if isinstance(
                ck.attrs["format"], bytes) else ck.attrs["format"] == "spallbar checkpoint 3",
                f"{name}: checkpoint format attribute")
            check("ua" in ck["state"] and "ledger0" in ck["run"].attrs,
                  f"{name}: checkpoint holds /state/ua and /run ledger0")

    # truncation: outputs that run past the checkpoint are cut back to it
    name = "c2delay"
    p = run(exe, [name + "_full.nml", "--output", name + "_T", "-q"], work)
    check(p.returncode == 0, "truncation: complete run")
    p = run(exe, [name + "_full.nml", "--output", name + "_T", "--restart", name + ".ck.h5",
                  "-q"], work)
    check(p.returncode == 0, f"truncation: restart exits 0 ({p.stderr.strip()})")
    same_outputs(check, "truncated and continued", work, name + "_U", name + "_T")

    # SIGTERM: the checkpoint of the step where the run stops, then a restart
    sig_deck = set_run(open(os.path.join(work, "example3_case2", "min_fragment_h190.nml")).read(),
                       hdf5=".true.", field_every="50", history_every="1",
                       checkpoint="'sig.ck.h5'", checkpoint_every="500")
    with open(os.path.join(work, "sig.nml"), "w") as f:
        f.write(sig_deck)
    p = run(exe, ["sig.nml", "--output", "sig_U", "-q"], work)
    check(p.returncode == 0, "signal deck: uninterrupted run")
    os.remove(os.path.join(work, "sig.ck.h5"))
    proc = subprocess.Popen([exe, "sig.nml", "--output", "sig_R", "-q"], cwd=work,
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    while not os.path.exists(os.path.join(work, "sig.ck.h5")) and time.time() < deadline \
            and proc.poll() is None:
        time.sleep(0.005)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=120)
    check(proc.returncode == 143, f"SIGTERM: exit 143, got {proc.returncode} ({err.strip()})")
    check("and the checkpoint" in err, "SIGTERM: the message says the checkpoint is written")
    with h5py.File(os.path.join(work, "sig.ck.h5"), "r") as ck:
        step = int(ck.attrs["step"])
    with h5py.File(os.path.join(work, "sig_U.h5"), "r") as h:
        nsteps = int(h["mesh"].attrs["steps"])
    check(0 < step < nsteps, f"SIGTERM: stopped inside the run (step {step} of {nsteps})")
    p = run(exe, ["sig.nml", "--output", "sig_R", "--restart", "sig.ck.h5", "-q"], work)
    check(p.returncode == 0, f"SIGTERM: restart exits 0 ({p.stderr.strip()})")
    same_outputs(check, "stopped by SIGTERM and restarted", work, "sig_U", "sig_R")

    interrupted_restart(check, exe, work)

    # refusals: exit 2, one line, the outputs untouched
    name = "c2delay"
    full = open(os.path.join(work, name + "_full.nml")).read()

    def refused(what, args, needle, deck_text=None, prefix=name + "_R"):
        if deck_text is not None:
            with open(os.path.join(work, "refused.nml"), "w") as f:
                f.write(deck_text)
        before = {e: sha(os.path.join(work, prefix + e)) for e in EXTS + [".h5"]
                  if os.path.exists(os.path.join(work, prefix + e))}
        p = run(exe, args, work)
        lines = p.stderr.strip().splitlines()
        check(p.returncode == 2, f"{what}: exit 2, got {p.returncode} ({p.stderr.strip()})")
        check(len(lines) == 1 and needle in p.stderr,
              f"{what}: one line containing {needle!r}: {p.stderr.strip()!r}")
        after = {e: sha(os.path.join(work, prefix + e)) for e in EXTS + [".h5"]
                 if os.path.exists(os.path.join(work, prefix + e))}
        check(before == after, f"{what}: outputs unchanged")
        left = [f for f in os.listdir(work) if f.endswith(".restart")]
        check(not left, f"{what}: no .restart files ({left})")

    ck = name + ".ck.h5"
    refused("another deck", ["refused.nml", "--output", name + "_R", "--restart", ck],
            "&load p0", full.replace("p0       = 0.1e6", "p0       = 0.2e6"))
    refused("t_end before the checkpoint", ["refused.nml", "--output", name + "_R", "--restart",
            ck], "after this deck's t_end", set_run(full, t_end="0.1",
                                                    profile_times="0.05, 0.1"))
    refused("earlier profile times changed", ["refused.nml", "--output", name + "_R",
            "--restart", ck], "other profile_times",
            set_run(full, profile_times="0.06, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5"))
    refused("outputs missing", [name + "_full.nml", "--output", "nowhere", "--restart", ck],
            "is missing")
    with open(os.path.join(work, name + "_R.his"), "rb") as f:
        body = f.read()
    shutil.copy(os.path.join(work, name + "_R.prf"), os.path.join(work, "cut_R.prf"))
    shutil.copy(os.path.join(work, name + "_R.evt"), os.path.join(work, "cut_R.evt"))
    shutil.copy(os.path.join(work, name + "_R.frg"), os.path.join(work, "cut_R.frg"))
    shutil.copy(os.path.join(work, name + "_R.h5"), os.path.join(work, "cut_R.h5"))
    with open(os.path.join(work, "cut_R.his"), "wb") as f:
        f.write(body[:20000])
    refused("outputs shorter than the checkpoint", [name + "_full.nml", "--output", "cut_R",
            "--restart", ck], "bytes after its header, the checkpoint counts", prefix="cut_R")
    # a body that differs just before the checkpoint's mark: another run's outputs
    with h5py.File(os.path.join(work, ck), "r") as h:
        body_len = int(h["outputs"].attrs["body.his"])
    columns = open(os.path.join(work, name + "_R.his")).read().split("\n")
    head = next(len("\n".join(columns[:i + 1])) + 1 for i, line in enumerate(columns)
                if line.startswith("# t reaction_bottom"))
    for e in [".prf", ".evt", ".frg", ".h5"]:
        shutil.copy(os.path.join(work, name + "_R" + e), os.path.join(work, "other_R" + e))
    changed = bytearray(body)
    at = head + body_len - 30
    changed[at] = ord("7") if changed[at] != ord("7") else ord("3")
    with open(os.path.join(work, "other_R.his"), "wb") as f:
        f.write(bytes(changed))
    refused("rows differ at the checkpoint", [name + "_full.nml", "--output", "other_R",
            "--restart", ck], "is not the output of the run that wrote the checkpoint",
            prefix="other_R")
    refused("an output file, not a checkpoint", [name + "_full.nml", "--output", name + "_R",
            "--restart", name + "_U.h5"], "is not a spallbar checkpoint")
    refused("not HDF5", [name + "_full.nml", "--output", name + "_R", "--restart",
            name + "_full.nml"], "is not an HDF5 file")
    refused("no such checkpoint", [name + "_full.nml", "--output", name + "_R", "--restart",
            "absent.h5"], "does not exist")
    refused("--restart without a file", [name + "_full.nml", "--restart"], "needs a CHECKPOINT")
    refused("--restart with --sweep", ["--sweep", name + "_full.nml", "--restart", ck],
            "not with --sweep")
    refused("checkpoint path not writable", ["refused.nml", "--output", "unwritten", "-q"],
            "&run: checkpoint = 'no/such/dir/ck.h5'",
            set_run(full, checkpoint="'no/such/dir/ck.h5'"), prefix="unwritten")
    check(not os.path.exists(os.path.join(work, "unwritten.his")),
          "checkpoint path not writable: no outputs written")
    refused("checkpoint_every without checkpoint", ["refused.nml", "-q"],
            "&run: checkpoint_every = 10 needs checkpoint",
            set_run(text_without_checkpoint(full), checkpoint_every="10"), prefix="refused")
    other_program(check, exe, work, name, full, refused)
    return check.finish()


def other_program(check, exe, work, name, full, refused):
    """Issue 32, item 1: a checkpoint another program wrote (here the identity a build of
    other sources writes, 'spallbar 0.1.0' as every build before the identity wrote) is
    refused naming both programs; --restart-any-version accepts it, says so on stderr and in
    every header and PREFIX.h5, and gives this program's continuation."""
    mine = run(exe, ["--version"], work).stdout.splitlines()[0]
    ck = name + ".ck.h5"
    shutil.copy(os.path.join(work, ck), os.path.join(work, "other.ck.h5"))
    with h5py.File(os.path.join(work, "other.ck.h5"), "r+") as h:
        check(h["identity"].attrs["program"].decode() == mine,
              f"identity: the checkpoint names this program ({mine})")
        # fixed-length, as spallbar writes it (h5py's str would be variable-length)
        h["identity"].attrs["program"] = np.bytes_(b"spallbar 0.1.0")
    # the checksum covers the identity (format 3): signed as the other program would have
    resign(os.path.join(work, "other.ck.h5"))
    refused("a checkpoint of another program", [name + "_full.nml", "--output", name + "_R",
            "--restart", "other.ck.h5"],
            f"was written by spallbar 0.1.0, this is {mine}")
    refused("--restart-any-version without --restart", [name + "_full.nml",
            "--restart-any-version"], "--restart-any-version goes with --restart")
    for e in EXTS + [".h5"]:
        shutil.copy(os.path.join(work, name + "_R" + e), os.path.join(work, "any_R" + e))
    p = run(exe, [name + "_full.nml", "--output", "any_R", "--restart", "other.ck.h5",
                  "--restart-any-version", "-q"], work)
    check(p.returncode == 0 and "--restart-any-version" in p.stderr and
          "was written by spallbar 0.1.0" in p.stderr,
          f"--restart-any-version: exit 0 and a note on stderr ({p.returncode}, {p.stderr!r})")
    note = "# restarted (--restart-any-version) from a checkpoint of spallbar 0.1.0"
    for e in EXTS:
        with open(os.path.join(work, "any_R" + e)) as f:
            head = [line for line in f.read().splitlines() if line.startswith("#")]
        check(head and head[0].startswith("# " + mine + " built from ") and note in
              "\n".join(head[:2]), f"--restart-any-version: any_R{e} header names both programs")
        with open(os.path.join(work, "any_R" + e)) as f, \
                open(os.path.join(work, name + "_U" + e)) as g:
            body_a = [line for line in f.read().splitlines() if not line.startswith("#")]
            body_u = [line for line in g.read().splitlines() if not line.startswith("#")]
        check(body_a == body_u, f"--restart-any-version: any_R{e} rows are this program's run")
    with h5py.File(os.path.join(work, "any_R.h5"), "r") as h:
        check(h.attrs["restarted_from"].decode() == "spallbar 0.1.0" and
              h.attrs["program"].decode() == mine,
              "--restart-any-version: PREFIX.h5 names both programs")


BIG = WEIBULL.replace("t_end = 3.0e-4", "t_end = 2.0e-2\n  hdf5 = .true.\n  field_every = 97")


def interrupted_restart(check, exe, work):
    """A --restart killed anywhere in its file handling, then --restart again."""
    full = set_run(BIG, checkpoint="'big_end.ck.h5'")
    with open(os.path.join(work, "big_full.nml"), "w") as f:
        f.write(full)
    with open(os.path.join(work, "big_short.nml"), "w") as f:
        f.write(short_deck(full, 0.45, "big.ck.h5"))
    p = run(exe, ["big_full.nml", "--output", "big_U", "-q"], work)
    check(p.returncode == 0, f"interrupted restart: uninterrupted run ({p.stderr.strip()})")
    p = run(exe, ["big_short.nml", "--output", "big_R", "-q"], work)
    check(p.returncode == 0, f"interrupted restart: short run ({p.stderr.strip()})")
    exts = EXTS + [".h5"]
    pristine = {}
    for e in exts:
        with open(os.path.join(work, "big_R" + e), "rb") as f:
            pristine[e] = f.read()
    restart_args = ["big_full.nml", "--output", "big_R", "--restart", "big.ck.h5", "-q"]

    def path(e, aside=False):
        return os.path.join(work, "big_R" + e + (".restart" if aside else ""))

    def lay_out(files):
        """The previous outputs as a crash left them: {name: bytes}."""
        for f in os.listdir(work):
            if f.startswith("big_R."):
                os.remove(os.path.join(work, f))
        for name, data in files.items():
            with open(os.path.join(work, name), "wb") as f:
                f.write(data)

    def resumed(what):
        left = sorted(f for f in os.listdir(work) if f.startswith("big_R."))
        p = run(exe, restart_args, work)
        check(p.returncode == 0, f"{what} ({left}): the next --restart exits 0, got "
              f"{p.returncode} ({p.stderr.strip()})")
        same_outputs(check, what, work, "big_U", "big_R")

    head = {e: pristine[e][:200] for e in EXTS}   # a fresh header, cut: what a crash leaves
    # 1. killed while renaming: .his and .prf set aside, the others not yet
    lay_out({"big_R.his.restart": pristine[".his"], "big_R.prf.restart": pristine[".prf"],
             "big_R.evt": pristine[".evt"], "big_R.frg": pristine[".frg"],
             "big_R.imp": pristine[".imp"], "big_R.h5": pristine[".h5"]})
    resumed("killed while renaming")
    # 2. killed while copying: every file set aside, .his cut at 3 MB, the others headers
    state = {f"big_R{e}.restart": pristine[e] for e in exts}
    state.update({f"big_R{e}": head[e] for e in EXTS})
    state["big_R.his"] = pristine[".his"][:3 * 1048576]
    lay_out(state)
    resumed("killed while copying .his")
    # 3. killed while PREFIX.h5 was rebuilt: text files rebuilt, PREFIX.h5 cut (no HDF5 file)
    state = {f"big_R{e}.restart": pristine[e] for e in exts}
    for e in EXTS:
        with open(os.path.join(work, "big_U" + e), "rb") as f:
            state[f"big_R{e}"] = f.read()
    state["big_R.h5"] = pristine[".h5"][:4096]
    lay_out(state)
    resumed("killed while PREFIX.h5 was rebuilt")
    # 4. killed while removing the set-aside files: .his.restart and .prf.restart gone
    state = {f"big_R{e}.restart": pristine[e] for e in [".evt", ".frg", ".imp", ".h5"]}
    state.update({f"big_R{e}": pristine[e] for e in exts})
    lay_out(state)
    resumed("killed while removing the set-aside files")
    # 5. real SIGKILLs: once the outputs are set aside, at a random time in the rebuild
    # (how long the outputs stay set aside, measured first: the kills fall inside it)
    def start():
        lay_out({f"big_R{e}": pristine[e] for e in exts})
        proc = subprocess.Popen([exe] + restart_args, cwd=work, stdin=subprocess.DEVNULL,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.time() + 60
        while not os.path.exists(path(".his", True)) and proc.poll() is None \
                and time.time() < deadline:
            time.sleep(0.0005)
        return proc, time.time()

    proc, t0 = start()
    while os.path.exists(path(".his", True)) and proc.poll() is None:
        time.sleep(0.0005)
    window = time.time() - t0
    proc.wait()
    rng = random.Random(19)
    landed = 0
    attempt = 0
    # 4 kills; on a loaded machine the window measured first can be longer than the one a
    # kill meets, so the kills go on, earlier in the window, until one has landed (at most 12)
    while attempt < 4 or (landed == 0 and attempt < 12):
        proc, t0 = start()
        share = rng.uniform(0.1, 0.9) if attempt < 4 else rng.uniform(0.0, 0.2)
        time.sleep(max(0.0, share * window - (time.time() - t0)))
        proc.kill()
        proc.wait()
        left = sorted(f for f in os.listdir(work) if f.endswith(".restart"))
        landed += bool(left)
        attempt += 1
        resumed(f"SIGKILL {attempt}")
    check(landed > 0, f"SIGKILL: at least one kill landed inside the restart ({landed} of {attempt})")
    print(f"interrupted restart: 4 crash states and {landed} of {attempt} SIGKILLs inside the "
          f"restart (outputs set aside for {window:.3f} s) resumed, outputs identical")
    # a fresh run on the prefix drops set-aside files left behind
    lay_out({"big_R.his.restart": b"stale", "big_R.h5.restart": b"stale"})
    p = run(exe, ["big_short.nml", "--output", "big_R", "-q"], work)
    left = [f for f in os.listdir(work) if f.endswith(".restart")]
    check(p.returncode == 0 and not left, f"a fresh run drops PREFIX.*.restart ({left})")


def text_without_checkpoint(text):
    return re.sub(r"^\s*checkpoint\s*=.*\n", "", text, flags=re.M)


if __name__ == "__main__":
    sys.exit(main())
