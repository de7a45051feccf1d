#!/usr/bin/env python3
"""Hostile suite over the FILE surface (issue 32), beside fuzz_structural.py (decks).

Seeded cases drawn from five families, each judged against doc/outputs.md ("Before anything
is written; when writing fails", "Checkpoint files") and doc/build.md ("Program identity"):

  outputs   an output, temporary (.part), lock or checkpoint (or its .part) that is the deck
            or its load table: by name, through a symbolic link (relative, absolute, chains)
            or a hard link, spelled with './', 'sub/..' or an absolute path. Expected: exit 2,
            one line, every file of the folder as it was (nothing made, not even a lock).
            Near misses (names that only look alike) are controls: exit 0, the outputs of a
            run alone.
  kept      a complete run, then a rerun on the prefix that fails (the energy guard, exit 3)
            or is stopped (SIGTERM, SIGKILL at a random time), with and without HDF5 and a
            checkpoint. Without a checkpoint: the previous PREFIX.* byte for byte, the run's
            own .part readable. With one: a --restart from the checkpoint gives the outputs
            of the uninterrupted run alone.
  together  two runs started together on the same or other prefixes and checkpoints (a
            checkpoint that is the other's PREFIX.h5, .his, .lock ...): never both exit 0
            when they would write a common file; an exit-0 run's outputs are those of a run
            alone; a refused run exits 2 with one line and makes none of its own outputs.
  readers   a reader holding PREFIX.h5 or PREFIX.his (a shared flock, a plain open handle,
            h5py) during a rerun: exit 0, the reader's bytes unchanged, the new outputs
            those of a run alone.
  identity  a checkpoint whose /identity program is changed (re-signed, or not) is refused
            (exit 2, one line) unless --restart-any-version, which continues it like this
            program; an unchanged identity re-signed continues byte for byte.

Outcomes: ok, and the violations silent-wrong (exit 0 where the doc says otherwise, or
outputs other than a run alone's), crash (a signal or exit >= 128 not from our signal, a
gfortran runtime message), lost (an input or a previous result changed or gone where the
doc keeps it), refused-wrong (exit 2 without exactly one line, or with files left). Counts
per family and per class; each violating case is kept under WORKDIR/violations/ with a
reproduce.sh; exit 1 on any violation.

usage: fuzz_files.py SPALLBAR WORKDIR [--count N] [--seed S] [--jobs J]
"""
import argparse
import concurrent.futures
import fcntl
import hashlib
import os
import random
import shlex
import shutil
import signal
import subprocess
import sys
import time

import h5py

from checkpoint_tools import set_program
from cli_restart import h5_differences
from fuzz_structural import RUNTIME_TEXT

TEXTS = [".his", ".prf", ".evt", ".frg", ".imp"]
TABLE = "0 0\n1e-4 1e6\n2e-4 0\n"
CLASSES = ("ok", "silent-wrong", "crash", "lost", "refused-wrong")


def deck(t_end=2e-4, cells=200, hdf5=False, checkpoint=None, every=0, gauges=False,
         table=None, p0=1e6, guard=False):
    """A small deck (doc/deck.md): two segments, a few hundred cells, a short t_end."""
    if guard:   # two halves flying apart, events 'paper': the energy guard, exit 3
        return ("&run t_end = 2e-3, events = 'paper', history_every = 1, "
                f"hdf5 = {'.true.' if hdf5 else '.false.'} /\n&mesh dt = 1e-5 /\n"
                "&segments n = 2, length = 0.01, 0.01, young = 2e9, 2e9,\n"
                "  density = 2000, 2000, strength = 0, 0, velocity = 1, -1 /\n")
    run = [f"t_end = {t_end!r}", "title = 'files'", f"profile_times = {t_end / 2!r}, {t_end!r}"]
    if hdf5:
        run += ["hdf5 = .true.", "field_every = 20"]
    if checkpoint:
        run += [f"checkpoint = '{checkpoint}'", f"checkpoint_every = {every}"]
    load = (f"kind = 'table', table = '{table}'" if table else
            f"kind = 'power', p0 = {p0!r}, t_k = 1e-4")
    text = (f"&run {', '.join(run)} /\n&mesh cells = {cells} /\n"
            "&segments n = 2, length = 0.1, 0.1, young = 2*1e9, density = 2*1000, "
            "strength = 1e5, -1 /\n"
            f"&load {load} /\n")
    if gauges:
        text += "&gauges x = 0.05, 0.15, every = 5 /\n"
    return text


def outputs_of(prefix, text):
    """The files a run of the deck text writes on prefix (doc/outputs.md)."""
    exts = TEXTS + ([".gau"] if "&gauges" in text else []) + \
        ([".h5", ".xmf"] if "hdf5 = .true." in text else [])
    return [prefix + e for e in exts]


def launch(exe, args, cwd):
    return subprocess.Popen([exe] + args, cwd=cwd, stdin=subprocess.DEVNULL,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            errors="replace")


def spallbar(exe, args, cwd, timeout=300, case=None):
    p = launch(exe, args, cwd)
    out, err = p.communicate(timeout=timeout)
    if case is not None:
        case.heard(p.returncode, err)
    return p.returncode, err


def snapshot(d):
    """Every entry under d: a link's target, a file's digest, a folder."""
    seen = {}
    for root, dirs, files in os.walk(d):
        for n in dirs + files:
            p = os.path.join(root, n)
            rel = os.path.relpath(p, d)
            if os.path.islink(p):
                seen[rel] = "-> " + os.readlink(p)
            elif os.path.isdir(p):
                seen[rel] = "dir"
            else:
                with open(p, "rb") as f:
                    seen[rel] = hashlib.sha256(f.read()).hexdigest()
    return seen


def digests(d, names):
    out = {}
    for n in names:
        p = os.path.join(d, n)
        if os.path.exists(p):
            with open(p, "rb") as f:
                out[n] = hashlib.sha256(f.read()).hexdigest()
    return out


def crashed(rc, err, sent=None):
    """A signal or exit >= 128 we did not cause, or gfortran's runtime text."""
    if any(t in err for t in RUNTIME_TEXT):
        return True
    if sent is not None and rc in (-sent, 128 + sent):
        return False
    return rc < 0 or rc >= 128 or rc not in (0, 2, 3)


class Refs:
    """Runs alone (one folder per deck, prefix and extra arguments), made once."""

    def __init__(self, exe, work):
        self.exe, self.work, self.made = exe, os.path.join(work, "alone"), {}
        import threading
        self.lock = threading.Lock()

    def get(self, text, prefix, deck_arg="deck.nml", table=None):
        """The folder of a run alone of text, given as deck_arg (the header names it) on
        prefix; a relative deck_arg is written there, an absolute one only read."""
        key = hashlib.sha256(repr((text, prefix, deck_arg, table)).encode()).hexdigest()[:16]
        with self.lock:
            if key in self.made:
                return self.made[key]
            d = os.path.join(self.work, key)
            os.makedirs(os.path.join(d, "sub"), exist_ok=True)
            if not os.path.isabs(deck_arg):
                with open(os.path.join(d, deck_arg), "w") as f:
                    f.write(text)
            if table:
                with open(os.path.join(d, table), "w") as f:
                    f.write(TABLE)
            rc, err = spallbar(self.exe, [deck_arg, "--quiet", "--output", prefix], d)
            if rc != 0:
                raise RuntimeError(f"a run alone failed: exit {rc} {err!r} in {d}")
            self.made[key] = d
            return d


def differences(ref, rprefix, d, prefix, text, note_ok=False):
    """Outputs of prefix in d that differ from rprefix's in ref (text byte for byte; with
    note_ok, the '#' lines of a --restart-any-version header are left out; .h5 by content)."""
    bad = []
    for name in outputs_of("", text):
        a, b = os.path.join(ref, rprefix + name), os.path.join(d, prefix + name)
        if not os.path.exists(b):
            bad.append(f"{prefix}{name} missing")
        elif name == ".h5":
            diff = h5_differences(a, b)
            if diff and not (note_ok and all(x.startswith(("/:", "/identity")) for x in diff)):
                bad.append(f"{prefix}.h5: {diff[:3]}")
        else:
            ta, tb = open(a, "rb").read(), open(b, "rb").read()
            if note_ok:
                ta = b"\n".join(x for x in ta.split(b"\n") if not x.startswith(b"#"))
                tb = b"\n".join(x for x in tb.split(b"\n") if not x.startswith(b"#"))
            if ta != tb:
                bad.append(f"{prefix}{name} differs from a run alone")
    return bad


def first_run(exe, d, case, decks, deck_name):
    """Write decks (name: text) into d and run deck_name on the prefix 'run'; a failure
    (the case's verdict set) returns False."""
    for name, text in decks.items():
        with open(os.path.join(d, name), "w") as f:
            f.write(text)
    args = [deck_name, "--quiet", "--output", "run"]
    case.note(args)
    rc, err = spallbar(exe, args, d, case=case)
    if rc != 0:
        case.fail("crash" if crashed(rc, err) else "refused-wrong",
                  f"the first run: exit {rc} {err!r}")
    return rc == 0


class Case:
    def __init__(self, family, label):
        self.family, self.label = family, label
        self.cmds = []          # what was run, for reproduce.sh
        self.verdict, self.why = "ok", ""

    def fail(self, cls, why):
        if self.verdict == "ok":
            self.verdict, self.why = cls, why

    def note(self, args):
        self.cmds.append(" ".join(shlex.quote(a) for a in args))

    def heard(self, rc, err):
        """What the last noted command answered (kept with a violation)."""
        self.cmds[-1] += "\n#   exit " + str(rc) + "".join("\n#   " + x for x in
                                                        err.strip().splitlines())


# ---------------------------------------------------------------- family: outputs over inputs

def spell(rng, name, d):
    """name (a file in d) as './name', 'sub/../name', an absolute path or itself."""
    return rng.choice([name, "./" + name, "sub/../" + name, os.path.join(d, name)])


def link_to(rng, d, target, at):
    """Make at (relative to d) a symbolic link to target, maybe through a chain of links,
    relative or absolute."""
    hops = rng.randint(1, 3)
    dest = target
    for k in range(hops - 1):
        mid = os.path.join("sub", f"hop{k}_{rng.randrange(1000)}")
        src = os.path.join(d, dest) if rng.random() < 0.5 else os.path.relpath(
            os.path.join(d, dest), os.path.dirname(os.path.join(d, mid)))
        os.symlink(src, os.path.join(d, mid))
        dest = mid
    src = os.path.join(d, dest) if rng.random() < 0.5 else os.path.relpath(
        os.path.join(d, dest), os.path.dirname(os.path.join(d, at)))
    os.symlink(src, os.path.join(d, at))


def case_outputs(rng, exe, d, refs, case):
    os.makedirs(os.path.join(d, "sub"))
    hdf5, gauges = rng.random() < 0.4, rng.random() < 0.3
    use_table = rng.random() < 0.5
    use_ck = rng.random() < 0.4
    prefix = rng.choice(["run", "x", "out.d", "a.b"])
    ck = rng.choice(["ck.h5", "run.ck.h5", "sub/c.h5"]) if use_ck else None
    victim = "table" if use_table and rng.random() < 0.5 else "deck"
    written = outputs_of(prefix, deck(hdf5=hdf5, gauges=gauges))
    # the files the run writes: outputs, their .part, the lock; the checkpoint and its .part
    targets = written + [w + ".part" for w in written] + [prefix + ".lock"]
    if ck:
        targets += [ck, ck + ".part"]
    how = rng.choice(["name", "name", "symlink", "hardlink", "near"])
    target = rng.choice(targets)
    deck_name, table_name = "deck.nml", "load.txt" if use_table else None
    collide = how != "near"
    if how == "near":   # a control: only alike
        base = target[4:] if target.startswith("sub/") else target
        target = rng.choice([base + "x", "x" + base, base.upper(), base + "~",
                             base.replace(".", "_", 1)])
    if how in ("name", "near"):
        if victim == "deck":
            deck_name = target
        else:
            table_name = target
    ck_text = ck
    if ck and rng.random() < 0.3:
        ck_text = rng.choice(["./" + ck, "sub/../" + ck, "sub/./../" + ck])
    text = deck(hdf5=hdf5, gauges=gauges, checkpoint=ck_text, every=10,
                table=spell(rng, table_name, d) if table_name else None)
    with open(os.path.join(d, deck_name), "w") as f:
        f.write(text)
    if table_name:
        with open(os.path.join(d, table_name), "w") as f:
            f.write(TABLE)
    source = deck_name if victim == "deck" else table_name
    if how == "symlink":
        link_to(rng, d, source, target)
    elif how == "hardlink":
        os.link(os.path.join(d, source), os.path.join(d, target))
    args = [spell(rng, deck_name, d), "--quiet", "--output", spell(rng, prefix, d)]
    case.label = f"{how} {victim}={source!r} as {target!r} (hdf5 {hdf5}, ck {ck_text!r})"
    before = snapshot(d)
    case.note(args)
    p = launch(exe, args, d)
    _, err = p.communicate(timeout=300)
    rc, lines = p.returncode, err.strip().splitlines()
    case.heard(rc, err)
    after = snapshot(d)
    if crashed(rc, err):
        return case.fail("crash", f"exit {rc}: {err.strip()[-300:]}")
    changed = [k for k in before if after.get(k) != before[k]]
    if changed:
        return case.fail("lost", f"exit {rc}; inputs changed or gone: {changed[:4]}")
    if collide:
        if rc == 0:
            return case.fail("silent-wrong", "exit 0: an output over an input ran")
        if rc != 2 or len(lines) != 1:
            return case.fail("refused-wrong", f"exit {rc}, {len(lines)} lines: {err!r}")
        made = sorted(set(after) - set(before))
        if made:
            return case.fail("refused-wrong", f"exit 2 but made {made[:5]}")
        return None
    if rc != 0:
        return case.fail("refused-wrong", f"a near miss refused: exit {rc} {err.strip()!r}")
    base = os.path.basename(prefix)
    ref = refs.get(text, base, args[0], table_name)
    bad = differences(ref, base, d, base, text)
    if bad:
        case.fail("silent-wrong", "; ".join(bad[:3]))
    return None


# ------------------------------------------------------------- family: previous results kept

def case_kept(rng, exe, d, refs, case):
    hdf5 = rng.random() < 0.5
    with_ck = rng.random() < 0.4
    how = rng.choice(["guard", "SIGTERM", "SIGKILL"]) if not with_ck else \
        rng.choice(["SIGTERM", "SIGKILL"])
    prefix = "run"
    first = deck(hdf5=hdf5, p0=2e6)
    ck = "run.ck.h5" if with_ck else None
    cells = rng.choice([200, 300])
    full = deck(t_end=6e-4, cells=cells, hdf5=hdf5, checkpoint=ck, every=rng.choice([20, 50]))
    second = deck(hdf5=hdf5, guard=True) if how == "guard" else full
    case.label = f"{how}, hdf5 {hdf5}, checkpoint {ck}"
    if not first_run(exe, d, case, {"first.nml": first, "second.nml": second}, "first.nml"):
        return None
    names = outputs_of(prefix, first)
    kept = digests(d, names)
    args = ["second.nml", "--quiet", "--output", prefix]
    case.note(args)
    p = launch(exe, args, d)
    sent = None
    if how != "guard":
        wait = rng.uniform(0.0, 1.0)
        case.label += f", after {wait:.2f} s"
        try:
            p.wait(timeout=wait)
        except subprocess.TimeoutExpired:
            sent = signal.SIGTERM if how == "SIGTERM" else signal.SIGKILL
            p.send_signal(sent)
    _, err = p.communicate(timeout=300)
    rc = p.returncode
    case.heard(rc, err)
    if crashed(rc, err, sent):
        return case.fail("crash", f"second run: exit {rc}: {err.strip()[-300:]}")
    if rc == 0:   # it ended before the signal: the run alone
        bad = differences(refs.get(second, prefix, "second.nml"), prefix, d, prefix, second)
        return case.fail("silent-wrong", "; ".join(bad[:3])) if bad else None
    if how == "guard" and rc != 3:
        return case.fail("silent-wrong", f"the energy-guard deck: exit {rc} {err!r}")
    # (rc -15: the signal came before the program had set its handler, as at its start)
    if rc == 3 or rc == 128 + signal.SIGTERM:
        lines = err.strip().splitlines()
        if not lines or "this run's outputs are" not in err and "checkpoint" not in err:
            return case.fail("silent-wrong", f"exit {rc}: the message does not name the "
                                             f".part files: {err!r}")
    ck_there = ck and os.path.exists(os.path.join(d, ck))
    if not ck_there:
        now = digests(d, names)
        changed = [n for n in names if now.get(n) != kept.get(n)]
        # killed while it renamed its finished outputs (doc/outputs.md: each PREFIX.ext is
        # whole, the previous run's or this one's): a changed file must be the new run's
        alone = digests(refs.get(second, prefix, "second.nml"), names) if changed else {}
        wrong = [n for n in changed if n.endswith((".his", ".prf", ".evt", ".frg", ".imp", ".gau")) and
                 now.get(n) != alone.get(n)]
        if changed and (rc == 3 or wrong):
            return case.fail("lost", f"exit {rc}: previous outputs changed {changed}, "
                                     f"not to the new run's: {wrong}")
        his = os.path.join(d, prefix + ".his.part")
        if os.path.exists(his):
            try:
                lines = open(his).read().splitlines()
                rows = [x for x in lines if x.startswith(" ") and x.strip()]
                if sent == signal.SIGKILL:
                    rows = rows[:-1]   # its last line may be cut
                [float(v) for x in rows for v in x.split()]
                if not lines or lines[0].startswith("#"):
                    raise ValueError("no column line")
            except (ValueError, UnicodeDecodeError) as e:
                return case.fail("lost", f"run.his.part unreadable: {e}")
        return None
    # a checkpoint: the outputs at their names continue it; a restart ends the run alone's
    args = ["second.nml", "--quiet", "--output", prefix, "--restart", ck]
    case.note(args)
    rc2, err2 = spallbar(exe, args, d, case=case)
    if crashed(rc2, err2):
        return case.fail("crash", f"restart: exit {rc2}: {err2.strip()[-300:]}")
    if rc2 != 0:
        return case.fail("lost", f"restart from the checkpoint of a stopped run: exit {rc2} "
                                 f"{err2.strip()!r}")
    bad = differences(refs.get(second, prefix, "second.nml"), prefix, d, prefix, second)
    if bad:
        case.fail("silent-wrong", "restart: " + "; ".join(bad[:3]))
    return None


# ------------------------------------------------------------------ family: two runs together

def case_together(rng, exe, d, refs, case):
    hdf5 = [rng.random() < 0.6, rng.random() < 0.6]
    prefixes = ["a", rng.choice(["a", "b", "b"])]
    cks = []
    for k in range(2):
        other = prefixes[1 - k]
        cks.append(rng.choice([None, None, f"ck{k}.h5", "ck.h5", other + ".h5",
                               other + ".his", other + ".h5.part", other + ".lock",
                               other + ".xmf"]))
    texts = [deck(t_end=5e-4, cells=rng.choice([200, 300]), hdf5=hdf5[k], checkpoint=cks[k],
                  every=40) for k in range(2)]
    writes = []
    for k in range(2):
        outs = outputs_of(prefixes[k], texts[k])
        w = set(outs + [o + ".part" for o in outs] + [prefixes[k] + ".lock"])
        if cks[k]:
            w |= {cks[k], cks[k] + ".part", cks[k] + ".lock"}
        writes.append(w)
    common = writes[0] & writes[1]
    for k in range(2):
        with open(os.path.join(d, f"d{k}.nml"), "w") as f:
            f.write(texts[k])
    delay = rng.choice([0.0, 0.0, rng.uniform(0, 0.3)])
    case.label = (f"prefixes {prefixes}, checkpoints {cks}, hdf5 {hdf5}, second after "
                  f"{delay:.2f} s, common {sorted(common)[:3]}")
    args = [[f"d{k}.nml", "--quiet", "--output", prefixes[k]] for k in range(2)]
    before = snapshot(d)
    procs = []
    for k in range(2):
        case.note(args[k] + ["&"])
        procs.append(launch(exe, args[k], d))
        if k == 0 and delay:
            time.sleep(delay)
    res = []
    for k, p in enumerate(procs):
        _, err = p.communicate(timeout=300)
        res.append((p.returncode, err))
        case.cmds[k] += f"\n#   exit {p.returncode}" + "".join("\n#   " + x for x in
                                                               err.strip().splitlines())
    for k, (rc, err) in enumerate(res):
        if crashed(rc, err):
            return case.fail("crash", f"run {k}: exit {rc}: {err.strip()[-300:]}")
    both = res[0][0] == 0 and res[1][0] == 0 and common
    if both and any(c and c.endswith(".lock") for c in cks):
        # a checkpoint renamed over a lock file (doc/outputs.md: refused, whatever runs)
        return case.fail("silent-wrong", f"both exit 0 though a checkpoint is a lock file: "
                                         f"{sorted(common)}")
    if both:   # one may have ended before the other began: judged by the outputs
        case.label += " [both exit 0: one after the other?]"
    for k, (rc, err) in enumerate(res):
        if rc == 0:
            if both and set(outputs_of(prefixes[k], texts[k])) & writes[1 - k]:
                continue   # the other run's, written after this one's
            bad = differences(refs.get(texts[k], prefixes[k], f"d{k}.nml"), prefixes[k], d, prefixes[k],
                              texts[k])
            if bad:
                return case.fail("silent-wrong", f"run {k}: " + "; ".join(bad[:3]))
        elif rc == 2:
            lines = err.strip().splitlines()
            if len(lines) != 1:
                return case.fail("refused-wrong", f"run {k}: exit 2, {len(lines)} lines {err!r}")
            other = writes[1 - k] if res[1 - k][0] != 2 else set()
            mine = {n for n in writes[k] - other if not n.endswith(".lock")}
            made = sorted(n for n in mine if n not in before and os.path.lexists(
                os.path.join(d, n)))
            if made:
                return case.fail("refused-wrong", f"run {k}: exit 2 but made {made}")
            if not common and res[1 - k][0] != 2:
                case.label += f" [refused without a common file: {lines[0]}]"
        else:   # the other run cost this one its outputs
            return case.fail("lost", f"run {k}: exit {rc} {err.strip()!r}")
    return None


# ------------------------------------------------------------------------ family: readers

def case_readers(rng, exe, d, refs, case):
    what = rng.choice([".h5", ".h5", ".his", ".xmf", ".evt"])
    how = rng.choice(["flock", "open", "h5py"] if what == ".h5" else ["flock", "open"])
    first, second = deck(hdf5=True, p0=2e6), deck(hdf5=True, gauges=rng.random() < 0.3,
                                                  p0=rng.choice([1e6, 3e6]))
    case.label = f"{how} on run{what}"
    if not first_run(exe, d, case, {"first.nml": first, "second.nml": second}, "first.nml"):
        return None
    path = os.path.join(d, "run" + what)
    held = open(path, "rb")
    h5 = None
    try:
        before = held.read()
        if how == "flock":
            fcntl.flock(held, fcntl.LOCK_SH)
        elif how == "h5py":
            h5 = h5py.File(path, "r")
            keys = sorted(h5.keys())
        args = ["second.nml", "--quiet", "--output", "run"]
        case.note(args)
        rc, err = spallbar(exe, args, d, case=case)
        held.seek(0)
        again = held.read()
        if h5 is not None and sorted(h5.keys()) != keys:
            case.fail("lost", "what h5py reads changed under it")
    finally:
        if h5 is not None:
            h5.close()
        held.close()
    if crashed(rc, err):
        return case.fail("crash", f"rerun: exit {rc}: {err.strip()[-300:]}")
    if rc != 0 or err.strip():
        return case.fail("silent-wrong", f"a reader held run{what}: exit {rc} {err.strip()!r}")
    if again != before:
        return case.fail("lost", f"the reader's run{what} changed under it")
    bad = differences(refs.get(second, "run", "second.nml"), "run", d, "run", second)
    if bad:
        case.fail("silent-wrong", "; ".join(bad[:3]))
    left = sorted(f for f in os.listdir(d) if f.endswith(".part"))
    if left:
        case.fail("silent-wrong", f"exit 0 left temporaries {left}")
    return None


# ----------------------------------------------------------------------- family: identity

def case_identity(rng, exe, d, refs, case):
    hdf5 = rng.random() < 0.5
    text = deck(t_end=3e-4, cells=200, hdf5=hdf5, checkpoint="run.ck.h5",
                every=rng.choice([15, 30]))
    if not first_run(exe, d, case, {"deck.nml": text}, "deck.nml"):
        return None
    mine = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout \
        .splitlines()[0]
    change = rng.choice(["other", "other", "same", "unsigned"])
    other = mine
    if change != "same":
        other = rng.choice(["spallbar 0.1.0", mine[:-1] + chr(ord(mine[-1]) ^ 1),
                            mine.replace("spallbar", "spallbaz"), "x" * rng.randint(1, 80),
                            mine + " (patched)"])
    shutil.copy(os.path.join(d, "run.ck.h5"), os.path.join(d, "in.ck.h5"))
    # one handle for the change and the new checksum: a second open of a file whose objects
    # h5py has not let go of yet fails on HDF5's own lock (errno 11)
    set_program(os.path.join(d, "in.ck.h5"), other, sign=change != "unsigned")
    anyv = rng.random() < 0.5
    case.label = f"{change} identity {other!r}, --restart-any-version {anyv}, hdf5 {hdf5}"
    args = ["deck.nml", "--quiet", "--output", "run", "--restart", "in.ck.h5"] + \
        (["--restart-any-version"] if anyv else [])
    case.note(args)
    keep = digests(d, outputs_of("run", text))
    rc, err = spallbar(exe, args, d, case=case)
    lines = err.strip().splitlines()
    if crashed(rc, err):
        return case.fail("crash", f"restart: exit {rc}: {err.strip()[-300:]}")
    refuse = change == "unsigned" or (change == "other" and not anyv)
    if refuse:
        if rc == 0:
            return case.fail("silent-wrong", f"a checkpoint of {other!r} restarted: {err!r}")
        if rc != 2 or len(lines) != 1:
            return case.fail("refused-wrong", f"exit {rc}, {len(lines)} lines {err!r}")
        if digests(d, outputs_of("run", text)) != keep:
            return case.fail("lost", "a refused restart changed the outputs")
        return None
    if rc != 0:
        return case.fail("refused-wrong" if rc == 2 else "silent-wrong",
                         f"restart: exit {rc} {err.strip()!r}")
    noted = change == "other"
    if noted and "--restart-any-version" not in err:
        case.fail("silent-wrong", f"--restart-any-version not said on stderr: {err!r}")
    bad = differences(refs.get(text, "run", "deck.nml"), "run", d, "run", text, note_ok=noted)
    if bad:
        case.fail("silent-wrong", "; ".join(bad[:3]))
    return None


FAMILIES = {"outputs": (case_outputs, 4), "kept": (case_kept, 2),
            "together": (case_together, 2), "readers": (case_readers, 1),
            "identity": (case_identity, 1)}


def run_case(exe, work, refs, k, family, seed):
    rng = random.Random(seed)
    case = Case(family, family)
    d = os.path.join(work, "cases", f"case{k:05d}")
    os.makedirs(d)
    t0 = time.monotonic()
    try:
        FAMILIES[family][0](rng, exe, d, refs, case)
    except subprocess.TimeoutExpired as e:
        case.fail("crash", f"a hang: {e}")
    case.seconds = time.monotonic() - t0
    if case.verdict != "ok":
        keep = os.path.join(work, "violations", f"case{k:05d}")
        shutil.copytree(d, keep, symlinks=True)
        with open(os.path.join(keep, "reproduce.sh"), "w") as f:
            f.write(f"# {family}: {case.label}\n# {case.verdict}: {case.why}\n"
                    f"# the folder as the case left it; its commands (in order, from a fresh "
                    f"copy: tests/fuzz_files.py --seed S --only {k}):\n")
            f.write("".join(f"{shlex.quote(exe)} {c}\n" for c in case.cmds))
    shutil.rmtree(d, ignore_errors=True)
    return case


def main():
    p = argparse.ArgumentParser(description="hostile cases over the file surface")
    p.add_argument("exe", help="the spallbar program")
    p.add_argument("work", help="a folder (emptied); violations are kept in it")
    for opt, default, what in (("--count", 40, "cases"), ("--seed", 32, "the seed"),
                               ("--jobs", 2, "cases at once"),
                               ("--only", None, "run case K alone (a violation's)")):
        p.add_argument(opt, type=int, default=default, help=what)
    p.add_argument("--verbose", action="store_true", help="one line per case")
    args = p.parse_args()
    exe = os.path.abspath(args.exe)
    if os.path.exists(args.work):
        shutil.rmtree(args.work)
    os.makedirs(args.work)
    rng = random.Random(args.seed)
    names = list(FAMILIES)
    weights = [FAMILIES[n][1] for n in names]
    # every family at least once, then by weight
    plan = names[:min(len(names), args.count)] + rng.choices(
        names, weights, k=max(0, args.count - len(names)))
    seeds = [rng.randrange(2 ** 31) for _ in plan]
    todo = range(len(plan)) if args.only is None else [args.only]
    refs = Refs(exe, args.work)
    t0 = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        cases = list(pool.map(lambda k: (k, run_case(exe, args.work, refs, k, plan[k],
                                                     seeds[k])), todo))
    tally = {f: dict.fromkeys(CLASSES, 0) for f in names}
    bad = 0
    for k, case in cases:
        tally[case.family][case.verdict] += 1
        if args.verbose:
            print(f"case {k} {case.family} {case.verdict} {case.seconds:.1f} s: {case.label}")
        if case.verdict != "ok":
            bad += 1
            print(f"VIOLATION case {k} ({case.family}, {case.verdict}): {case.label}\n"
                  f"    {case.why}\n    kept in {os.path.join(args.work, 'violations')}/"
                  f"case{k:05d}")
        elif "refused without a common file" in case.label:
            print(f"note case {k}: {case.label}")
    print(f"fuzz_files: outcomes by family (seed {args.seed}):")
    for f in names:
        print(f"  {f:10s} " + ", ".join(f"{c} {n}" for c, n in tally[f].items()))
    total = {c: sum(tally[f][c] for f in names) for c in CLASSES}
    print(f"fuzz_files: {len(cases)} cases in {time.monotonic() - t0:.0f} s: " +
          ", ".join(f"{c} {n}" for c, n in total.items()))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
