#!/usr/bin/env python3
"""Plausibility warnings (issue 21): a value outside the ranges of engineering materials and
loads gets a warning on stderr naming the variable, its value and the likely unit slip; the
run still runs (exit 0); --quiet keeps the warnings; &run warnings = .false. silences them;
the decks of input/ get none, nor the estimate's (issue 32: more than an hour, more than
10 GB), whose warnings name &mesh cells and &run t_end, or the variable of each large output.
The transit count (t_end over 1000 transits: ms meant?) warns a spall deck, not a drop, a
bounce, a striking mass or a dry interface, where long runs are the point (issue 35).

usage: cli_warnings.py SPALLBAR INPUT_DIR WORKDIR
"""
import glob
import os
import shutil
import signal
import subprocess
import sys
import threading

from clitools import Checks, run

BASE = """&run t_end = {t_end} {extra}/
&mesh cells = 10 /
&segments n = 1, length = 0.1, young = {young}, density = {density}, strength = {strength} /
&load kind = 'power', p0 = {p0}, t_k = {t_k} /
"""
GOOD = dict(t_end="2e-4", extra="", young="30e9", density="2400", strength="2e6", p0="1e6", t_k="1e-4")
CASES = [  # (what changes, the words every warning line must hold)
    (dict(density="2.4"), ["&segments: density(1) = 2.4 kg/m^3", "g/cm^3 meant?",
                           "2400 kg/m^3", "wave speed of 111803 m/s"]),
    (dict(young="5e4", density="120", t_end="2e-2"), ["&segments: young(1) = 50000 Pa",
                                                      "50000 MPa = 5e10 Pa meant?"]),
    (dict(p0="20"), ["&load: p0 = 20 Pa", "20 MPa = 2e7 Pa meant?"]),
    (dict(t_k="50"), ["&load: t_k = 50 s", "us meant?", "50 us = 5e-5 s"]),
    (dict(strength="20"), ["&segments: strength(1) = 20 Pa", "20 MPa = 2e7 Pa meant?"]),
]

# issue 35: a 1 m concrete bar for 1 s (3859 transits). Loaded at its top it is a spall test
# whose t_end is ms meant: warned. Dropped onto a base, struck by a mass, parting at a dry
# interface, or under gravity alone, long runs are the point: no transit warning.
DROP = """&run t_end = 1.0 {run} /
&mesh cells = 5 /
&segments n = {n}, length = {length}, young = {n}*35e9, density = {n}*2350 {seg} /
{rest}
"""
SPALL_1S = DROP.format(run="", n=1, length="1.0", seg=", strength = 4e6",
                       rest="&load kind = 'power', p0 = 1e7, t_k = 1e-4 /")
LONG_RUNS = [  # (what, deck) that must run without the transit warning
    ("a drop onto the base", DROP.format(run=", gravity = 9.81", n=1, length="1.0", seg="",
                                         rest="&ends bottom = 'base', base_gap = 0.05 /")),
    ("gravity alone (free fall)", DROP.format(run=", gravity = 9.81", n=1, length="1.0",
                                              seg="", rest="")),
    ("a base without gravity", DROP.format(run="", n=1, length="1.0", seg=", velocity = 1.0",
                                           rest="&ends bottom = 'base', base_gap = 0.01 /")),
    ("a striking mass", DROP.format(run="", n=1, length="1.0", seg="",
                                    rest="&impactor mass = 500, velocity = 2.0 /")),
    ("a dry interface", DROP.format(run="", n=2, length="0.5, 0.5",
                                    seg=", velocity = 1.0, 0.0, interface = 'dry', gap = 0.001",
                                    rest="")),
]


GAUGES = """&run t_end = 0.198 /
&mesh cells = 10000 /
&segments n = 1, length = 1.0, young = 200e9, density = 7850 /
&load kind = 'power', p0 = 1e8, t_k = 1e-6 /
&gauges x = 100*0.50005, every = 1 /
"""


def warnings_then_stop(exe, args, work):
    """The run's warnings (the stderr lines before its first other line or the first 30 s),
    then SIGTERM."""
    p = subprocess.Popen([exe] + args, cwd=work, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True)
    lines = []
    stop = threading.Timer(30.0, p.send_signal, [signal.SIGTERM])
    stop.start()
    line = p.stderr.readline()
    while line.startswith("spallbar: warning: "):
        lines.append(line.rstrip("\n"))
        if "more than 10 GB" in line:
            break
        line = p.stderr.readline()
    stop.cancel()
    p.send_signal(signal.SIGTERM)
    p.communicate()
    return lines


def main():
    exe, indir, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    for change, words in CASES:
        deck = BASE.format(**dict(GOOD, **change))
        with open(os.path.join(work, "w.nml"), "w") as f:
            f.write(deck)
        r = run(exe, ["w.nml", "--quiet"], work)
        text = r.stderr
        check(r.returncode == 0, f"{change}: exit {r.returncode}")
        check(all(l.startswith("spallbar: warning: ") for l in text.splitlines()) and text,
              f"{change}: {text!r}")
        for w in words:
            check(w in text, f"{change}: no {w!r} in {text!r}")
        print(f"ok   {change}: {text.splitlines()[0] if text else ''}")
        with open(os.path.join(work, "w.nml"), "w") as f:
            f.write(BASE.format(**dict(GOOD, **change, extra=", warnings = .false. ")))
        r = run(exe, ["w.nml", "--quiet"], work)
        check(r.returncode == 0 and r.stderr == "", f"{change} with warnings = .false.: "
              f"{r.stderr!r}")
    # young = 30 (GPa meant) makes dt larger than t_end: refused (exit 2), and the one line
    # says why
    with open(os.path.join(work, "w.nml"), "w") as f:
        f.write(BASE.format(**dict(GOOD, young="30")))
    r = run(exe, ["w.nml", "--quiet"], work)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and "shorter than half a step" in lines[0] and
          "young(1) and density(1) give a wave speed of 0.11" in lines[0] and
          "Pa and kg/m^3 meant?" in lines[0], f"young = 30: exit {r.returncode} {r.stderr!r}")
    print(f"ok   young = 30: {lines[0] if lines else ''}")
    # a deck that gives dt: the slip makes the segment lengths no whole number of cells; the
    # one line of the refusal names the wave speed too
    with open(os.path.join(work, "w.nml"), "w") as f:
        f.write(BASE.format(**dict(GOOD, density="2.4")).replace("cells = 10", "dt = 1e-6"))
    r = run(exe, ["w.nml", "--quiet"], work)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and "not a whole number" in lines[0] and
          "give a wave speed of 111803.3" in lines[0] and "Pa and kg/m^3 meant?" in lines[0],
          f"density = 2.4 with dt: exit {r.returncode} {r.stderr!r}")
    print(f"ok   density = 2.4 with dt: {lines[0] if lines else ''}")
    # a Weibull scale in MPa; t_end in ms (10000 transits of the bar)
    for text, words in (
            (BASE.format(**GOOD) + "&strength_field kind = 'weibull', modulus = 6, scale = 150 /\n",
             ["&strength_field: scale = 150 Pa", "150 MPa = 1.5e8 Pa meant?"]),
            (BASE.format(**dict(GOOD, t_end="0.4")),
             ["&run: t_end = 0.4 s is 14142 transits of the bar", "ms meant? (0.4 ms = 0.0004 s)"])):
        with open(os.path.join(work, "w.nml"), "w") as f:
            f.write(text)
        r = run(exe, ["w.nml", "--quiet"], work)
        check(r.returncode == 0 and all(w in r.stderr for w in words) and
              len(r.stderr.splitlines()) == 1, f"{words[0]}: exit {r.returncode} {r.stderr!r}")
        print(f"ok   {r.stderr.strip()}")
    # the bar: the spall deck warns, the decks of long motions do not
    with open(os.path.join(work, "w.nml"), "w") as f:
        f.write(SPALL_1S)
    r = run(exe, ["w.nml", "--quiet"], work)
    words = ["&run: t_end = 1 s is 3859 transits of the bar", "ms meant?"]
    check(r.returncode == 0 and all(w in r.stderr for w in words) and
          len(r.stderr.splitlines()) == 1, f"spall deck over 1 s: exit {r.returncode} {r.stderr!r}")
    print(f"ok   a spall deck over 1 s: {r.stderr.strip()}")
    for what, text in LONG_RUNS:
        with open(os.path.join(work, "w.nml"), "w") as f:
            f.write(text)
        r = run(exe, ["w.nml", "--quiet"], work)
        check(r.returncode == 0 and r.stderr == "", f"{what} over 1 s (3859 transits): exit "
              f"{r.returncode} {r.stderr!r}")
        print(f"ok   {what} over 1 s (3859 transits): exit {r.returncode}, no warning")
    with open(os.path.join(work, "w.nml"), "w") as f:
        f.write(BASE.format(**GOOD))
    r = run(exe, ["w.nml", "--quiet"], work)
    check(r.returncode == 0 and r.stderr == "", f"a plausible deck: {r.stderr!r}")
    print("ok   warnings = .false. silences them; a plausible deck has none")
    # the deck (issue 32, item 8): 100 gauges every step on 1e4 cells to 0.198 s
    # would write about 63 GB of .gau and 8.4 GB of .his; the run is stopped once it warned
    with open(os.path.join(work, "g.nml"), "w") as f:
        f.write(GAUGES)
    lines = warnings_then_stop(exe, ["g.nml", "--quiet"], work)
    volume = [l for l in lines if "more than 10 GB" in l]
    check(len(volume) == 1 and all(w in volume[0] for w in (
        "the outputs would be about 71", ".gau 63.2 GB from &gauges every = 1 with 100 gauges",
        ".his 8.41 GB from &run history_every = 1")), f"gauges every step: {lines}")
    print(f"ok   {volume[0] if volume else lines}")
    decks = sorted(glob.glob(os.path.join(indir, "*.nml")) +
                   glob.glob(os.path.join(indir, "example3_case2", "*.nml")) +
                   glob.glob(os.path.join(indir, "long", "*.nml")))
    for d in decks:
        r = run(exe, [os.path.abspath(d), "--output", os.path.join(work, "in"), "--quiet"], work)
        check(r.returncode == 0 and r.stderr == "", f"{d}: {r.stderr!r}")
    print(f"ok   the {len(decks)} decks of input/: no warning")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
