#!/usr/bin/env python3
"""Characteristic stepping (issue 36, spb_ring) against the lattice: equal results.

Each deck is run twice, as it is (where an intact homogeneous breakable bar has a span of
steps without anything due, spb_ring stands in for the lattice's steps) and with
SPALLBAR_STEPPING=lattice (every step on the lattice arrays). They must give

  * the same events: step, node and kind of every row of PREFIX.evt, in order;
  * every value of PREFIX.his, .prf, .frg, .gau and .evt within 1e-12 of its scale: the
    column's largest magnitude, or its family's (energies and works; impulses and momenta;
    stresses; positions: the bar's length) for the columns that hold round-off only
    (ledger, ledger_w, e_lost_w, l_defect, x_drift, jordan, ...);

and the comparison must be able to fail: the same outputs with one event moved by a step,
or one value moved by 1e-10 of its scale, are refused. The decks: a concrete spall bar
(triangular pulse on the free top, free bottom) at 1000 and 10000 cells with profiles and
a gauge, a Weibull strength field with the load on the bottom face, a fixed bottom under a
tensile pulse, a bar of two segments of one material, and one whose history is written
every step (no span: the lattice's steps, bit for bit). At least one deck must differ from
the lattice's in some bit (the characteristic steps ran). Restart: a run checkpointed every
K steps (span ends) and restarted from its middle checkpoint gives its outputs byte for
byte.

usage: cli_rings.py SPALLBAR WORKDIR       (plain Python)
"""
import hashlib
import math
import os
import shutil
import subprocess
import sys

from clitools import Checks, _value

TOL = 1.0e-12
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

# column families whose values may be round-off only: their scale is the family's
FAMILIES = {
    "energy": ("e_", "w_", "ledger"),
    "impulse": ("momentum", "i_", "p_shift"),
    "stress": ("reaction_", "s_end_"),
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


def family_scale(table, name):
    """The largest magnitude over the columns of name's family (0: none)."""
    for prefixes in FAMILIES.values():
        if any(name.startswith(p) for p in prefixes):
            return max([abs(v) for col, vals in table.items()
                        if any(col.startswith(p) for p in prefixes)
                        for v in vals if isinstance(v, float) and math.isfinite(v)] + [0.0])
    return 0.0


def compare(a, b, length=1.0):
    """The differences between two tables (column -> values) beyond TOL of their scales:
    a list of text lines (empty: equal)."""
    bad = []
    if set(a) != set(b):
        return [f"columns differ: {sorted(set(a) ^ set(b))}"]
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
        scale = max(finite + [family_scale(a, name)])
        if name.startswith("x") or name in ("l_defect", "overlap", "u", "opening"):
            scale = max(scale, length)
        if name == "jordan":
            scale = max(scale, 1.0)   # already relative to the momentum scale
        for k, (p, q) in enumerate(nums):
            if math.isnan(p) and math.isnan(q):
                continue
            if not abs(p - q) <= TOL * scale:
                bad.append(f"{name}[{k}]: {p!r} vs {q!r} (scale {scale:.3e})")
                break
    return bad


def outputs(work, prefix):
    """Every text output of a run that exists, by extension."""
    out = {}
    for ext in (".his", ".prf", ".frg", ".gau", ".evt"):
        path = os.path.join(work, prefix + ext)
        if os.path.exists(path):
            out[ext] = path
    return out


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def equal_runs(check, work, ring, lattice):
    """The checks of one deck; whether some output differs in a bit (the rings ran)."""
    ra, la = outputs(work, ring), outputs(work, lattice)
    check(sorted(ra) == sorted(la), f"{ring}: the same outputs ({sorted(ra)} vs {sorted(la)})")
    ev_r, ev_l = events(ra[".evt"]), events(la[".evt"])
    check(ev_r == ev_l, f"{ring}: the same events (step, node, kind): {ev_r[:3]} vs {ev_l[:3]}")
    differs = False
    for ext in sorted(set(ra) & set(la)):
        bad = compare(history(ra[ext]), history(la[ext]))
        check(not bad, f"{ring}{ext}: within {TOL:.0e} of the lattice's: {bad[:3]}")
        differs = differs or sha(ra[ext]) != sha(la[ext])
    return ev_r, differs


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
        ev, differs = equal_runs(check, work, name + "_rings", name + "_lattice")
        check(len(ev) > 0, f"{name}: the bar breaks")
        print(f"{name}: {len(ev)} events, first {ev[:1]}; differs from the lattice in some "
              f"bit: {differs}")
        if name == "every_step":
            check(not differs, "history every step: no span, the lattice's bits")
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
    text = deck_text("restart", 1000, 1.3, 100,
                     run_extra=f"  checkpoint = '{name}.ck.h5'\n  checkpoint_every = 400\n")
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
    for ext in (".his", ".evt", ".frg", ".spl"):
        a, b = os.path.join(work, name + "_u" + ext), os.path.join(work, name + "_r" + ext)
        check(os.path.exists(a) and os.path.exists(b) and sha(a) == sha(b),
              f"restart: {ext} equals the uninterrupted run's")


if __name__ == "__main__":
    sys.exit(main())
