"""A start without Jordan content for every initial state (issue 34, item 4; doc/method.md,
"Static state (2.4)").

Part `item4`: the deck of the issue's item 4 (tests/decks/item4_hammer_on_pile.nml: a steel
hammer at 5 m/s just touching a steel pile at rest on the base, a dry interface, gravity, a
static start). The hammer is in free fall at t = 0 and the pile in its own equilibrium, so:

  * `jordan` (|J|, the alternating sum of the free fragments, relative to the largest
    momentum scale so far: every term of J is one of the sums that scale adds up) is at most
    JORDAN_TOL at row 0 and at every row. J dt / m is the amplitude of the Jordan partner as a
    displacement, so this is also its share of the displacement scale. Round-off of a sum of
    the 500 nodes' terms is ~500 x 1.1e-16 = 6e-14; measured 1.8e-17 (the old start: 9.46e-7);
  * the only event at t^0 is the collision at the interface (physical: the faces approach at
    5 m/s), and the next is the separation when the wave the impact sent down has come back
    from the base and out of the hammer's free top: at 2 (L_hammer + L_pile) / a, to a step;
  * `reaction_bottom` at row 0 is the pile's weight, rho g L_pile (the hammer rests on nothing);
  * e_lost_w and the wave ledger ledger_w stay within LEDGER_TOL of the energy scale (the
    collision at touching faces of fragments without a Jordan component and the separation
    are exact for the wave energy; measured 4.4e-16 and 4e-14; the old start booked 0.194 J/m²,
    3.9e-6 of the scale).

Part `states`: COUNT decks (seeded; as many of each class below) from every initial state the
deck can ask for:
`unstressed` and `static`, gravity 0, 9.81 (down), -9.81 (up, for a base above) and 5000,
every pair of ends (free, fixed, transmit, base, velocity at either end), one to three
segments with dry or bonded interfaces whose sides rest, move together, move differently
or are parted by a gap, equal or differing areas, with and without `&initial strain_rate`.
Decks the program refuses (exit 2: a static start with a gap, two free ends under gravity,
a strain rate against a support, ...) are skipped and counted. For each run (300 steps):

  * `jordan` <= JORDAN_TOL at row 0 and at every row;
  * every event at t^0 is physical: a collision at a dry interface whose upper side moves
    down faster than its lower side, a base-collision of a face moving onto its base; no
    fracture, separation or lift-off in the first step (a contact the static state would
    pull starts open, nothing else pulls at t = 0: the decks have no load). A separation
    at a round-off tension (|S| <= 1e-9 Z |v|) is counted and printed, not failed: a bar in
    uniform motion between two transmitting ends has no stress, so the fracture test's
    guard eps_rel x (largest stress so far) is 0, and a dry joint then parts at the 1e-16
    relative round-off of its motion's stress (-2e-9 Pa), a matter of spb_fracture's guard,
    not of the start;
  * e_lost_w of a run without events within LEDGER_TOL of the energy scale (what the events
    at t^0 book is printed, not checked: a collision at t^0 with a side a fixed or
    constant-velocity end holds books up to 7e-3 of the scale by the collision rules, with or
    without gravity, whatever the start; a gap that closes in the first step is an event of
    the step);
  * the wave ledger ledger_w within LEDGER_TOL of the scale over the run (1e-12: round-off of
    a few hundred steps and events, measured <= 4.8e-13 here; the old start's static decks
    with a dry interface moving onto the other side drifted up to 2e-5).

Every class of start (state, gravity or not, one segment or dry interfaces, how their sides
move, a gap) that the deck allows runs COUNT / (number of classes) decks.

usage: cli_static_start.py SPALLBAR DECKS_DIR WORKDIR [--count N] [--seed S]
"""
import argparse
import itertools
import os
import random
import shutil
import sys

import numpy as np

from cli_event_layer import energy_scale, his
from clitools import Checks, run

JORDAN_TOL = 1.0e-12
LEDGER_TOL = 1.0e-12
ENDS = ["free", "fixed", "transmit", "base", "velocity"]
DT = 1.0e-6
STEPS = 300


def event_rows(path, stress=False):
    """(step, kind, node) of every event row of PREFIX.evt (and its stress [Pa])."""
    return [(int(l.split()[1]), l.split()[2], int(l.split()[3])) +
            ((float(l.split()[5]),) if stress else ())
            for l in open(path) if l.startswith(" ") and l.strip()]


def part_item4(check, exe, decks, work):
    name = "item4_hammer_on_pile"
    shutil.copy(os.path.join(decks, name + ".nml"), work)
    r = run(exe, [name + ".nml", "--quiet"], work)
    check(r.returncode == 0, f"{name}: exit {r.returncode}: {r.stderr.strip()!r}")
    if r.returncode != 0:
        return
    h = his(os.path.join(work, name + ".his"))
    ev = event_rows(os.path.join(work, name + ".evt"))
    rho, g, e, l_hammer, l_pile = 7850.0, 9.81, 210e9, 0.5, 2.0
    a = (e / rho) ** 0.5
    dt = h["t"][1] - h["t"][0]
    scale = energy_scale(h)
    j0, jmax = h["jordan"][0], np.max(h["jordan"])
    check(j0 <= JORDAN_TOL, f"{name}: jordan at row 0 {j0:.2e} > {JORDAN_TOL:.0e}")
    check(jmax <= JORDAN_TOL, f"{name}: largest jordan {jmax:.2e} > {JORDAN_TOL:.0e}")
    n_hammer = 100
    check(len(ev) >= 2 and ev[0] == (0, "collision", n_hammer),
          f"{name}: the first event is not the collision at node {n_hammer} at t0: {ev[:2]}")
    back = round(2.0 * (l_hammer + l_pile) / (a * dt))
    check(len(ev) >= 2 and ev[1][1] == "separation" and abs(ev[1][0] - back) <= 1,
          f"{name}: the second event is not the separation at step {back}: {ev[:2]}")
    weight = rho * g * l_pile
    check(abs(h["reaction_bottom"][0] - weight) <= 1e-12 * weight,
          f"{name}: reaction_bottom at row 0 {h['reaction_bottom'][0]!r}, the pile's weight "
          f"{weight!r}")
    lost = np.max(np.abs(h["e_lost_w"])) / scale
    ledger = np.ptp(h["ledger_w"]) / scale
    check(lost <= LEDGER_TOL, f"{name}: |e_lost_w| up to {lost:.2e} of the scale")
    check(ledger <= LEDGER_TOL, f"{name}: wave ledger drift {ledger:.2e} of the scale")
    print(f"item4: jordan row 0 {j0:.2e}, largest {jmax:.2e}; events {ev[:2]}; "
          f"|e_lost_w| {lost:.2e}, ledger_w drift {ledger:.2e} of the scale {scale:.6g} J/m^2")


def deck(state, g, top, bot, nseg, vel, dry, gap, area, strain_rate):
    """A bar of nseg segments (7, 10, 5 cells of steel, aluminium, concrete)."""
    cells = [7, 10, 5][:nseg]
    young = [2e11, 7e10, 3e10][:nseg]
    rho = [7850.0, 2700.0, 2400.0][:nseg]
    length = [c * (e / d) ** 0.5 * DT for c, e, d in zip(cells, young, rho)]
    j = lambda x: ", ".join(repr(v) for v in x)
    seg = (f"n = {nseg}, length = {j(length)}, young = {j(young)}, density = {j(rho)}, "
           f"velocity = {j(vel)}, area = {j(area)}")
    if nseg > 1:
        seg += f", interface = {', '.join(dry)}, gap = {j(gap)}"
    return (f"&run t_end = {STEPS * DT!r}, gravity = {g!r}, energy_guard = 0, "
            f"warnings = .false. /\n&mesh dt = {DT!r}, fit = 'stretch' /\n&segments {seg} /\n"
            f"&ends top = '{top}', bottom = '{bot}' /\n"
            f"&initial state = '{state}', strain_rate = {strain_rate!r} /\n")


def starts():
    """Every initial state of the product (the deck's parameters and a class name)."""
    for state, g, top, bot, nseg, motion, kind, gap, areas, sr in itertools.product(
            ["unstressed", "static"], [0.0, 9.81, -9.81, 5000.0], ENDS, ENDS, [1, 2, 3],
            ["rest", "onto", "apart", "together"], ["dry", "bonded"], [False, True],
            [False, True], [0.0, 200.0]):
        if nseg == 1 and (kind == "bonded" or gap or motion in ("onto", "apart")):
            continue
        if gap and kind == "bonded":
            continue
        vel = {"rest": [0.0, 0.0, 0.0], "onto": [5.0, 0.0, -2.0], "apart": [-2.0, 0.0, 5.0],
               "together": [1.0, 1.0, 1.0]}[motion][:nseg]
        dry = [f"'{kind}'", "'dry'"][:nseg - 1]
        gaps = [1e-6 if gap else 0.0, 0.0][:nseg - 1]
        area = ([1.0, 2.0, 0.5] if areas else [1.0, 1.0, 1.0])[:nseg]
        cls = (state, g != 0.0, "dry" if nseg > 1 else "one", motion, gap)
        yield cls, deck(state, g, top, bot, nseg, vel, dry, gaps, area, sr), vel, dry, top, bot


def physical_t0(ev, vel, dry, top, bot, n):
    """Whether an event at t^0 is a face moving onto what it strikes."""
    step, kind, node = ev[:3]
    if kind == "base-collision":
        return (node == n and bot == "base" and vel[-1] > 0.0) or \
               (node == 0 and top == "base" and vel[0] < 0.0)
    if kind != "collision":
        return False
    # the node of the interface after segment j: the dry interfaces of the deck (7, 17 cells)
    for j, cells in enumerate([7, 17][:len(dry)]):
        if node == cells and dry[j] == "'dry'" and vel[j] > vel[j + 1]:
            return True
    return False


def part_states(check, exe, work, count, seed):
    r = random.Random(seed)
    by_class = {}
    for start in starts():
        by_class.setdefault(start[0], []).append(start)
    # every class but a static start under gravity with a gap (refused: not an equilibrium)
    classes = sorted((c for c in by_class if not (c[0] == "static" and c[1] and c[4])), key=str)
    per_class = max(1, count // len(classes))
    ran, refused, worst, roundoff = 0, 0, [0.0, 0.0, 0.0, 0.0], 0
    for cls in classes:
        members = by_class[cls]
        r.shuffle(members)
        done = 0
        for k, (_, text, vel, dry, top, bot) in enumerate(members):
            if done == per_class:
                break
            name = f"start_{classes.index(cls):02d}_{k:04d}"
            with open(os.path.join(work, name + ".nml"), "w") as f:
                f.write(text)
            p = run(exe, [name + ".nml", "--quiet"], work)
            if p.returncode == 2:
                refused += 1
                continue
            check(p.returncode == 0, f"{name} {cls}: exit {p.returncode}: {p.stderr.strip()!r}")
            if p.returncode != 0:
                continue
            done += 1
            res = check_start(check, work, name, f"{name} {cls} {top}/{bot}", vel, dry, top, bot)
            worst = [max(w, x) for w, x in zip(worst, res[:4])]
            roundoff += res[4]
        ran += done
        check(done == per_class, f"{cls}: only {done} of {per_class} decks ran")
    print(f"states: {ran} runs ({refused} decks refused), {len(classes)} classes; worst jordan "
          f"at row 0 {worst[0]:.1e}, over the runs {worst[1]:.1e}, e_lost_w after the first "
          f"step {worst[2]:.1e} (not checked), ledger_w drift {worst[3]:.1e}; separations "
          f"at round-off tension in the first step: {roundoff}")


def check_start(check, work, name, what, vel, dry, top, bot):
    """The checks of part `states` on one run: (jordan at row 0, its largest, |e_lost_w|
    after the first step and the wave ledger's drift, relative)."""
    h = his(os.path.join(work, name + ".his"))
    ev = event_rows(os.path.join(work, name + ".evt"), stress=True)
    n = 7 + (10 if len(vel) > 1 else 0) + (5 if len(vel) > 2 else 0)
    scale = energy_scale(h)
    # the stress of the motion, Z |v| (steel's Z is the largest of the three materials)
    s_motion = (2e11 * 7850.0) ** 0.5 * max(abs(v) for v in vel)
    roundoff = 0
    j0, jmax = h["jordan"][0], np.max(h["jordan"])
    lost1 = abs(h["e_lost_w"][1]) / scale
    ledger = np.ptp(h["ledger_w"]) / scale
    check(j0 <= JORDAN_TOL, f"{what}: jordan at row 0 {j0:.2e}")
    check(jmax <= JORDAN_TOL, f"{what}: largest jordan {jmax:.2e}")
    for e in ev:
        if e[0] == 0:
            check(physical_t0(e, vel, dry, top, bot, n), f"{what}: event at t0 {e}")
        elif e[0] == 1 and e[1] in ("fracture", "separation", "lift-off"):
            if e[1] == "separation" and abs(e[3]) <= 1e-9 * s_motion:
                roundoff += 1
                continue
            check(False, f"{what}: {e} in the first step")
    if not ev:
        lost = np.max(np.abs(h["e_lost_w"])) / scale
        check(lost <= LEDGER_TOL, f"{what}: e_lost_w {lost:.2e} of the scale, no event")
    check(ledger <= LEDGER_TOL, f"{what}: wave ledger drift {ledger:.2e} of the scale")
    return j0, jmax, lost1, ledger, roundoff


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    for name in ("exe", "decks", "work"):
        ap.add_argument(name)
    ap.add_argument("--count", type=int, default=400, help="decks of part states")
    ap.add_argument("--seed", type=int, default=34, help="their draw")
    args = ap.parse_args(argv)
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    check = Checks()
    exe = os.path.abspath(args.exe)
    part_item4(check, exe, os.path.abspath(args.decks), args.work)
    part_states(check, exe, args.work, args.count, args.seed)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
