#!/usr/bin/env python3
"""The paper's Example 3, case 2 (zero tensile strength, massive fragmentation), from the
decks in input/example3_case2/ (issue 5; doc/validation.md has the measured tables).

  cli_case2.py SPALLBAR DECK_DIR WORKDIR run RULE POLICY   one rule x policy at h/19,
      h/95, h/190: the energy bound, the ledger, the momentum balance with the base
      impulse, the base reaction and its spurious peaks; prints the event counts
  cli_case2.py SPALLBAR DECK_DIR WORKDIR convergence       h/19, h/95, h/190 agree
  cli_case2.py SPALLBAR DECK_DIR WORKDIR observations      the paper's observations

The last two read the runs the first kind leaves in WORKDIR (ctest fixtures).
Plain Python: no numpy needed.
"""
import os
import sys

from clitools import Checks, run

CELLS = (19, 95, 190)
P0 = 0.1e6                 # load amplitude [Pa]
H = 0.95                   # bar height [m]
A = (20.0e6 / 1765.8) ** 0.5
T_END = 0.6

# tolerances of the checks (doc/validation.md gives the measured values)
ENERGY_TOL = 0.005         # excess over E0 + W, share of the largest work of the load so far
LEDGER_TOL = 1.0e-9        # ledger drift, share of the largest work of the load
MOMENTUM_TOL = 1.0e-9      # momentum balance, share of the base impulse
IMPULSE_TOL = 0.005        # sum of reaction dt vs the base's exact impulse
PEAK_JUMP = P0             # a spurious peak: one row above both neighbours by more than this
PEAK_FRACTION = 0.01       # share of steps with a spurious peak: the paper's ~1%
REACTION_BOUND = 4.0 * P0  # the elastic bar: 2 p0 + rho g h = 2.16 p0, plus the peaks
CONVERGENCE_TOL = 0.15     # mesh-to-mesh distance of the 4 h/a window means


def history(prefix):
    """Columns of PREFIX.his by name (header line '# t reaction_bottom ...')."""
    names, rows = None, []
    with open(prefix + ".his") as f:
        for line in f:
            if line.startswith("#"):
                words = line[1:].split()
                if words and words[0] == "t" and "reaction_bottom" in words:
                    names = words
                continue
            rows.append([float(x) for x in line.split()])
    return {name: [r[k] for r in rows] for k, name in enumerate(names)}


def events(prefix):
    kinds = {}
    with open(prefix + ".evt") as f:
        for line in f:
            if not line.startswith("#"):
                kind = line.split()[2]
                kinds[kind] = kinds.get(kind, 0) + 1
    return kinds


def energy_excess(h):
    """Largest (E - E0 - W) / max W so far, and the largest excess [J/m^2]."""
    e = [k + s + p for k, s, p in zip(h["e_kin"], h["e_strain"], h["e_pot"])]
    wmax, worst, worst_abs = 0.0, -1.0, -1.0e300
    for ek, w in zip(e, h["w_ext"]):
        wmax = max(wmax, abs(w))
        ex = ek - e[0] - w
        worst_abs = max(worst_abs, ex)
        if wmax > 0.0:
            worst = max(worst, ex / wmax)
    return worst, worst_abs


def spurious_peaks(r):
    """Rows whose base reaction stands above both neighbours by more than PEAK_JUMP."""
    return sum(1 for k in range(1, len(r) - 1)
               if r[k] - r[k - 1] > PEAK_JUMP and r[k] - r[k + 1] > PEAK_JUMP)


def check_run(check, exe, deck_dir, work, rule, policy):
    for cells in CELLS:
        name = f"{rule}_{policy}_h{cells}"
        r = run(exe, [os.path.join(deck_dir, name + ".nml"), "-q", "--output",
                      os.path.join(work, name)], work)
        check(r.returncode == 0, f"{name}: exit {r.returncode} {r.stderr.strip()}")
        if r.returncode != 0:
            continue
        h = history(os.path.join(work, name))
        ev = events(os.path.join(work, name))
        t, react = h["t"], h["reaction_bottom"]
        dt = t[1] - t[0]
        check(abs(t[-1] - T_END) < dt, f"{name}: runs to t = {T_END} s")
        wmax = max(abs(w) for w in h["w_ext"])
        rel, ex = energy_excess(h)
        drift = max(abs(x - h["ledger"][0]) for x in h["ledger"]) / wmax
        mom = [m - h["momentum"][0] - (g + e + s + p) for m, g, e, s, p in
               zip(h["momentum"], h["i_gravity"], h["i_ends"], h["i_support"], h["p_shift"])]
        i_base = -h["i_support"][-1]
        mom_err = max(abs(x) for x in mom) / i_base
        imp_err = abs(sum(react) * dt - i_base) / i_base
        peaks = spurious_peaks(react)
        steps = len(react) - 1
        print(f"{name}: events {sum(ev.values())} (collisions {ev.get('collision', 0)}, "
              f"separations {ev.get('separation', 0)}, fractures {ev.get('fracture', 0)}, "
              f"base collisions {ev.get('base-collision', 0)}); excess {ex:.3g} J/m^2 = "
              f"{100 * rel:.3f}% of the largest work {wmax:.1f} J/m^2; ledger drift "
              f"{drift:.1e}; momentum balance {mom_err:.1e}; impulse of the reaction column vs "
              f"the base's {imp_err:.2e}; p_shift {h['p_shift'][-1] / i_base:.3f} of the base "
              f"impulse; spurious peaks {peaks} of {steps} steps ({100 * peaks / steps:.2f}%); "
              f"largest reaction {max(react) / P0:.2f} p0")
        check(rel <= ENERGY_TOL, f"{name}: energy excess {100 * rel:.3f}% > {100 * ENERGY_TOL}%")
        check(drift <= LEDGER_TOL, f"{name}: ledger drift {drift:.1e}")
        check(mom_err <= MOMENTUM_TOL, f"{name}: momentum balance {mom_err:.1e}")
        check(imp_err <= IMPULSE_TOL, f"{name}: reaction impulse {imp_err:.2e}")
        check(peaks / steps <= PEAK_FRACTION, f"{name}: spurious peaks {peaks / steps:.3f}")
        check(max(react) <= REACTION_BOUND and min(react) >= -1.0e-6 * P0,
              f"{name}: reaction within [0, {REACTION_BOUND / P0:.0f} p0]")


def window_means(t, r, width):
    """Mean of r over consecutive windows of the given width [s], from t = 0."""
    sums, counts = {}, {}
    for tk, rk in zip(t, r):
        k = int(tk / width)
        sums[k] = sums.get(k, 0.0) + rk
        counts[k] = counts.get(k, 0) + 1
    return [sums[k] / counts[k] for k in sorted(sums) if (k + 1) * width <= T_END + 1e-12]


def distance(a, b):
    """Relative L1 distance of two window-mean histories."""
    n = min(len(a), len(b))
    return sum(abs(a[k] - b[k]) for k in range(n)) / sum(abs(b[k]) for k in range(n))


def check_convergence(check, work):
    # the norm: the base reaction averaged over windows of 4 h/a (the period of the fixed
    # bar, the time scale of the paper's main collision periods; 16 windows in 0.6 s), the
    # relative L1 distance between two meshes. Over single transits h/a the fragmentation
    # differs in detail (printed, not tested).
    worst = 0.0
    for rule in ("accelerate", "delay", "min"):
        for policy in ("above", "fragment"):
            line = []
            for mult in (4, 1):
                m = {}
                for cells in CELLS:
                    h = history(os.path.join(work, f"{rule}_{policy}_h{cells}"))
                    m[cells] = window_means(h["t"], h["reaction_bottom"], mult * H / A)
                d = [distance(m[19], m[95]), distance(m[19], m[190]), distance(m[95], m[190])]
                line.append(f"windows of {mult} h/a: h/19-h/95 {d[0]:.3f}, h/19-h/190 {d[1]:.3f}, "
                            f"h/95-h/190 {d[2]:.3f}")
                if mult == 4:
                    # 'above' (and the default rules): every pair agrees; 'fragment' under the
                    # admissible rules keeps more energy in one-cell fragments and agrees from
                    # h/95 on (h/19 is too coarse for it: doc/validation.md)
                    tested = d if policy == "above" else d[2:]
                    worst = max(worst, max(tested))
                    check(max(tested) <= CONVERGENCE_TOL,
                          f"{rule}/{policy}: meshes disagree ({max(tested):.3f})")
            print(f"{rule}/{policy}: mean base reaction, relative L1 distance; " + "; ".join(line))
    print(f"worst distance over windows of 4 h/a: {worst:.3f} (tolerance {CONVERGENCE_TOL})")


def check_observations(check, exe, deck_dir, work):
    # (1) after the first separation from the base: an almost permanent contact phase, in
    #     which the main collision periods (the bar compact, one fragment) carry the large
    #     reactions and the fragmented periods between them small ones
    for cells in CELLS:
        name = f"accelerate_fragment_h{cells}"
        h = history(os.path.join(work, name))
        r, frag = h["reaction_bottom"], h["fragments"]
        first_sep = next(k for k in range(1, len(r)) if r[k] <= 0.0 and frag[k] > 1)
        rest = range(first_sep, len(r))
        contact = sum(1 for k in rest if r[k] > 0.0) / len(rest)
        compact = [r[k] for k in rest if frag[k] == 1]
        split = [r[k] for k in rest if frag[k] > 1]
        mc, ms = sum(compact) / len(compact), sum(split) / len(split)
        print(f"{name}: after the first separation (t = {h['t'][first_sep]:.4f} s) the base is "
              f"in contact {100 * contact:.1f}% of the steps; mean reaction compact {mc:.4g} Pa "
              f"({len(compact)} steps), fragmented {ms:.4g} Pa ({len(split)} steps)")
        check(contact >= 0.8, f"{name}: contact {contact:.2f} of the steps")
        check(mc >= 2.0 * ms, f"{name}: compact periods do not carry the reaction")
    # (2) the full-mass model drifts away from the half-mass one as time goes on (Fig. 12):
    #     window means over 4 h/a, the first three windows (to 0.107 s) against the rest,
    #     compared with how much the half-mass model itself moves between h/19 and h/190
    name = "fullmass_accelerate_fragment_h19"
    r = run(exe, [os.path.join(deck_dir, name + ".nml"), "-q", "--output",
                  os.path.join(work, name)], work)
    check(r.returncode == 0, f"{name}: exit {r.returncode} {r.stderr.strip()}")
    width = 4.0 * H / A
    m = {}
    for key in (name, "accelerate_fragment_h19", "accelerate_fragment_h190"):
        h = history(os.path.join(work, key))
        m[key] = window_means(h["t"], h["reaction_bottom"], width)
    full, half, fine = m[name], m["accelerate_fragment_h19"], m["accelerate_fragment_h190"]
    early, late = distance(full[:3], half[:3]), distance(full[3:], half[3:])
    mesh = distance(half[3:], fine[3:])
    print(f"full-mass vs half-mass model (h/19, accelerate/fragment), mean base reaction over "
          f"4 h/a: relative L1 distance {early:.3f} to t = {3 * width:.3f} s, {late:.3f} after "
          f"(the half-mass model between h/19 and h/190 after: {mesh:.3f})")
    check(early <= 0.15, f"full-mass model departs early ({early:.3f})")
    check(late >= 0.3 and late >= 2.0 * mesh, f"full-mass model does not drift ({late:.3f})")


def main():
    exe, deck_dir, work, what = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    check = Checks()
    if what == "run":
        check_run(check, exe, deck_dir, work, sys.argv[5], sys.argv[6])
    elif what == "convergence":
        check_convergence(check, work)
    elif what == "observations":
        check_observations(check, exe, deck_dir, work)
    else:
        raise SystemExit(f"unknown mode {what}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
