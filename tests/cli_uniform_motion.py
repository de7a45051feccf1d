#!/usr/bin/env python3
"""A bar in uniform motion has no stress, so nothing in it may break or part (the fracture
test's round-off guard, doc/method.md "Tolerances, their defaults and why").

Two segments with a dry interface and two with zero strength, every pair of free and
transmitting ends, velocities from 1e-3 to 1e3 m/s of either sign, impedance ratios 1 and 7:
no event in 200 steps, and every stress of the profiles at round-off of Z|v|. A transmitting
end's condition carries Z v, so its section stresses round off at eps Z |v| even where no
stress sets the scale: before the guard took that in, a dry joint moving at 0.3 m/s between
transmitting ends parted at step 3 on a section stress of -2.6e-11 Pa.

usage: cli_uniform_motion.py SPALLBAR WORKDIR
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from clitools import Checks, run_deck, fresh_work      # noqa: E402

DECK = """&run t_end = 2e-3, profile_times = 1e-3, 2e-3, warnings = .false. /
&mesh dt = 1e-5 /
&segments n = 2, length = 0.1, 0.1, young = 2e9, {young2}, density = 2000, {rho2},
  {joint}, velocity = {v}, {v} /
&ends top = '{top}', bottom = '{bottom}' /
"""


def events(path):
    with open(path) as f:
        return [l for l in f if l.startswith(" ") and l.strip()]


def stresses(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith(" ") and line.strip():
                out.append(abs(float(line.split()[3])))
    return out


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    exe = os.path.abspath(argv[0])
    work = fresh_work(argv[1], "uniform_motion")
    check = Checks()
    count, worst = 0, 0.0
    for joint in ("interface = 'dry'", "strength = 0, 0"):
        for young2, rho2 in (("2e9", "2000"), ("14e9", "14000")):
            for top, bottom in (("transmit", "transmit"), ("free", "transmit"),
                                ("transmit", "free"), ("free", "free")):
                for v in (1e-3, 0.3, -0.7, 5.0, -31.0, 1e3):
                    name = f"u{count}"
                    count += 1
                    deck = DECK.format(young2=young2, rho2=rho2, joint=joint, v=repr(v),
                                       top=top, bottom=bottom)
                    if not run_deck(check, exe, work, name, deck):
                        continue
                    ev = events(os.path.join(work, name + ".evt"))
                    check(not ev, f"{name} ({joint}, {top}/{bottom}, v = {v}): "
                          f"{len(ev)} events, the first: {ev[0].split()[:6] if ev else ''}")
                    z = (float(young2) * float(rho2)) ** 0.5
                    s = max(stresses(os.path.join(work, name + ".prf")))
                    worst = max(worst, s / (z * abs(v)))
                    check(s <= 1e-12 * z * abs(v), f"{name}: a stress of {s:.3g} Pa in uniform "
                          f"motion at {v} m/s")
    print(f"uniform motion: {count} decks, largest stress {worst:.2g} of Z|v|")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
