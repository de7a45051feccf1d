#!/usr/bin/env python3
"""Cross-sections at the largest supported impedance ratio (issue 32, item 7; doc/areas.md).

The deck accepts segments whose axial impedances rho a A differ by up to 1e6 and refuses
more (exit 2, one line naming area). At exactly 1e6, in area or in the material, with the
wide segment loaded (the side whose round-off the narrow one reads), the wave ledger
`ledger_w` of PREFIX.his stays at its round-off: within LEDGER_BOUND of the scale (the
largest |w_wave| or the initial e_wave). Measured 2e-14 .. 7e-14 at 400 cells for every
ratio up to 1e14; at 1e15 it drifts 1.4e-11 .. 5.6e-11, at 1e30 by 0.93 (doc/areas.md).

usage: cli_areas.py SPALLBAR WORKDIR
"""
import os
import shutil
import sys

from clitools import Checks, history, run, run_deck

LEDGER_BOUND = 2e-13   # of the scale: round-off of 1600 steps of 800 cells (7e-14 measured)
CELLS = 400            # per segment
T_END = 4 * 0.5 / (2e11 / 7800) ** 0.5   # four transits of a segment


def deck(area, young="2e11, 2e11", density="7800, 7800", ends=("free", "free"), load=True):
    """Two bonded steel-like segments of 0.5 m, a constant pressure on the top face."""
    text = (f"&run t_end = {T_END!r}, history_every = 1, energy_guard = 0 /\n"
            f"&mesh cells = {CELLS} /\n"
            f"&segments n = 2, length = 0.5, 0.5, young = {young}, density = {density}, "
            f"area = {area} /\n"
            f"&ends top = '{ends[0]}', bottom = '{ends[1]}' /\n")
    if load:
        text += "&load kind = 'power', p0 = 1e8, exponent = 0 /\n"
    return text


# (name, deck): each at the impedance ratio 1e6
AT_LIMIT = [
    ("wide_top_free_free", deck("1e6, 1")),
    ("wide_top_fixed_bottom", deck("1e6, 1", ends=("free", "fixed"))),
    ("wide_top_transmit", deck("1e6, 1", ends=("transmit", "transmit"))),
    ("wide_bottom", deck("1, 1e6")),
    # the same ratio in the material (same wave speed: the cells stay the same)
    ("material", deck("1, 1", young="2e11, 2e5", density="7800, 7.8e-3")),
    # half in the area, half in the material
    ("area_and_material", deck("1e3, 1", young="2e11, 2e8", density="7800, 7.8")),
]


def ledger_drift(path):
    """max |ledger_w - ledger_w(0)| over the rows, of the scale max(|w_wave|, e_wave(0))."""
    h = history(path)
    lw, ww = h["ledger_w"], h["w_wave"]
    scale = max(max(abs(x) for x in ww), h["e_wave"][0])
    return max(abs(x - lw[0]) for x in lw) / scale


def main():
    exe, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()

    for name, text in AT_LIMIT:
        if not run_deck(check, exe, work, name, text):
            continue
        drift = ledger_drift(os.path.join(work, name + ".his"))
        check(drift <= LEDGER_BOUND, f"{name}: ledger_w drifts {drift:.3g} of the scale, "
              f"above {LEDGER_BOUND:g}")
        if drift <= LEDGER_BOUND:
            print(f"ok   {name}: ratio 1e6, ledger_w drift {drift:.3g} of the scale")

    # just beyond the limit, in either segment: refused before anything is written
    for name, area, seg in (("beyond_top", "1.01e6, 1", 2), ("beyond_bottom", "1, 1.01e6", 1)):
        with open(os.path.join(work, name + ".nml"), "w") as f:
            f.write(deck(area))
        r = run(exe, [name + ".nml", "--quiet"], work)
        lines = r.stderr.splitlines()
        want = f"spallbar: &segments: area({seg}): the axial impedance rho a A of segment " \
               f"{3 - seg} is 1.01e6 times that of segment {seg}; at most 1e6 is supported"
        check(r.returncode == 2, f"{name}: exit {r.returncode}, expected 2")
        check(len(lines) == 1 and want in lines[0], f"{name}: stderr {r.stderr!r}")
        left = [x for x in os.listdir(work) if x.startswith(name + ".") and x != name + ".nml"]
        check(not left, f"{name}: wrote {left}")
        print(f"ok   {name}: {lines[0] if lines else ''}")

    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
