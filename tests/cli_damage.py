#!/usr/bin/env python3
"""Time-dependent fracture, the Tuler-Butcher criterion (issue 35): &segments
damage_integral K and damage_exponent lambda (doc/method.md, "Time-dependent fracture").

  * a constant tension S > R held at a section (a step load of tension on the free top of
    a bar whose lower segment can break, transmitting bottom): the first fracture comes
    K / (S - R)^lambda after the brittle one (K = 0), to within one step; exactly the
    step the rectangle rule gives, t_brittle + (ceil(K / ((S - R)^lambda dt)) - 1) dt, at
    several K and lambda;
  * a tension rising linearly at the section (a load table ramp): the break comes where
    sigma_dot^lambda tau^(lambda+1) / (lambda + 1) = K, tau after the strength is passed,
    to within two steps (the rule's first-order error on a varying S);
  * K = 0 given is the brittle run to the bit (every output row), and so is a K given for
    an unbreakable segment... refused instead (exit 2), as K < 0, lambda <= 0 and the
    full-mass model are;
  * with a fracture energy the damage decides when the cohesive crack opens: the crack
    event comes K / (S - R)^lambda after the one without damage, to within one step;
  * admissibility: in a spall run with damage (and one with damage and cohesive cracks)
    e_lost_w never decreases and ledger_w stays constant (1e-9 of the energy scale);
  * the echo lists damage_integral and damage_exponent only where the deck gives them.

usage: cli_damage.py SPALLBAR WORKDIR
"""
import math
import os
import sys

import numpy as np

from clitools import Checks, expect_refused, fresh_work, run_deck

DT = 1.0e-6
S, R = 8.0e6, 5.0e6


def deck(k, lam, extra_seg="", load=None, t_end=1.0e-4, run_extra=""):
    load = load or "kind = 'power', p0 = -8.0e6, t_k = 1.0, exponent = 0"
    return f"""&run
  title = 'tuler-butcher'
  t_end = {t_end}
{run_extra}/
&mesh
  dt = {DT}
/
&segments
  n = 2
  length = 0.02, 0.05
  young = 1.0e9, 1.0e9
  density = 1000.0, 1000.0
  strength = -1, {R}
  damage_integral = 0, {k}
  damage_exponent = 2, {lam}
{extra_seg}/
&ends
  top = 'free', bottom = 'transmit'
/
&load
  {load}
/
"""


def body(path):
    with open(path) as f:
        return [line for line in f if line.startswith(" ")]


def columns(path):
    with open(path) as f:
        lines = f.readlines()
    names = [l for l in lines if l.startswith("t ") or l.startswith("# t ")][-1]
    names = names.lstrip("# ").split()
    rows = [l.split() for l in lines if l.startswith(" ")]
    return names, rows


def first_event(work, name, kind):
    names, rows = columns(os.path.join(work, name + ".evt"))
    for r in rows:
        if r[names.index("kind")] == kind:
            return float(r[names.index("t")])
    return None


def history(work, name):
    names, rows = columns(os.path.join(work, name + ".his"))
    a = np.array([[float(v) for v in r] for r in rows])
    return {n: a[:, k] for k, n in enumerate(names)}


def go(exe, work, name, text, check):
    return run_deck(check, exe, work, name, text)


def main():
    exe, check = os.path.abspath(sys.argv[1]), Checks()
    work = fresh_work(sys.argv[2], "damage")

    # the brittle reference, K = 0 given, and K = 0 not given (the same bits)
    go(exe, work, "brittle", deck(0, 2), check)
    t_b = first_event(work, "brittle", "fracture")
    check(t_b is not None, f"brittle: the section breaks ({t_b})")
    plain = deck(0, 2).replace("  damage_integral = 0, 0\n", "").replace(
        "  damage_exponent = 2, 2\n", "")
    go(exe, work, "plain", plain, check)
    for ext in (".his", ".evt", ".prf", ".frg"):
        check(body(os.path.join(work, "brittle" + ext)) == body(os.path.join(work, "plain" + ext)),
              f"K = 0 given: the rows of {ext} are those of a deck without it")
    with open(os.path.join(work, "plain.his")) as f:
        head = f.read()
    check("damage_integral" not in head, "a deck without damage does not echo it")
    with open(os.path.join(work, "brittle.his")) as f:
        head = f.read()
    check("damage_integral" in head and "damage_exponent" in head,
          "a deck that gives them echoes them")

    # a constant tension held above R: t = t_b + K / (S - R)^lambda, to within one step
    worst = 0.0
    for lam, tau in ((1.0, 7.3e-6), (2.0, 23.6e-6), (3.5, 41.2e-6), (2.0, 0.4e-6)):
        k = tau * (S - R) ** lam
        name = f"held_{lam}_{tau:.1e}"
        go(exe, work, name, deck(f"{k!r}", lam), check)
        t_k = first_event(work, name, "fracture")
        steps = math.ceil(tau / DT)
        exact_step = t_b + (steps - 1) * DT
        worst = max(worst, abs(t_k - (t_b + tau)) / DT)
        check(t_k is not None and abs(t_k - (t_b + tau)) <= DT * (1 + 1e-9),
              f"lambda = {lam}, K = {k:.3g}: break at {t_k} s, closed form {t_b + tau} s "
              "(within one step)")
        check(t_k is not None and abs(t_k - exact_step) < 1e-3 * DT,
              f"lambda = {lam}, K = {k:.3g}: the rectangle rule's step {exact_step} s")
    print(f"constant tension: largest |t - (t_b + K/(S-R)^lambda)| = {worst:.3f} dt")

    # a tension rising linearly at the section: sigma_dot tau^(lambda+1)/(lambda+1) = K
    ramp = 2.0e11          # Pa/s: the load's tension rate
    with open(os.path.join(work, "ramp.txt"), "w") as f:
        f.write(f"0 0\n1e-3 {-ramp * 1e-3!r}\n")
    load = "kind = 'table', table = 'ramp.txt'"
    go(exe, work, "ramp_b", deck(0, 2, load=load), check)
    t_rb = first_event(work, "ramp_b", "fracture")
    worst = 0.0
    for lam, tau in ((1.0, 12.3e-6), (2.0, 20.7e-6)):
        k = (ramp ** lam) * tau ** (lam + 1) / (lam + 1)
        name = f"ramp_{lam}"
        go(exe, work, name, deck(f"{k!r}", lam, load=load), check)
        t_k = first_event(work, name, "fracture")
        worst = max(worst, abs(t_k - (t_rb + tau)) / DT)
        check(t_k is not None and abs(t_k - (t_rb + tau)) <= 2 * DT,
              f"ramp, lambda = {lam}: break at {t_k} s, closed form {t_rb + tau} s "
              "(within two steps)")
    print(f"linear ramp: largest |t - (t_b + tau)| = {worst:.3f} dt")

    # with a fracture energy the damage decides when the cohesive crack opens
    gc = "  fracture_energy = 0, 50.0\n"
    go(exe, work, "coh_b", deck(0, 2, extra_seg=gc), check)
    t_cb = first_event(work, "coh_b", "crack")
    tau = 17.4e-6
    go(exe, work, "coh_k", deck(f"{tau * (S - R) ** 2!r}", 2, extra_seg=gc), check)
    t_ck = first_event(work, "coh_k", "crack")
    check(t_cb is not None and t_ck is not None and abs(t_ck - (t_cb + tau)) <= DT,
          f"cohesive: the crack opens K/(S-R)^2 later ({t_cb} -> {t_ck} s, tau = {tau})")

    # admissibility: the wave measure's books with damage (brittle and cohesive)
    spall = f"""&run
  title = 'damage spall'
  t_end = 6.0e-4
/
&mesh
  cells = 400
/
&segments
  n = 1
  length = 1.0
  young = 35.0e9
  density = 2350.0
  strength = 4.0e6
  damage_integral = 1.0e8
  {{extra}}
/
&ends
  top = 'free', bottom = 'free'
/
&load
  kind = 'power', p0 = 30.0e6, t_k = 1.0e-4, exponent = 1, t_cut = 1.0e-4
/
"""
    for name, extra in (("spall", ""), ("spall_coh", "fracture_energy = 100.0")):
        go(exe, work, name, spall.replace("{extra}", extra), check)
        h = history(work, name)
        scale = max(np.abs(h["w_ext"]).max(), 1e-30)
        check(h["fragments"][-1] > 1 or h["cracks_open"].max() > 0,
              f"{name}: the bar spalls ({h['fragments'][-1]:.0f} fragments)")
        drop = np.min(np.diff(h["e_lost_w"]))
        check(drop >= -1e-12 * scale, f"{name}: e_lost_w never decreases ({drop / scale:.1e})")
        spread = np.ptp(h["ledger_w"]) / scale
        check(spread <= 1e-9, f"{name}: ledger_w constant ({spread:.1e} of the scale)")
        print(f"{name}: fragments {h['fragments'][-1]:.0f}, min d e_lost_w {drop / scale:.1e}, "
              f"ledger_w spread {spread:.1e}")

    def bad(what, text, needles):
        expect_refused(check, exe, work, what, text, needles)
    bad("K < 0", deck(-1.0, 2), ["&segments", "damage_integral(2)", ">= 0"])
    bad("lambda = 0", deck(1.0, 0.0), ["&segments", "damage_exponent(2)", "> 0"])
    bad("lambda < 0", deck(1.0, -2.0), ["&segments", "damage_exponent(2)", "> 0"])
    bad("K on an unbreakable segment",
        deck(1.0, 2).replace("damage_integral = 0, 1.0", "damage_integral = 1.0, 1.0"),
        ["&segments", "damage_integral(1)", "strength(1)"])
    bad("K with the full-mass model", deck(1.0, 2, run_extra="  model = 'full-mass'\n"),
        ["&segments", "damage_integral", "half-mass"])
    bad("K beyond n", deck(1.0, 2).replace("damage_integral = 0, 1.0",
                                           "damage_integral = 0, 1.0, 3.0"),
        ["&segments", "damage_integral(3)", "n = 2"])
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
