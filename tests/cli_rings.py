#!/usr/bin/env python3
"""Characteristic stepping (issue 36, spb_ring) against the lattice: equal results.

Each deck is run twice, as it is (where an intact homogeneous breakable bar has a span of
steps without anything due, spb_ring stands in for the lattice's steps) and with
SPALLBAR_STEPPING=lattice (every step on the lattice arrays). They must give

  * the same events: step, node and kind of every row of PREFIX.evt, in order;
  * every value of PREFIX.his, .prf, .frg, .gau, .evt and .imp within 1e-12 of its scale:
    the column's largest magnitude, or its family's (energies and works; impulses and
    momenta; stresses; positions: the bar's length) for the columns that hold round-off
    only (ledger, ledger_w, e_lost_w, l_defect, x_drift, jordan, ...). The lattice's own
    round-off grows in its zig-zag mode by ~1e-16 a step, which the rings' exact shift has
    not: the tolerance is at least 2e-16 times the steps; and a deck with 10 events or more
    (each reads the fields and amplifies their round-off) is run once more on the lattice
    with its load one ulp larger: the tolerance is at least four times that difference;

and the comparison must be able to fail: the same outputs with one event moved by a step,
or one value moved by 1e-10 of its scale, are refused. The decks: a concrete spall bar
(triangular pulse on the free top, free bottom) at 1000 and 10000 cells with profiles and
a gauge, a Weibull strength field with the load on the bottom face, a fixed bottom under a
tensile pulse, a bar of two segments of one material, one whose history is written
every step (no span: the lattice's steps, bit for bit), one whose gauges are read every step
(their rows inside the spans read from the rings), one that breaks many times (rings
between the split nodes, fragments flying), one hanging under gravity, and a bar of three
materials (concrete, steel, concrete: rings meeting at the interfaces), breakable
(fractures, collisions, separations: the contact episodes' forces sampled from the rings;
also under the paper's rules and the delay timing) and unbreakable with a fixed bottom
(gauges reading sections). Each of those with gauges read every step and the last six must
differ from the lattice's in some bit (the characteristic steps ran). Restart: a run with
gauges read every step, checkpointed every K steps (span ends) and restarted from its middle
checkpoint, gives its outputs byte for byte.

usage: cli_rings.py SPALLBAR WORKDIR       (plain Python)
"""
import hashlib
import math
import re
import os
import shutil
import subprocess
import sys

from clitools import Checks, _value

TOL = 1.0e-12
# The lattice's own round-off feeds its zig-zag mode (values alternating from node to node),
# which grows linearly with the steps (doc/method.md, "Characteristic stepping"); the exact
# shift of the rings has none. Over a long run with events, which read the fields where the
# mode sits, the two differ by about 1e-16 a step: the tolerance is the larger of TOL and
# TOL_STEP times the run's steps.
TOL_STEP = 2.0e-16
C_CONCRETE = math.sqrt(35.0e9 / 2350.0)

BAR = """&run
  title = '{title}'
  t_end = {t_end!r}
  history_every = {every}
{run_extra}/
&mesh
  cells = {cells}
/
&segments
  n = {nseg}
  length = {length}
  young = {young}
  density = {density}
  strength = {strength}
/
&ends
  top = '{top}'
  bottom = '{bottom}'
/
&load
  kind = 'power'
  face = '{face}'
  p0 = {p0!r}
  t_k = {t_k!r}
  exponent = 1.0
/
{extra}"""

LAYERED = """&run
  title = '{title}'
  t_end = {t_end!r}
  history_every = {every}
  profile_times = 2.0e-4, 6.0e-4
{run_extra}/
&mesh
  dt = 1.0e-7
  fit = 'stretch'
/
&segments
  n = 3
  length = 0.4, 0.3, 0.5
  young = 35.0e9, 200.0e9, 35.0e9
  density = 2350.0, 7850.0, 2350.0
  strength = {strength}
/
&ends
  top = 'free'
  bottom = '{bottom}'
/
&load
  kind = 'power'
  face = 'top'
  p0 = 3.0e7
  t_k = 1.0e-4
  exponent = 1.0
/
&gauges
  x = 0.2, 0.55, 1.0
  every = 200
/
"""

# five gauges read every step: on nodes inside the rings (0.2, 0.55 m), in a cell (0.33341 m),
# in the scab (0.9 m) and on the rear face
GAUGES_EVERY_STEP = "&gauges\n  x = 0.2, 0.55, 0.33341, 0.9, 1.0\n  every = 1\n/\n"
# a hundred (nodes and cells about 0.01 m apart, the ends included): their readings fill a
# block of 3495 steps (spb_sim ring_gauge_values), so that a longer span takes several
MANY_GAUGES = ("&gauges\n  x = " + ", ".join([repr(round(0.01 * k + 0.00037 * (k % 3), 5))
                                            for k in range(99)] + ["1.0"]) +
               "\n  every = 1\n/\n")

# column families whose values may be round-off only: their scale is the family's
FAMILIES = {
    "energy": ("e_", "w_", "ledger"),
    "impulse": ("momentum", "i_", "p_shift"),
    "stress": ("reaction_", "s_end_", "stress"),
}


def deck_text(title, cells, t_transits, every, top="free", bottom="free", face="top",
              p0=20.0e6, nseg=1, strength="8.0e6", run_extra="", extra=""):
    """A concrete bar of 1 m (nseg equal segments) under a triangular pulse of 100 us."""
    seg = 1.0 / nseg
    return BAR.format(title=title, t_end=t_transits / C_CONCRETE, every=every,
                      run_extra=run_extra, cells=cells, nseg=nseg,
                      length=", ".join([repr(seg)] * nseg),
                      young=", ".join(["35.0e9"] * nseg),
                      density=", ".join(["2350.0"] * nseg),
                      strength=", ".join([strength] * nseg), top=top, bottom=bottom,
                      face=face, p0=p0, t_k=1.0e-4, extra=extra)


def history(path):
    """The columns of a text output by name: the names of its first line, the rows the lines
    that start with a blank (PREFIX.prf and .frg: the blocks of every time, one after the
    other)."""
    with open(path) as f:
        lines = f.read().splitlines()
    names = lines[0].split() if lines else []
    rows = [[_value(x) for x in line.split()] for line in lines[1:]
            if line.startswith(" ") and line.strip()]
    return {name: [r[k] for r in rows if k < len(r)] for k, name in enumerate(names)}


def run(exe, work, name, prefix, lattice, args=()):
    env = dict(os.environ)
    env.pop("SPALLBAR_STEPPING", None)
    if lattice:
        env["SPALLBAR_STEPPING"] = "lattice"
    return subprocess.run([exe, name + ".nml", "--output", prefix, "--quiet"] + list(args),
                          cwd=work, env=env, capture_output=True, text=True, timeout=1200)


def events(path):
    """(step, node, kind) of every event row."""
    t = history(path)
    if not t or "step" not in t:
        return []
    return list(zip([int(x) for x in t["step"]], [int(x) for x in t["node"]], t["kind"]))


def family_scales(table):
    """The largest magnitude over the columns of each family (FAMILIES: name -> scale)."""
    return {fam: max([abs(v) for col, vals in table.items()
                      if any(col.startswith(p) for p in prefixes)
                      for v in vals if isinstance(v, float) and math.isfinite(v)] + [0.0])
            for fam, prefixes in FAMILIES.items()}


def family_scale(table, name, scales=None):
    """The largest magnitude over the columns of name's family (0: none); scales: the
    table's family_scales, when made already."""
    for fam, prefixes in FAMILIES.items():
        if any(name.startswith(p) for p in prefixes):
            return (scales or family_scales(table))[fam]
    return 0.0


def compare(a, b, length=1.0, tol=TOL):
    """The differences between two tables (column -> values) beyond tol of their scales:
    a list of text lines (empty: equal)."""
    bad = []
    if set(a) != set(b):
        return [f"columns differ: {sorted(set(a) ^ set(b))}"]
    scales = family_scales(a)
    for name in a:
        x, y = a[name], b[name]
        if len(x) != len(y):
            bad.append(f"{name}: {len(x)} rows vs {len(y)}")
            continue
        nums = [(p, q) for p, q in zip(x, y) if isinstance(p, float) and isinstance(q, float)]
        if len(nums) != len(x):
            if [p for p in x if not isinstance(p, float)] != [q for q in y if not isinstance(q, float)]:
                bad.append(f"{name}: words differ")
            continue
        finite = [abs(v) for p, q in nums for v in (p, q) if math.isfinite(v)]
        scale = max(finite + [family_scale(a, name, scales)])
        if name.startswith("x") or name in ("l_defect", "overlap", "u", "opening", "shift"):
            scale = max(scale, length)
        if name == "jordan":
            scale = max(scale, 1.0)   # already relative to the momentum scale
        for k, (p, q) in enumerate(nums):
            if math.isnan(p) and math.isnan(q):
                continue
            if not abs(p - q) <= tol * scale:
                bad.append(f"{name}[{k}]: {p!r} vs {q!r} (scale {scale:.3e})")
                break
    return bad


def outputs(work, prefix):
    """Every text output of a run that exists, by extension."""
    out = {}
    for ext in (".his", ".prf", ".frg", ".gau", ".evt", ".imp"):
        path = os.path.join(work, prefix + ext)
        if os.path.exists(path):
            out[ext] = path
    return out


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def equal_runs(check, work, ring, lattice, sensitivity=None):
    """The checks of one deck; whether some output differs in a bit (the rings ran). With
    sensitivity (the lattice's own difference under a one-ulp change of the load, worst),
    the tolerance is at least four times it."""
    ra, la = outputs(work, ring), outputs(work, lattice)
    check(sorted(ra) == sorted(la), f"{ring}: the same outputs ({sorted(ra)} vs {sorted(la)})")
    ev_r, ev_l = events(ra[".evt"]), events(la[".evt"])
    check(ev_r == ev_l, f"{ring}: the same events (step, node, kind): {ev_r[:3]} vs {ev_l[:3]}")
    differs = False
    steps = max([int(x) for x in history(la[".his"]).get("step", [0])] + [0])
    tol = max(TOL, TOL_STEP * steps)
    if sensitivity is not None:
        tol = max(tol, 4.0 * sensitivity)
    far = 0.0
    for ext in sorted(set(ra) & set(la)):
        bad = compare(history(ra[ext]), history(la[ext]), tol=tol)
        check(not bad, f"{ring}{ext}: within {tol:.1e} of the lattice's: {bad[:3]}")
        far = max(far, worst(history(ra[ext]), history(la[ext])))
        differs = differs or sha(ra[ext]) != sha(la[ext])
    print(f"{ring}: worst difference from the lattice {far:.2e} of its column's scale "
          f"(tolerance {tol:.1e})")
    return ev_r, differs


def worst(a, b, length=1.0):
    """The largest difference of two tables relative to its column's scale (compare's)."""
    lo, hi = 0.0, 1.0
    if compare(a, b, length, tol=hi):
        return math.inf
    for _ in range(60):
        mid = math.sqrt(max(lo, 1e-18) * hi)
        if compare(a, b, length, tol=mid):
            lo = mid
        else:
            hi = mid
        if hi / max(lo, 1e-18) < 1.1:
            break
    return hi


def perturbed_load(text):
    """The deck with its load's p0 one ulp larger (the lattice's own sensitivity)."""
    def bump(m):
        return f"p0 = {float(m.group(1)) * (1.0 + 2.0 ** -52)!r}"
    return re.sub(r"p0 = ([-+0-9.eE]+)", bump, text, count=1)


def sensitivity_of(exe, work, name, text):
    """The lattice's worst difference over its outputs under a one-ulp change of p0."""
    with open(os.path.join(work, name + "_ulp.nml"), "w") as f:
        f.write(perturbed_load(text))
    p = run(exe, work, name + "_ulp", name + "_ulp", True)
    if p.returncode != 0:
        return math.inf
    la, ua = outputs(work, name + "_lattice"), outputs(work, name + "_ulp")
    return max([worst(history(ua[e]), history(la[e])) for e in sorted(set(la) & set(ua))] +
               [0.0])


def can_fail(check, work, ring, lattice):
    """The comparison refuses a one-step shift of an event and a value moved by 1e-10."""
    ev = events(os.path.join(work, lattice + ".evt"))
    if ev:
        shifted = [(ev[0][0] + 1,) + ev[0][1:]] + ev[1:]
        check(shifted != events(os.path.join(work, ring + ".evt")),
              "a one-step shift of the first event is seen")
    his = history(os.path.join(work, lattice + ".his"))
    moved = {k: list(v) for k, v in his.items()}
    k = len(moved["e_kin"]) // 2
    moved["e_kin"][k] += 1.0e-10 * max(abs(v) for v in moved["e_kin"])
    check(compare(history(os.path.join(work, ring + ".his")), moved),
          "a history value moved by 1e-10 of its scale is seen")
    moved = {k: list(v) for k, v in his.items()}
    moved["t"] = moved["t"][1:] + [moved["t"][-1]]
    check(compare(history(os.path.join(work, ring + ".his")), moved),
          "rows shifted by one are seen")


def main():
    exe, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    gauge = "&gauges\n  x = 0.5, 0.95\n  every = 250\n/\n"
    cases = [
        ("spall1k", deck_text("spall 1000 cells", 1000, 1.4, 50,
                              run_extra="  profile_times = 1.0e-4, 2.0e-4, 3.0e-4\n",
                              extra=gauge)),
        ("spall10k", deck_text("spall 10000 cells", 10000, 1.12, 2000,
                               run_extra="  profile_times = 2.5e-4\n")),
        ("weibull", deck_text("Weibull field, bottom load", 2000, 1.3, 100, face="bottom",
                              extra="&strength_field\n  kind = 'weibull'\n  modulus = 8.0\n"
                                    "  scale = 9.0e6\n  seed = 7\n/\n")),
        ("fixed", deck_text("fixed bottom, tensile pulse", 1500, 1.2, 64, bottom="fixed",
                            p0=-6.0e6)),
        ("fixed_top", deck_text("fixed top, tensile pulse on the free bottom", 1200, 1.3, 75,
                                top="fixed", face="bottom", p0=-6.0e6)),
        ("two_segments", deck_text("two segments of one material", 1600, 1.3, 80, nseg=2)),
        ("every_step", deck_text("history every step", 600, 1.2, 1)),
        # gauges every step (a lab's signals), history rows seldom: the rows inside each span
        # read from the rings (on the rear face, on nodes and inside cells of the rings)
        ("gauges_every_step", deck_text("gauges every step", 3000, 1.15, 4000,
                                        extra=GAUGES_EVERY_STEP)),
        # (one transit: before the first fracture)
        ("many_gauges", deck_text("a hundred gauges every step", 3600, 1.0, 5000,
                                  extra=MANY_GAUGES)),
        # after the first fracture: rings between the split nodes, fragments flying and
        # colliding (the contact episodes' forces sampled), many events
        ("many_breaks", deck_text("many fractures", 4000, 8.0, 100, strength="3.0e6",
                                  p0=4.0e7)),
        # gravity: a bar hanging from a fixed top, a tensile pulse on its free bottom
        ("hanging", deck_text("hanging under gravity", 3000, 2.5, 100, top="fixed",
                              face="bottom", p0=-6.0e6, run_extra="  gravity = 9.81\n")),
        # three segments: rings meeting at the interfaces; breakable concrete, steel between
        ("layered", LAYERED.format(title="concrete, steel, concrete", t_end=2.4e-3, every=60,
                                   strength="7.0e6, -1.0, 7.0e6",
                                   bottom="free", run_extra="")),
        # the same under the paper's event rules, and under the delay timing (its nodes
        # joined at t^{n+1} start their section test late: the lattice takes those steps)
        ("layered_paper", LAYERED.format(title="paper rules", t_end=2.4e-3, every=60,
                                         strength="7.0e6, -1.0, 7.0e6", bottom="free",
                                         run_extra="  events = 'paper'\n")),
        ("layered_delay", LAYERED.format(title="delay timing", t_end=2.4e-3, every=60,
                                         strength="7.0e6, -1.0, 7.0e6", bottom="free",
                                         run_extra="  timing = 'delay'\n")),
        # the same unbreakable, the bottom fixed: no fracture test, gauges read sections
        ("layered_intact", LAYERED.format(title="unbreakable, fixed bottom", t_end=2.4e-3,
                                          every=60, strength="-1.0, -1.0, -1.0",
                                          bottom="fixed", run_extra="")),
    ]
    any_differs = False
    for name, text in cases:
        with open(os.path.join(work, name + ".nml"), "w") as f:
            f.write(text)
        p = run(exe, work, name, name + "_rings", False)
        q = run(exe, work, name, name + "_lattice", True)
        ok = p.returncode == 0 and q.returncode == 0
        check(ok, f"{name}: both runs exit 0 ({p.stderr.strip()[:200]} {q.stderr.strip()[:200]})")
        if not ok:
            continue
        sens = None
        if len(events(os.path.join(work, name + "_lattice.evt"))) >= 10:
            # many events: each reads the fields, and the run's own round-off is amplified
            sens = sensitivity_of(exe, work, name, text)
            print(f"{name}: the lattice's own difference under a one-ulp load: {sens:.2e}")
        ev, differs = equal_runs(check, work, name + "_rings", name + "_lattice", sens)
        if name not in ("layered_intact", "many_gauges"):
            check(len(ev) > 0, f"{name}: the bar breaks")
        kinds = [k for _, _, k in ev]
        if name == "many_breaks":
            check(kinds.count("fracture") >= 5, f"{name}: many fractures ({len(kinds)})")
        if name in ("layered", "layered_paper", "layered_delay"):
            check({"fracture", "collision", "separation"} <= set(kinds),
                  f"{name}: fractures, collisions, separations ({sorted(set(kinds))})")
        print(f"{name}: {len(ev)} events, first {ev[:1]}; differs from the lattice in some "
              f"bit: {differs}")
        if name == "every_step":
            check(not differs, "history every step: no span, the lattice's bits")
        elif name in ("many_breaks", "hanging", "layered", "layered_paper", "layered_delay",
                      "layered_intact", "gauges_every_step", "many_gauges"):
            check(differs, f"{name}: the characteristic steps ran (some bit differs)")
        any_differs = any_differs or differs
        if name == "spall1k":
            can_fail(check, work, name + "_rings", name + "_lattice")
    check(any_differs, "the characteristic steps ran (some deck differs in some bit)")
    restart(check, exe, work)
    return check.finish()


def restart(check, exe, work):
    """Checkpoints every 400 steps (where a span ends) and a restart from the middle one give
    the uninterrupted run's outputs byte for byte."""
    name = "rck"
    # (gauges every step: their rows inside the spans read from the rings)
    text = deck_text("restart", 1000, 1.3, 100,
                     run_extra=f"  checkpoint = '{name}.ck.h5'\n  checkpoint_every = 400\n",
                     extra=GAUGES_EVERY_STEP)
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(text)
    p = run(exe, work, name, name + "_u", False)
    check(p.returncode == 0, f"restart: uninterrupted run ({p.stderr.strip()[:300]})")
    shutil.copy(os.path.join(work, name + ".ck.h5"), os.path.join(work, name + "_end.ck.h5"))
    # the run stopped at step 800 by a shorter t_end keeps the checkpoint of step 800
    short = text.replace(f"t_end = {1.3 / C_CONCRETE!r}", f"t_end = {800 / (1000 * C_CONCRETE)!r}")
    with open(os.path.join(work, name + "_s.nml"), "w") as f:
        f.write(short)
    p = run(exe, work, name + "_s", name + "_r", False)
    check(p.returncode == 0, f"restart: run to step 800 ({p.stderr.strip()[:300]})")
    p = run(exe, work, name, name + "_r", False, ["--restart", name + ".ck.h5"])
    check(p.returncode == 0, f"restart: from step 800 ({p.stderr.strip()[:300]})")
    for ext in (".his", ".evt", ".frg", ".spl", ".gau"):
        a, b = os.path.join(work, name + "_u" + ext), os.path.join(work, name + "_r" + ext)
        check(os.path.exists(a) and os.path.exists(b) and sha(a) == sha(b),
              f"restart: {ext} equals the uninterrupted run's")


if __name__ == "__main__":
    sys.exit(main())
