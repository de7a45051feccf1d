"""The rigid base at either end (issue 33): a bar against a base above it is the mirror of a
bar on a base below it.

Each case is a deck with a base below the bar (`&ends bottom = 'base'`) and its mirror: the
segments reversed, `top` and `bottom` swapped (`base_gap` -> `base_gap_top`), gravity and
the segments' velocities negated, the load on the other face. Both are run (PREFIX.h5, full
double precision) and compared:

  * events: the same (step, kind) with node i <-> n - i, the same stresses;
  * history: energies and ledgers equal (from their values at t = 0), counts equal; momentum
    and impulses negated; the reactions and end stresses of the two ends swapped.

The cases cover landing and lift-off under every timing and shift rule, both event rule sets
('admissible'; 'paper' where only the base makes events: its collision rule between fragments
moves the upper side, a direction no mirror follows), the full-mass model, a static start on the base, a gap to the
base, dry interfaces colliding on the way, and a bar held at its far end with an odd cell
count (the landing credit). The bound: the mirrored run does the same arithmetic on
mirrored numbers but not in the same order (sums over the bar run from the other end), so
values agree to round-off, relative to each column's scale: 1e-12 (measured at most 3e-13;
the events' decisions are the same, so nothing is amplified beyond the lattice's own
round-off growth over the run).

Then a base above the bar restarts bit-identically (from a checkpoint while the bar rests
against it and one while it is off it), and bad input about it is refused (exit 2, one line
naming &ends or &initial and the variable, no file written).

usage: cli_base_mirror.py SPALLBAR WORKDIR     (needs numpy and h5py)
"""
import os
import sys

import h5py
import numpy as np

from cli_restart import same_outputs
from clitools import Checks, run

# compared relative to the run's energy scale [J/m^2] (the largest of these columns)
ENERGY = ("e_kin", "e_strain", "e_pot", "w_ext", "e_lost", "w_load", "w_transmit", "ledger",
          "e_fracture", "e_join", "e_shift", "e_contact", "e_wave", "e_wave_g", "w_wave",
          "e_lost_w", "ledger_w")
# relative to their own scale; jordan and overlap are already relative (absolute bound)
SAME = ("t", "fragments", "step")
ABSOLUTE = ("jordan", "overlap")
# relative to the run's momentum scale [kg/(m s)], negated in the mirror
NEGATED = ("momentum", "i_gravity", "i_ends", "i_support", "p_shift")
SWAPPED = (("reaction_bottom", "reaction_top"), ("s_end_top", "s_end_bottom"))
BOUND = 1e-12

# Seed Example 3's soil bar (doc/validation.md): h = 0.95 m, E = 20 MPa, rho = 1765.8 kg/m^3
SOIL = dict(length=[0.95], young=[20.0e6], density=[1765.8])
EX3_LOAD = dict(kind="'power'", face="'top'", p0=0.1e6, t_k=0.5, exponent=3.0, t_cut=0.5)


def case(run_, segments, ends, load=None, initial=None, mesh=None):
    """A deck as groups of variables (lists for per-segment values)."""
    return {"run": dict(run_, hdf5=".true."), "mesh": mesh or {}, "segments": segments,
            "ends": ends, "load": load or {}, "initial": initial or {}}


def cases():
    """The decks with a base below the bar, by name."""
    out = {}
    for timing, shift, events in (("accelerate", "above", "admissible"),
                                  ("delay", "fragment", "admissible"),
                                  ("min", "fragment", "admissible"),
                                  ("accelerate", "above", "paper"),
                                  ("delay", "fragment", "paper")):
        rules = dict(gravity=9.81, timing=f"'{timing}'", shift=f"'{shift}'",
                     events=f"'{events}'", warnings=".false.")
        tag = f"{timing}_{shift}_{events}"
        out[f"ex3_case1_{tag}"] = case(
            dict(rules, t_end=1.0), dict(n=1, **SOIL), dict(top="'free'", bottom="'base'"),
            EX3_LOAD, dict(state="'static'"), dict(cells=19))
        # an unbreakable bar dropped onto the base from a gap: it bounces
        out[f"bounce_{tag}"] = case(
            dict(rules, t_end=0.02), dict(n=1, length=[0.5], young=[2e9], density=[2000.0],
                                          velocity=[1.5]),
            dict(top="'free'", bottom="'base'", base_gap=1e-4), mesh=dict(dt=1e-5))
        if events == "paper":
            # the paper's rules move the upper side of a collision between fragments (doc/
            # method.md): a rule with a direction, which no mirror can follow
            continue
        out[f"ex3_case2_{tag}"] = case(
            dict(rules, t_end=0.3), dict(n=1, strength=[0.0], **SOIL),
            dict(top="'free'", bottom="'base'"), EX3_LOAD, dict(state="'static'"),
            dict(cells=19))
        # a breakable two-layer bar dropped onto the base from a gap, a dry interface with a
        # gap of its own on the way: collisions, landings, lift-offs, breaks
        out[f"drop_{tag}"] = case(
            dict(rules, t_end=0.02), dict(n=2, length=[0.3, 0.2], young=[2e9, 1.5e9],
                                          density=[2000.0, 1500.0], strength=[0.4e6, 0.2e6],
                                          interface=["'dry'"], gap=[2e-5],
                                          velocity=[1.5, 1.0]),
            dict(top="'free'", bottom="'base'", base_gap=1e-4), mesh=dict(dt=1e-5))
    # a bar between two bases (a floor and a ceiling) under gravity: both faces can land in
    # one step; the deeper overlap lands first, the stronger pull lets go first (end_order)
    # (admissible only: the paper's collision rule has a direction, above)
    for events in ("admissible",):
        out[f"two_bases_{events}"] = case(
            dict(gravity=9.81, t_end=0.02, events=f"'{events}'", warnings=".false."),
            dict(n=2, length=[0.3, 0.2], young=[2e9, 1.5e9], density=[2000.0, 1500.0],
                 strength=[0.4e6, 0.2e6], velocity=[1.5, 1.0]),
            dict(top="'base'", bottom="'base'", base_gap=1e-4, base_gap_top=3e-5),
            mesh=dict(dt=1e-5))
    # the full-mass model (the paper's comparison, Fig. 12)
    out["ex3_case2_full_mass"] = case(
        dict(gravity=9.81, t_end=0.3, model="'full-mass'", warnings=".false."),
        dict(n=1, strength=[0.0], **SOIL), dict(top="'free'", bottom="'base'"), EX3_LOAD,
        dict(state="'static'"), dict(cells=19))
    # held at the far end, odd cell count: a bar hanging from a fixed top stretches onto the
    # base below it (the landing credit of doc/method.md), then a load pulls it off again
    out["hanging_odd"] = case(
        dict(gravity=9.81, t_end=0.05, warnings=".false."),
        dict(n=1, length=[0.95], young=[2.0e6], density=[1765.8]),
        dict(top="'fixed'", bottom="'base'", base_gap=2e-4), mesh=dict(cells=21))
    return out


def mirror(deck):
    """The mirrored deck: segments reversed, ends swapped, gravity and velocities negated."""
    m = {g: dict(v) for g, v in deck.items()}
    seg = m["segments"]
    for k, v in list(seg.items()):
        if isinstance(v, list):
            seg[k] = v[::-1]
    if "velocity" in seg:
        seg["velocity"] = [-v for v in seg["velocity"]]
    ends = m["ends"]
    ends["top"], ends["bottom"] = ends["bottom"], ends["top"]
    gaps = ends.pop("base_gap", None), ends.pop("base_gap_top", None)
    if gaps[0] is not None:
        ends["base_gap_top"] = gaps[0]
    if gaps[1] is not None:
        ends["base_gap"] = gaps[1]
    if "gravity" in m["run"]:
        m["run"]["gravity"] = -m["run"]["gravity"]
    if "face" in m["load"]:
        m["load"]["face"] = "'bottom'" if m["load"]["face"] == "'top'" else "'top'"
    return m


def text(deck):
    """The namelist text of a deck."""
    lines = []
    for group, values in deck.items():
        if not values and group not in ("mesh",):
            continue
        items = []
        for k, v in values.items():
            if isinstance(v, list):
                v = ", ".join(repr(x) if isinstance(x, float) else str(x) for x in v)
            items.append(f"{k} = {v}")
        lines.append(f"&{group} " + ", ".join(items) + " /")
    return "\n".join(lines) + "\n"


def read(path):
    """History columns and events of PREFIX.h5."""
    with h5py.File(path, "r") as f:
        h = {k: f["history"][k][()] for k in f["history"]}
        ev = {k: f["events"][k][()] for k in ("step", "kind", "node", "stress")}
        n = int(f["mesh"].attrs["cells"])
    return h, ev, n


def dev(a, b, scale=None):
    """max |a - b| relative to scale (default: the larger of their own scales)."""
    if scale is None:
        scale = max(np.max(np.abs(a)), np.max(np.abs(b)))
    return float(np.max(np.abs(a - b)) / max(scale, 1e-300)) if len(a) else 0.0


def compare(check, name, base, mirrored, spring=False):
    """The mirror relations between two runs; returns the largest deviation."""
    (h, ev, n), (hm, evm, nm) = base, mirrored
    check(n == nm and len(h["t"]) == len(hm["t"]), f"{name}: different mesh or row count")
    if not (n == nm and len(h["t"]) == len(hm["t"])):
        return float("inf")
    worst = 0.0
    a = sorted(zip(ev["step"], ev["kind"], ev["node"]))
    # a node i is node n - i in the mirror; the full-mass model's breaks are its springs' (cut
    # spring k reported as node k - 1): k <-> n + 1 - k
    last = np.where(evm["kind"] == 1, n - 1, n) if spring else n
    b = sorted(zip(evm["step"], evm["kind"], last - evm["node"]))
    check(a == b, f"{name}: the events are not the mirrored ones ({len(a)} vs {len(b)})")
    if a == b and len(a):
        worst = max(worst, dev(np.sort(ev["stress"]), np.sort(evm["stress"])))
    e_scale = max(np.max(np.abs(h[c])) for c in ENERGY)
    p_scale = max(np.max(np.abs(h[c])) for c in NEGATED)
    # from their values at t = 0: a gap at a dry interface moves what lies below it down by
    # the gap, so the mirrored bar starts displaced by it as a whole (e_pot and the ledgers
    # holding it differ by g M gap, a constant)
    for col in ENERGY:
        worst = max(worst, dev(h[col] - h[col][0], hm[col] - hm[col][0], e_scale))
    for col in SAME:
        worst = max(worst, dev(h[col], hm[col]))
    for col in ABSOLUTE:
        worst = max(worst, dev(h[col], hm[col], 1.0))
    for col in NEGATED:
        worst = max(worst, dev(h[col], -hm[col], p_scale))
    check(worst <= BOUND, f"{name}: mirror deviation {worst:.2e} > {BOUND:.0e}")
    return worst


def restart(check, exe, work, deck):
    """The deck (a base above the bar) stopped at t1 with a checkpoint, restarted to t_end,
    against the uninterrupted run (cli_restart.same_outputs), t1 once while the bar rests
    against the base and once while it is off it."""
    full = dict(deck, run=dict(deck["run"], checkpoint="'full.ck.h5'", checkpoint_every=400))
    with open(os.path.join(work, "top_full.nml"), "w") as f:
        f.write(text(full))
    r = run(exe, ["top_full.nml", "--output", "top_U", "-q"], work)
    check(r.returncode == 0, f"restart: uninterrupted run exits 0 ({r.stderr.strip()})")
    if r.returncode:
        return
    with h5py.File(os.path.join(work, "top_U.h5"), "r") as f:
        t_ev, kind = f["events/t"][()], f["events/kind"][()]
    lift, land = t_ev[kind == 3], t_ev[kind == 4]
    t_off = 0.5 * (lift[0] + land[land > lift[0]][0])
    t_on = 0.5 * (land[0] + lift[lift > land[0]][0])
    for t1, contact in ((t_on, 1), (t_off, 0)):
        tag = f"restart_top_base_contact_{contact}"
        short = dict(full, run=dict(full["run"], t_end=float(t1), checkpoint="'mid.ck.h5'"))
        with open(os.path.join(work, "top_short.nml"), "w") as f:
            f.write(text(short))
        for ext in (".his", ".prf", ".evt", ".frg", ".h5", ".xmf"):
            if os.path.exists(os.path.join(work, "top_R" + ext)):
                os.remove(os.path.join(work, "top_R" + ext))
        r = run(exe, ["top_short.nml", "--output", "top_R", "-q"], work)
        check(r.returncode == 0, f"{tag}: run to t1 = {t1:.4f} s exits 0 ({r.stderr.strip()})")
        with h5py.File(os.path.join(work, "mid.ck.h5"), "r") as ck:
            got = int(ck["state"].attrs.get("base_contact_top", -1))
        check(got == contact, f"{tag}: the checkpoint's base_contact_top is {got}, not {contact}")
        r = run(exe, ["top_full.nml", "--output", "top_R", "--restart", "mid.ck.h5", "-q"], work)
        check(r.returncode == 0, f"{tag}: restart exits 0 ({r.stderr.strip()})")
        failures = check.failures
        same_outputs(check, tag, work, "top_U", "top_R")
        if check.failures == failures:
            print(f"ok   {tag}: from t = {t1:.4f} s, outputs byte- and bit-identical")


BAD = (  # (ends, initial, the words the message must hold)
    ("top = 'free', base_gap_top = 1e-3", "", ("&ends", "base_gap_top", "top = 'free'")),
    ("top = 'base', base_gap_top = -1e-3", "", ("&ends", "base_gap_top", ">= 0")),
    ("top = 'base', base_gap_top = 1e-3", "state = 'static'", ("&initial", "base_gap_top")),
    ("top = 'base'", "strain_rate = 1.0", ("&initial", "strain_rate")),
    ("bottom = 'base'", "state = 'static'", ("&initial", "gravity", "bottom = 'base'", "pull")),
)


def bad_input(check, exe, work):
    """Bad input about a base above the bar: exit 2, one line, no file."""
    for k, (ends, initial, words) in enumerate(BAD):
        name = f"bad_{k}"
        deck = (f"&run t_end = 1e-3, gravity = -9.81 /\n&mesh cells = 10 /\n"
                f"&segments n = 1, length = 1.0, young = 2e9, density = 2000 /\n"
                f"&ends {ends} /\n" + (f"&initial {initial} /\n" if initial else ""))
        for f in os.listdir(work):            # what an earlier run left
            if f.startswith(name + "."):
                os.remove(os.path.join(work, f))
        with open(os.path.join(work, name + ".nml"), "w") as f:
            f.write(deck)
        r = run(exe, [name + ".nml"], work)
        lines = r.stderr.strip().splitlines()
        written = [f for f in os.listdir(work) if f.startswith(name + ".") and f != name + ".nml"]
        ok = (r.returncode == 2 and len(lines) == 1 and all(w in lines[0] for w in words)
              and not written)
        check(ok, f"{name}: {ends} {initial}: exit {r.returncode}, {lines}, files {written}")
        if ok:
            print(f"ok   {name}: exit 2: {lines[0]}")


def main():
    exe, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(work, exist_ok=True)
    check = Checks()
    for name, deck in cases().items():
        outs = []
        for tag, d in (("below", deck), ("above", mirror(deck))):
            prefix = f"{name}_{tag}"
            with open(os.path.join(work, prefix + ".nml"), "w") as f:
                f.write(text(d))
            r = run(exe, [prefix + ".nml", "-q"], work)
            check(r.returncode == 0, f"{prefix}: exit {r.returncode}: {r.stderr.strip()}")
            outs.append(read(os.path.join(work, prefix + ".h5")) if r.returncode == 0 else None)
        if None in outs:
            continue
        worst = compare(check, name, *outs, spring="full_mass" in name)
        kinds = np.bincount(outs[0][1]["kind"], minlength=5)
        print(f"ok   {name}: {len(outs[0][1]['kind'])} events (by kind {kinds.tolist()}), "
              f"mirror deviation {worst:.1e} (bound {BOUND:.0e})")
    restart(check, exe, work, mirror(cases()["ex3_case1_accelerate_above_admissible"]))
    bad_input(check, exe, work)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
