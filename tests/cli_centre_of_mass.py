"""The centre-of-mass theorem and x_drift (issue 34): M (X_cm(t) - X_cm(0)) equals the sum of
the momentum over the steps times dt, plus what the corrections moved without momentum, which
every correction books in x_drift (doc/outputs.md, doc/method.md "What the corrections move").

Over the seeded random layered bars of tests/cli_event_layer.py (1-3 segments, random
strengths including 0, initial velocities, pulses on either face, free, fixed, base and
transmitting ends, gravity, every timing rule and shift policy), under both event rule sets
and with the full-mass model, each run with a history row every step (PREFIX.h5, full double
precision):

    measured drift_k = X_cm(k) - X_cm(0) - dt sum_{j <= k} momentum_j / M

(X_cm = x_cm, the mass-weighted mean displacement; momentum the bar's over each step) must
equal x_drift_k at every row to round-off: |x_drift - measured| <= 1e-12 of the run's
displacement scale (the largest |X_cm - X_cm(0)|, |dt sum momentum / M| or |x_drift|, at least
1e-9 of the bar's length): the sums over up to 1200 rows of 1e-16 relative errors (measured
worst 7e-14), an order of room. The generator makes no striking mass (with one, the
momentum column holds the mass's momentum too; doc/method.md, "What the corrections move",
gives the bar's). The cases with x_drift = 0 to round-off (a rule that keeps the theorem) and
those with a drift are counted.

usage: cli_centre_of_mass.py SPALLBAR WORKDIR [--count N] [--seed S]
"""
import argparse
import os
import random
import sys

import h5py
import numpy as np

from cli_event_layer import random_deck
from clitools import Checks, run

BOUND = 1e-12


def variant(deck, r):
    """The deck under a random event rule set and model, a history row every step, HDF5."""
    events = r.choice(["admissible", "admissible", "paper"])
    model = r.choice(["half-mass", "half-mass", "half-mass", "full-mass"])
    if events == "paper":                     # 'face' is the admissible rules' own policy
        deck = deck.replace("shift = 'face'", "shift = 'above'")
    return deck.replace("&run ", f"&run events = '{events}', model = '{model}', "
                        "history_every = 1, hdf5 = .true., warnings = .false., ", 1), events, model


def check_run(check, path, name):
    """|x_drift - measured drift| over the rows, relative to the displacement scale."""
    with h5py.File(path, "r") as f:
        h = {k: f["history"][k][()] for k in ("t", "x_cm", "x_drift", "momentum")}
        m_upper = f["mesh/m_upper"][()]
        m_lower = f["mesh/m_lower"][()]
        x = f["mesh/x"][()]
        dt = float(f["mesh"].attrs["dt"])
    mass = float(np.sum(m_upper) + np.sum(m_lower))
    paid = dt * np.cumsum(h["momentum"]) / mass
    paid -= paid[0]
    measured = h["x_cm"] - h["x_cm"][0] - paid
    scale = max(float(np.max(np.abs(h["x_cm"] - h["x_cm"][0]))), float(np.max(np.abs(paid))),
                float(np.max(np.abs(h["x_drift"]))), 1e-9 * float(x[-1] - x[0]))
    dev = float(np.max(np.abs(h["x_drift"] - h["x_drift"][0] - measured))) / scale
    check(dev <= BOUND, f"{name}: |x_drift - measured drift| = {dev:.2e} of the scale "
                        f"> {BOUND:.0e}")
    return dev, float(np.max(np.abs(h["x_drift"]))) / scale


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("work")
    ap.add_argument("--count", type=int, default=120)
    ap.add_argument("--seed", type=int, default=34)
    args = ap.parse_args(argv)
    exe = os.path.abspath(args.exe)
    os.makedirs(args.work, exist_ok=True)
    check = Checks()
    r = random.Random(args.seed)
    worst, ran, drifting, by_rule = 0.0, 0, 0, {}
    for k in range(args.count):
        deck, events, model = variant(random_deck(r), r)
        name = f"com_{k:03d}"
        with open(os.path.join(args.work, name + ".nml"), "w") as f:
            f.write(deck)
        res = run(exe, [name + ".nml", "-q"], args.work)
        if res.returncode == 2:
            continue                      # a combination the deck checks refuse
        check(res.returncode == 0, f"{name}: exit {res.returncode} {res.stderr.strip()}")
        if res.returncode != 0:
            continue
        dev, drift = check_run(check, os.path.join(args.work, name + ".h5"), name)
        ran += 1
        worst = max(worst, dev)
        drifting += drift > 1e-12
        key = f"{events}/{model}"
        by_rule[key] = by_rule.get(key, 0) + 1
    check(ran >= 80, f"only {ran} random decks ran")
    print(f"ok   {ran} random decks ({', '.join(f'{k} {v}' for k, v in sorted(by_rule.items()))}):"
          f" worst |x_drift - measured| {worst:.1e} of the scale (bound {BOUND:.0e}); "
          f"{drifting} with a drift, {ran - drifting} keeping the theorem")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
