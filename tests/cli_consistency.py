#!/usr/bin/env python3
"""The event corrections under refinement and their causality (issue 34; doc/method.md, "What
the corrections move" and "The 'face' correction").

1. Orders. The decks of bench/consistency.py for one fixed physical sequence of events: a bar
   dropped onto the base (one landing, one lift-off) and two bars meeting head-on (one
   collision, one separation), each at four offsets of the event within its step (means over
   them) on dt, dt/2, dt/4, dt/8. At t_end:
   * e_lost_w (the wave energy the events removed) at round-off under every rule checked;
   * x_drift (the centre of mass's displacement no momentum paid for): for the rigid shifts
     ('above', 'fragment') it falls at least linearly (order >= 0.9 between the last meshes) or
     is at round-off; for 'face' (only the two faces move) at least quadratically (>= 1.9) or
     at round-off;
   * l_defect (the cells' length no stress explains): at round-off for the rigid shifts, at
     least linear for 'face' (its face moves leave the correction in the two cells at the
     node).
3. Chatter (item 2 of the issue). Its deck (one-cell pieces over a fixed bottom) runs 1e6
   steps (t_end = 10 s) under the issue's own rules (delay/above), delay/face and the default
   accelerate/above: a bounded event count, no event after the first 3 ms, x_drift, e_lost_w
   and l_defect constant after them, jordan at round-off, and the wave ledger's drift at
   round-off (1e-9 of the scale) under accelerate, below 1e-6 under delay, where a free
   one-cell piece's Jordan block amplifies its steps' rounding (doc/method.md, "Chatter").
   Before the tensile late join was taken at t^n, 'delay' joined and parted on alternate
   steps for ever.
2. Causality (item 3 of the issue). A bar at 2 m/s closes a dry gap onto a bar whose bottom
   transmits; its twin has the lower bar 0.4 m long with a free bottom. Until a reflection
   could return from the twin's far end the two are the same problem. Under 'face' (every
   timing rule) the gauge records agree to 1e-9 of each record's scale; under 'above' they
   do not (the rigid shift moves the lower side by an amount that depends on its mass, 8
   cells of the transmitting bar against 40 of the twin): that difference is checked too,
   so that the comparison is shown able to fail.

usage: cli_consistency.py SPALLBAR WORKDIR
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "bench"))

from clitools import Checks, run, run_deck       # noqa: E402
from consistency import THETAS, LEVELS, drop_deck, pair_deck, last_row   # noqa: E402

ROUND_OFF_E = 1e-11        # e_lost_w [J/m^2] of an event that removes nothing (scale ~ 1e3)
ROUND_OFF_X = 1e-15        # x_drift, l_defect [m] (displacements ~ 1e-3 m)
TWIN_TOL = 1e-9            # gauge records, share of each record's largest value

TWIN = """&run t_end = 3e-4, timing = '{timing}', shift = '{shift}', warnings = .false. /
&mesh dt = 1e-5 /
&segments n = 2, length = 0.06, {lower}, young = 2e9, 2e9, density = 2000, 2000,
  interface = 'dry', gap = 7.4e-6, velocity = 2, 0 /
&ends top = 'free', bottom = '{bottom}' /
&gauges x = 0.025, 0.085 /
"""


def gauges(path):
    """Rows of PREFIX.gau (t and each gauge's stress, velocity, u)."""
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith(" ") and line.strip():
                rows.append([float(x) for x in line.split()])
    return rows


def order(a, b):
    return math.log2(a / b) if a > 0 and b > 0 else float("inf")


def check_orders(check, exe, work):
    rules = [("accelerate", "above"), ("min", "fragment"), ("accelerate", "face"),
             ("delay", "face"), ("within", "above")]
    for deck_name, build in (("drop", drop_deck), ("pair", pair_deck)):
        for timing, shift in rules:
            rule = (timing, shift, "admissible")
            means = {"x_drift": [], "e_lost_w": [], "l_defect": []}
            for level in LEVELS:
                rows = []
                for ti, theta in enumerate(THETAS):
                    name = f"{deck_name}_{timing}_{shift}_l{level}_t{ti}"
                    if not run_deck(check, exe, work, name, build(rule, level, theta)):
                        return
                    rows.append(last_row(os.path.join(work, name + ".his")))
                for key in means:
                    means[key].append(sum(abs(r[key]) for r in rows) / len(rows))
            tag = f"{deck_name} {timing}/{shift}"
            print(f"{tag}: x_drift {['%.3g' % x for x in means['x_drift']]}, e_lost_w "
                  f"{['%.3g' % x for x in means['e_lost_w']]}, l_defect "
                  f"{['%.3g' % x for x in means['l_defect']]}")
            es = means["e_lost_w"]
            if timing == "within":
                # the strain of the overlap loses the contact wave's sub-cell variance,
                # sigma_c^2 dt theta (1 - theta) (1/Z_i + 1/Z_i+1): first order
                check(order(es[-2], es[-1]) >= 0.9, f"{tag}: e_lost_w order "
                      f"{order(es[-2], es[-1]):.2f} >= 0.9: {es}")
            else:
                check(max(es) <= ROUND_OFF_E, f"{tag}: e_lost_w at round-off: {es}")
            # 'face' and 'within' move only the face halves (a landing's x_drift is the face
            # half's mass times its step)
            need = 1.9 if shift == "face" or timing == "within" else 0.9
            xs = means["x_drift"]
            check(xs[-1] <= ROUND_OFF_X or order(xs[-2], xs[-1]) >= need,
                  f"{tag}: x_drift order {order(xs[-2], xs[-1]):.2f} >= {need} or at "
                  f"round-off: {xs}")
            ls = means["l_defect"]
            if shift == "face" and timing != "within":
                check(ls[-1] <= ROUND_OFF_X or order(ls[-2], ls[-1]) >= 0.9,
                      f"{tag}: l_defect order {order(ls[-2], ls[-1]):.2f} >= 0.9: {ls}")
            else:
                check(max(ls) <= ROUND_OFF_X, f"{tag}: l_defect at round-off: {ls}")


def check_twin(check, exe, work):
    for timing, shift in (("accelerate", "face"), ("delay", "face"), ("min", "face"),
                          ("within", "above"), ("accelerate", "above")):
        recs = []
        for kind, lower, bottom in (("transmit", "0.08", "transmit"), ("twin", "0.4", "free")):
            name = f"twin_{kind}_{timing}_{shift}"
            deck = TWIN.format(timing=timing, shift=shift, lower=lower, bottom=bottom)
            if not run_deck(check, exe, work, name, deck):
                return
            recs.append(gauges(os.path.join(work, name + ".gau")))
        a, b = recs
        check(len(a) == len(b) and len(a) > 10, f"twin {timing}/{shift}: rows {len(a)}, {len(b)}")
        worst = 0.0
        for j in range(1, len(a[0])):
            scale = max(abs(r[j]) for r in a) or 1.0
            worst = max(worst, max(abs(x[j] - y[j]) for x, y in zip(a, b)) / scale)
        print(f"twin {timing}/{shift}: largest gauge difference {worst:.3g} of the scale")
        if shift == "face" or timing == "within":
            check(worst <= TWIN_TOL, f"twin {timing}/{shift}: {worst:.3g} > {TWIN_TOL}")
        else:
            check(worst > 1e-3, f"twin {timing}/{shift}: the rigid shift's dependence on the "
                  f"far side's mass is gone ({worst:.3g}): update doc/method.md")


CHATTER = """&run t_end = {t_end}, timing = '{timing}', shift = '{shift}', warnings = .false.,
  history_every = {every} /
&mesh dt = 1e-5 /
&segments n = 2, length = 0.03, 0.02, young = 4.9e9, 1.225e9, density = 4900, 1225,
  strength = 0, 0 /
&ends top = 'free', bottom = 'fixed' /
&load kind = 'power', face = 'top', p0 = 3.2e6, t_k = 9e-5, exponent = 1, t_cut = 4e-5 /
"""


def his_rows(path):
    """PREFIX.his by column name (lists of floats)."""
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith(" ") and line.strip():
                rows.append([float(x) for x in line.split()])
            elif names is None and line.split() and line.split()[0] == "t":
                names = line.split()
    return {k: [r[j] for r in rows] for j, k in enumerate(names)}


def event_times(path):
    with open(path) as f:
        return [float(l.split()[0]) for l in f if l.startswith(" ") and l.strip()]


def check_chatter(check, exe, work):
    # the deck under its own rules (delay/above), the default timing and 'face'
    for timing, shift, limit in (("accelerate", "above", 1e-9), ("delay", "above", 1e-6),
                                 ("delay", "face", 1e-6), ("within", "above", 1e-9)):
        name = f"chatter_{timing}_{shift}"
        if not run_deck(check, exe, work, name,
                        CHATTER.format(t_end=10.0, timing=timing, shift=shift, every=100000)):
            continue
        h = his_rows(os.path.join(work, name + ".his"))
        times = event_times(os.path.join(work, name + ".evt"))
        scale = max(abs(x) for x in h["e_wave"])
        drift = max(abs(x - h["ledger_w"][0]) for x in h["ledger_w"]) / scale
        print(f"chatter, {timing}/{shift}: {len(times)} events, the last at {max(times):.3g} s; "
              f"ledger_w drift {drift:.2g} of the scale; jordan {max(h['jordan']):.2g}; x_drift "
              f"{h['x_drift'][1]:.3g} .. {h['x_drift'][-1]:.3g} m; l_defect {h['l_defect'][-1]:.3g} m")
        check(len(times) < 100 and max(times) < 3e-3, f"chatter, {timing}/{shift}: {len(times)} "
              f"events, the last at {max(times)} s")
        # accelerate's pieces keep exactly representable stresses; under delay a free one-cell
        # piece rings at 1.02 MPa with a full mantissa, and the rounding of its steps feeds its
        # zig-zag Jordan block (doc/method.md, "Chatter"): measured 1.2e-7 over the 1e6 steps
        check(drift <= limit, f"chatter, {timing}/{shift}: ledger_w drift {drift:.3g} of the scale")
        check(max(h["jordan"]) <= 1e-12, f"chatter, {timing}/{shift}: jordan {max(h['jordan']):.3g}")
        for col in ("x_drift", "e_lost_w"):
            check(h[col][-1] == h[col][1], f"chatter, {timing}/{shift}: {col} moves after the "
                  "first row past the events")
        # l_defect is read from positions and stresses: constant to their round-off
        moved = max(abs(x - h["l_defect"][1]) for x in h["l_defect"][1:])
        check(moved <= 1e-12, f"chatter, {timing}/{shift}: l_defect moves by {moved:.3g} m "
              "after the first row past the events")


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    exe, work = os.path.abspath(argv[0]), argv[1]
    os.makedirs(work, exist_ok=True)
    check = Checks()
    check_orders(check, exe, work)
    check_twin(check, exe, work)
    check_chatter(check, exe, work)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
