#!/usr/bin/env python3
"""The paper's Example 3, case 2 (zero tensile strength, massive fragmentation), from the
decks in input/example3_case2/ (issue 5; doc/validation.md has the measured tables).

  cli_case2.py SPALLBAR DECK_DIR WORKDIR run RULE POLICY   one rule x policy at h/19,
      h/95, h/190: the energy bound, the ledger, the momentum balance with the base
      impulse, the base reaction and its spurious peaks; prints the event counts
  cli_case2.py SPALLBAR DECK_DIR WORKDIR convergence       h/19, h/95, h/190 agree
  cli_case2.py SPALLBAR DECK_DIR WORKDIR observations      the paper's observations
  cli_case2.py SPALLBAR DECK_DIR WORKDIR order             the default rules' observed order
      over [0, 0.1 s] (h/19 to h/760, 1 ms windows) and the sensitivity to the load's p0
      that keeps the later part from converging

The last two read the runs the first kind leaves in WORKDIR (ctest fixtures).
Plain Python: no numpy needed.
"""
import math
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
            if not line.startswith(" "):          # '#' lines, the column-name first line
                words = line.lstrip("#").split()
                if words and words[0] == "t" and "reaction_bottom" in words:
                    names = words
                continue
            rows.append([float(x) for x in line.split()])
    return {name: [r[k] for r in rows] for k, name in enumerate(names)}


def events(prefix):
    kinds = {}
    with open(prefix + ".evt") as f:
        for line in f:
            if line.startswith(" "):
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


def means_to(t, r, width, t_max):
    """Means of r over consecutive windows [k width, (k+1) width) that end by t_max."""
    sums, counts = {}, {}
    for tk, rk in zip(t, r):
        k = int(tk / width)
        if (k + 1) * width <= t_max + 1e-12:
            sums[k] = sums.get(k, 0.0) + rk
            counts[k] = counts.get(k, 0) + 1
    return [sums[k] / counts[k] for k in sorted(sums)]


def window_means(t, r, width):
    """Mean of r over consecutive windows of the given width [s], from t = 0 to T_END."""
    return means_to(t, r, width, T_END)


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


ORDER_CELLS = (19, 95, 190, 380, 760)
ORDER_T = 0.1              # the horizon of the order check [s]
ORDER_WINDOW = 1.0e-3      # the 1 ms windows
ORDER_MIN = 0.8


def default_deck(deck_dir, cells, t_end, p0_scale=1.0):
    """input/example3_case2's h/190 deck with the default rules (accelerate/above; events
    not given: 'admissible') at another mesh, end time and load amplitude."""
    text = open(os.path.join(deck_dir, "accelerate_above_h190.nml")).read()
    for old, new in (("cells = 190", f"cells = {cells}"), ("t_end         = 0.6",
                     f"t_end         = {t_end!r}"), ("p0       = 0.1e6", f"p0       = {P0 * p0_scale!r}"),
                     ("profile_times", "! profile_times")):
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


def run_deck(check, exe, work, name, text):
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(text)
    r = run(exe, [name + ".nml", "-q"], work)
    check(r.returncode == 0, f"{name}: exit {r.returncode} {r.stderr.strip()}")
    h = history(os.path.join(work, name))
    return h["t"], h["reaction_bottom"]


def check_order(check, exe, deck_dir, work):
    # convergence of the default rules where the base reaction is a continuous function of
    # the data: [0, 0.1 s], relative L1 distance of 1 ms window means between successive
    # meshes, observed order log(d1/d2)/log(r) >= 0.8 for each triple
    m = {}
    for cells in ORDER_CELLS:
        t, r = run_deck(check, exe, work, f"order_h{cells}", default_deck(deck_dir, cells, ORDER_T))
        m[cells] = means_to(t, r, ORDER_WINDOW, ORDER_T)
    d = [distance(m[a], m[b]) for a, b in zip(ORDER_CELLS, ORDER_CELLS[1:])]
    orders = [math.log(d[k] / d[k + 1]) / math.log(ORDER_CELLS[k + 2] / ORDER_CELLS[k + 1])
              for k in range(len(d) - 1)]
    print("default rules over [0, 0.1 s]: distances " + ", ".join(
        f"h/{a}-h/{b} {x:.4f}" for (a, b), x in zip(zip(ORDER_CELLS, ORDER_CELLS[1:]), d))
        + "; observed orders " + ", ".join(f"{o:.2f}" for o in orders))
    for o in orders:
        check(o >= ORDER_MIN, f"observed order {o:.2f} < {ORDER_MIN}")
    # why the whole run does not converge: at h/190 a relative change of 1e-4 in p0 moves the
    # 1 ms means over [0, 0.6 s] by more than 100 times that (events move by a step and the
    # bouncing that follows carries it on), while over [0, 0.1 s] the response stays linear
    eps = 1.0e-4
    base = run_deck(check, exe, work, "order_h190_full", default_deck(deck_dir, 190, T_END))
    pert = run_deck(check, exe, work, "order_h190_perturbed",
                    default_deck(deck_dir, 190, T_END, 1.0 + eps))
    early = distance(means_to(*pert, ORDER_WINDOW, ORDER_T), means_to(*base, ORDER_WINDOW, ORDER_T))
    late = distance(means_to(*pert, ORDER_WINDOW, T_END), means_to(*base, ORDER_WINDOW, T_END))
    print(f"p0 scaled by 1 + {eps:g} at h/190: distance {early:.2e} over [0, 0.1 s], "
          f"{late:.2e} over [0, 0.6 s]")
    check(early <= 2.0 * eps, f"p0 + {eps:g}: response over [0, 0.1 s] not linear ({early:.2e})")
    check(late >= 100.0 * eps, f"p0 + {eps:g}: distance over [0, 0.6 s] only {late:.2e} "
          "(doc/validation.md explains the late part's lack of convergence by its size)")


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
    elif what == "order":
        check_order(check, exe, deck_dir, work)
    else:
        raise SystemExit(f"unknown mode {what}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
