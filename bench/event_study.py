#!/usr/bin/env python3
"""Event-layer study of spallbar: energy, ledger, momentum, events, overlaps on fixed decks.

    event_study.py --exe PATH/spallbar --work DIR [--energy-column NAME] [--only NAME,...]
                   [--json OUT.json] [--jobs K] [--label TEXT] [--list]

A measurement, not a test (issue 17; doc/benchmarks.md, "The event study", says how to run
it and doc/validation.md, "The event layer", what it found): `make event-study` runs it on the
Release program in the wave measure (--energy-column e_wave), in a few seconds; the checks
that run in CI are tests/cli_event_layer.py's.

Writes a fixed set of decks into DIR (from the strings below), runs each with
`spallbar DECK --output DIR/NAME --quiet`, reads NAME.his / .evt / .prf by their headers
(doc/outputs.md) and prints

1. one row per run: exit status, wall time, events by kind, the energy excess
   max_rows (E - E0 - w_ext)/scale (E = e_kin + e_strain + e_pot, or NAME + e_pot with
   --energy-column NAME; with e_wave the wave measure e_wave + e_pot + e_wave_g, and w_wave,
   e_lost_w, ledger_w for w_ext, e_lost, ledger), the same in J/m^2, the excess at t_end,
   the final E/E0 (E0 includes e_pot, so it can be 0 or negative with a static state), the
   largest decrease of e_lost between rows (/scale; <= 0 when e_lost never decreases), the ledger drift (/scale), the
   final momentum and the largest momentum-balance residual, the largest overlap of split
   faces u(A_i) - u(B_i) in the profiles (/dx), the largest base penetration (/dx);
2. the Galilean (gal0 vs gal0_v3) and mirror (gal0 vs gal0_mirror) comparisons per
   timing x shift.

scale = max(e_kin + |e_strain| at row 0, max |w_ext|, 1e-300) (the energy guard's scale).
Every deck gets `profile_times` = 0 plus 20 evenly spaced times in (0, t_end]; the t = 0
block gives the initial u(A_N) for the penetration reference (u_base = u_A(N)(0) + base_gap)
and is included in the overlap maximum (where it is 0 unless the initial state overlaps).

--only takes run names or shell patterns (gal0_*_above, case2_*). --json writes every
number, the decks and the per-run notes. Exit status 0, also when a run ends with status 3
(reported in the table), 1 when a run could not start (the executable failed to launch or
refused the deck with status 2), 2 for bad arguments.

Needs python3 and numpy (the project's .venv has it).
"""
import argparse
import concurrent.futures
import fnmatch
import json
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CASE2_DIR = os.path.join(ROOT, "input", "example3_case2")

TIMINGS = ("accelerate", "delay", "min")
SHIFTS = ("above", "fragment")
EVENT_KINDS = ("fracture", "collision", "separation", "base-collision")
N_PROFILES = 20          # evenly spaced in (0, t_end]; plus t = 0 (profile_times allows 100)

# --------------------------------------------------------------------------- decks
# Each deck is a list of lines; the &run line is the first and gets profile_times appended.
# {timing}, {shift}: filled per variant.


def _deck(run, *rest):
    return {"run": run, "rest": list(rest)}


def build_decks():
    """Return an ordered dict name -> dict(run=..., rest=[...], t_end=...)."""
    decks = {}
    decks["pair"] = _deck(
        "&run t_end=0.04, timing='accelerate', energy_guard=0",
        "&mesh dt=1e-5 /",
        "&segments n=2, length=0.01,0.01, young=2e9,2e9, density=2000,2000, strength=0,0, "
        "velocity=1,-1 /")
    decks["pair"]["t_end"] = 0.04
    for name, timing in (("column_acc", "accelerate"), ("column_delay", "delay")):
        decks[name] = _deck(
            "&run t_end=0.03, timing='%s', energy_guard=0" % timing,
            "&mesh dt=1e-5 /",
            "&segments n=1, length=1.2, young=1.8e10, density=2000, strength=0, velocity=-0.1 /",
            "&ends top='fixed', bottom='base' /")
        decks[name]["t_end"] = 0.03

    gal_seg = ("n=3, length=0.84,0.45,1.6, young=29.4e9,9.1125e9,67.5e9, "
               "density=2400,1800,2700, strength=1.2e6,0.6e6,2.5e6")
    gal_seg_mirror = ("n=3, length=1.6,0.45,0.84, young=67.5e9,9.1125e9,29.4e9, "
                      "density=2700,1800,2400, strength=2.5e6,0.6e6,1.2e6")
    gal_load = "kind='power', face='%s', p0=5e6, t_k=4e-3, exponent=1, t_cut=3e-3"
    variants = (
        ("gal0", "", gal_seg, "top"),
        ("gal0_v3", "", gal_seg + ", velocity=3,3,3", "top"),
        ("gal0_g", ", gravity=9.81", gal_seg, "top"),
        ("gal0_mirror", "", gal_seg_mirror, "bottom"),
    )
    for base, run_extra, seg, face in variants:
        for timing in TIMINGS:
            for shift in SHIFTS:
                name = "%s_%s_%s" % (base, timing, shift)
                decks[name] = _deck(
                    "&run t_end=4e-3, timing='%s', shift='%s', energy_guard=0%s"
                    % (timing, shift, run_extra),
                    "&mesh dt=8e-6 /",
                    "&segments %s /" % seg,
                    "&ends top='free', bottom='free' /",
                    "&load %s /" % (gal_load % face))
                decks[name]["t_end"] = 4e-3
                decks[name]["family"] = base
                decks[name]["timing"], decks[name]["shift"] = timing, shift

    decks["hang"] = _deck(
        "&run t_end=1.5, gravity=9.81, timing='delay', energy_guard=0",
        "&mesh cells=40 /",
        "&segments n=1, length=10, young=5e7, density=1700, strength=0 /",
        "&ends top='fixed', bottom='base' /",
        "&initial state='static' /")
    decks["hang"]["t_end"] = 1.5

    for timing in TIMINGS:
        for shift in SHIFTS:
            name = "case2_h95_%s_%s" % (timing, shift)
            decks[name] = {"file": os.path.join(CASE2_DIR, "%s_%s_h95.nml" % (timing, shift))}
    return decks


def profile_times(t_end):
    times = [0.0] + [t_end * k / N_PROFILES for k in range(1, N_PROFILES + 1)]
    return ", ".join("%.15g" % t for t in times)


_RUN_VAR = re.compile(r"^\s*([A-Za-z_]\w*)\s*=")


def patch_file_deck(text):
    """A copied deck (one variable per line in &run): set energy_guard = 0 and our
    profile_times, replacing the lines that give them (a variable twice is refused)."""
    lines = text.splitlines()
    out, in_run, t_end, seen = [], False, None, set()
    start = None
    for line in lines:
        code = line.split("!", 1)[0]
        if re.match(r"^\s*&run\b", code, re.I):
            in_run = True
            start = len(out)
            if "/" in code or "=" in code:
                raise ValueError("copied deck: &run must hold one variable per line")
            out.append(line)
            continue
        if in_run:
            if re.match(r"^\s*/\s*$", code):
                in_run = False
                out.append(line)
                continue
            m = _RUN_VAR.match(code)
            if m and code.count("=") > 1 and "'" not in code and '"' not in code:
                raise ValueError("copied deck: &run must hold one variable per line")
            if m:
                var = m.group(1).lower()
                if var == "t_end":
                    t_end = float(code.split("=", 1)[1].strip().rstrip(",").replace("d", "e"))
                if var in ("energy_guard", "profile_times"):
                    seen.add(var)
                    out.append("  energy_guard = 0" if var == "energy_guard"
                               else "  profile_times = @PT@")
                    continue
        out.append(line)
    if start is None or t_end is None:
        raise ValueError("copied deck: no &run group with t_end")
    extra = []
    if "energy_guard" not in seen:
        extra.append("  energy_guard = 0")
    if "profile_times" not in seen:
        extra.append("  profile_times = @PT@")
    out[start + 1:start + 1] = extra
    return "\n".join(out).replace("@PT@", profile_times(t_end)) + "\n", t_end


def deck_text(spec):
    if "file" in spec:
        with open(spec["file"]) as f:
            text, t_end = patch_file_deck(f.read())
        return text, t_end
    t_end = spec["t_end"]
    run = "%s, profile_times=%s /" % (spec["run"], profile_times(t_end))
    return "\n".join([run] + spec["rest"]) + "\n", t_end


# --------------------------------------------------------------------------- readers
def read_table(path, want_names_start="t"):
    """Header column names (the last '#' line before the first row, doc/outputs.md) and
    the rows as lists of tokens (rows with the wrong token count are skipped)."""
    names, rows, header, last = None, [], [], None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                header.append(line.rstrip("\n"))
                last = line[1:].split()
                continue
            if names is None:
                names = last
            tok = line.split()
            if names is not None and len(tok) == len(names):
                rows.append(tok)
    if names is None:
        names = last
    if not names or names[0] != want_names_start:
        raise ValueError("%s: the last header line is not the column names" % path)
    return names, rows, header


def header_echo(header):
    """Echoed deck values: {(group, var): 'value text'} and the mesh segment lines."""
    echo, group, segs = {}, None, []
    for line in header:
        s = line[1:].strip()
        m = re.match(r"^&(\w+)$", s)
        if m:
            group = m.group(1).lower()
            continue
        if s == "/":
            group = None
            continue
        if group:
            m = re.match(r"^(\w+)\s*=\s*(.*?)\s*(!.*)?$", s)
            if m:
                echo[(group, m.group(1).lower())] = m.group(2)
        m = re.match(r"^segment\s+(\d+):\s*cells\s+(\d+)\.\.(\d+),\s*dx = a dt = (\S+) m,"
                     r"\s*a = (\S+) m/s,\s*Z = (\S+) kg", s)
        if m:
            segs.append(dict(j=int(m.group(1)), c0=int(m.group(2)), c1=int(m.group(3)),
                             dx=float(m.group(4)), a=float(m.group(5)), Z=float(m.group(6))))
        m = re.match(r"^mesh: dt = (\S+) s", s)
        if m:
            echo[("mesh", "dt_built")] = m.group(1)
    return echo, segs


def read_his(path):
    names, rows, header = read_table(path)
    if names is None:
        return None, None, header
    a = np.array([[float(x) for x in r] for r in rows], dtype=float).reshape(-1, len(names))
    return {n: a[:, k] for k, n in enumerate(names)}, names, header


def read_evt(path):
    names, rows, header = read_table(path)
    ev = []
    if names is None:
        return ev, header
    ik, ist, ino, it = names.index("kind"), names.index("step"), names.index("node"), \
        names.index("t")
    for r in rows:
        ev.append((int(r[ist]), int(r[ino]), r[ik], float(r[it])))
    return ev, header


def read_prf(path):
    """List of (t, step, array rows x 4 [x u v stress])."""
    blocks, cur, t, step = [], None, None, None
    with open(path) as f:
        for line in f:
            if line.startswith("# t = "):
                if cur is not None:
                    blocks.append((t, step, cur))
                t, step, cur = float(line.split("=", 1)[1]), None, []
                continue
            if line.startswith("# step ") and cur is not None:
                step = int(line.split()[2].rstrip(","))
                continue
            if line.startswith("#"):
                continue
            tok = line.split()
            if cur is not None and len(tok) in (4, 5):     # x u v stress [t]
                cur.append([float(x) for x in tok[:4]])
    if cur is not None:
        blocks.append((t, step, cur))
    return [(t, s, np.array(r, dtype=float).reshape(-1, 4)) for t, s, r in blocks]


# --------------------------------------------------------------------------- metrics
def fnum(x):
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else str(x)


def analyse(prefix, energy_column, notes):
    res = {}
    his, names, header = read_his(prefix + ".his")
    if his is None:
        notes.append("no history rows")
        return res
    echo, segs = header_echo(header)
    res["rows"] = int(len(his["t"]))
    res["t_final"] = fnum(his["t"][-1])
    res["steps"] = int(his["step"][-1]) if "step" in his else None
    dt = float(echo.get(("mesh", "dt_built"), "nan"))
    mass = sum(s["Z"] * dt * (s["c1"] - s["c0"] + 1) for s in segs) if segs else None
    res["mass"] = fnum(mass)
    res["columns"] = names
    # kinetic energy the deck asks for, 1/2 sum_j m_j v_j^2 (m_j from the mesh), against row 0
    vel = echo.get(("segments", "velocity"))
    if segs and vel is not None and "e_kin" in his:
        try:
            v = [float(x.replace("d", "e")) for x in vel.split(",")]
            if len(v) == 1:
                v = v * len(segs)
            ek = sum(0.5 * sg["Z"] * dt * (sg["c1"] - sg["c0"] + 1) * vj ** 2
                     for sg, vj in zip(segs, v))
            res["e_kin_deck"] = fnum(ek)
            if abs(his["e_kin"][0] - ek) > 1e-12 * max(ek, 1e-300):
                notes.append("row-0 e_kin = %.6g J/m^2, deck 1/2 sum m_j v_j^2 = %.6g"
                             % (his["e_kin"][0], ek))
        except ValueError:
            pass

    # energies
    need = ("e_kin", "e_strain", "e_pot", "w_ext")
    if all(k in his for k in need):
        e_pot = his["e_pot"]
        wave = energy_column == "e_wave" and all(k in his for k in ("e_wave", "e_wave_g", "w_wave", "e_lost_w", "ledger_w"))
        if wave:
            # the wave measure (doc/outputs.md): its own work, losses and ledger
            e = his["e_wave"] + e_pot + his["e_wave_g"]
            res["energy_measure"] = "e_wave + e_pot + e_wave_g (w_wave, e_lost_w, ledger_w)"
            his = dict(his)
            his["w_ext"] = his["w_wave"]
            his["e_lost"] = his["e_lost_w"]
            his["ledger"] = his["ledger_w"]
            his["e_kin"] = his["e_wave"]
            his["e_strain"] = 0.0 * his["e_wave"]
        elif energy_column:
            if energy_column in his:
                e = his[energy_column] + e_pot
                res["energy_measure"] = energy_column + " + e_pot"
            else:
                notes.append("column %r not in .his: used e_kin + e_strain + e_pot" % energy_column)
                e = his["e_kin"] + his["e_strain"] + e_pot
                res["energy_measure"] = "e_kin + e_strain + e_pot"
        else:
            e = his["e_kin"] + his["e_strain"] + e_pot
            res["energy_measure"] = "e_kin + e_strain + e_pot"
        w = his["w_ext"]
        scale = max(his["e_kin"][0] + abs(his["e_strain"][0]), float(np.max(np.abs(w))), 1e-300)
        exc = e - e[0] - w
        k = int(np.argmax(exc))
        res["scale"] = fnum(scale)
        res["E0"] = fnum(e[0])
        res["E_final"] = fnum(e[-1])
        res["excess_rel"] = fnum(exc[k] / scale)
        res["excess_abs"] = fnum(exc[k])
        res["excess_t"] = fnum(his["t"][k])
        res["E_over_E0"] = fnum(e[-1] / e[0]) if e[0] != 0 else None
        res["excess_end_rel"] = fnum(exc[-1] / scale)
        res["e_kin_final"] = fnum(his["e_kin"][-1])
        if "e_lost" in his and len(w) > 1:
            d = -np.diff(his["e_lost"])
            k = int(np.argmax(d))
            res["e_lost_max_decrease_rel"] = fnum(d[k] / scale)
            res["e_lost_max_decrease_t"] = fnum(his["t"][k + 1])
            res["e_lost_final"] = fnum(his["e_lost"][-1])
        elif "e_lost" not in his:
            notes.append("no e_lost column")
        if "ledger" in his:
            dl = np.abs(his["ledger"] - his["ledger"][0])
            res["ledger_drift_rel"] = fnum(np.max(dl) / scale)
        else:
            notes.append("no ledger column")
    else:
        notes.append("energy columns missing: %s" % [k for k in need if k not in his])

    # momentum balance (doc/outputs.md): momentum - momentum(0) = i_gravity + i_ends
    # + i_support + p_shift
    if "momentum" in his:
        p = his["momentum"]
        res["momentum_final"] = fnum(p[-1])
        res["momentum_initial"] = fnum(p[0])
        for c in ("i_gravity", "i_ends", "i_support", "p_shift"):
            if c in his:
                res[c + "_final"] = fnum(his[c][-1])
        parts = [c for c in ("i_gravity", "i_ends", "i_support", "p_shift") if c in his]
        missing = [c for c in ("i_gravity", "i_ends", "i_support", "p_shift") if c not in his]
        if missing:
            notes.append("momentum balance without %s" % missing)
        rhs = sum((his[c] for c in parts), np.zeros_like(p))
        bal = p - p[0] - rhs
        k = int(np.argmax(np.abs(bal)))
        pscale = max(abs(p[0]), float(np.max(np.abs(p))),
                     max((float(np.max(np.abs(his[c]))) for c in parts), default=0.0), 1e-300)
        res["momentum_balance_abs"] = fnum(bal[k])
        res["momentum_balance_rel"] = fnum(abs(bal[k]) / pscale)
        res["momentum_balance_t"] = fnum(his["t"][k])
        res["momentum_scale"] = fnum(pscale)
    else:
        notes.append("no momentum column")

    # events
    ev, _ = read_evt(prefix + ".evt")
    counts = {k: 0 for k in EVENT_KINDS}
    for _, _, kind, _ in ev:
        counts[kind] = counts.get(kind, 0) + 1
    other = sorted(set(counts) - set(EVENT_KINDS))
    if other:
        notes.append("unknown event kinds %s" % other)
    res["events"] = counts
    res["events_total"] = len(ev)

    # profiles: overlap of split faces and base penetration
    blocks = read_prf(prefix + ".prf")
    res["profiles"] = len(blocks)
    if blocks:
        rows = blocks[0][2].shape[0]
        n = rows // 2
        x = blocks[0][2][:, 0]
        # row r: r = 0 -> B_0; A_i -> 2i-1; B_i -> 2i (i < N); A_N -> 2N-1
        xnode = np.concatenate(([x[0]], x[1::2]))        # x_0 .. x_N
        dxc = np.diff(xnode)                               # cell k = 1..N -> dxc[k-1]
        best = (-np.inf, None, None)
        for t, step, a in blocks:
            if a.shape[0] != rows:
                notes.append("profile at t=%g has %d rows, first had %d" % (t, a.shape[0], rows))
                continue
            if n >= 2:
                ua = a[1:2 * n - 2:2, 1]                  # A_1 .. A_{N-1}
                ub = a[2:2 * n - 1:2, 1]                  # B_1 .. B_{N-1}
                dxn = np.minimum(dxc[:-1], dxc[1:])        # min of the cells either side
                ov = (ua - ub) / dxn
                k = int(np.argmax(ov))
                if ov[k] > best[0]:
                    best = (float(ov[k]), t, k + 1)
        res["overlap_dx"] = fnum(max(best[0], 0.0)) if best[1] is not None else None
        res["overlap_t"] = fnum(best[1]) if best[0] > 0 else None
        res["overlap_node"] = best[2] if best[0] > 0 else None
        bottom = echo.get(("ends", "bottom"), "").strip("'\"")
        if bottom == "base":
            gap = float(echo.get(("ends", "base_gap"), "0").replace("d", "e"))
            t0, _, a0 = blocks[0]
            if t0 != 0.0:
                notes.append("first profile not at t = 0: u_A(N)(0) taken as 0")
                ua0 = 0.0
            else:
                ua0 = float(a0[-1, 1])
            u_base = ua0 + gap
            pen = [(float(a[-1, 1]) - u_base, t) for t, _, a in blocks if a.shape[0] == rows]
            k = int(np.argmax([p for p, _ in pen]))
            res["u_base"] = fnum(u_base)
            res["penetration_dx"] = fnum(max(pen[k][0], 0.0) / dxc[-1])
            res["penetration_raw_dx"] = fnum(pen[k][0] / dxc[-1])
            res["penetration_t"] = fnum(pen[k][1])
    return res


# --------------------------------------------------------------------------- running
def run_one(exe, work, name, text):
    deck = os.path.join(work, name + ".nml")
    with open(deck, "w") as f:
        f.write(text)
    prefix = os.path.join(work, name)
    for ext in (".his", ".prf", ".evt", ".frg", ".h5"):
        if os.path.exists(prefix + ext):
            os.remove(prefix + ext)
    t0 = time.perf_counter()
    try:
        p = subprocess.run([exe, deck, "--output", prefix, "--quiet"], capture_output=True,
                           text=True)
    except OSError as e:
        return dict(name=name, started=False, rc=None, wall=0.0, stderr=str(e))
    wall = time.perf_counter() - t0
    return dict(name=name, started=p.returncode != 2, rc=p.returncode, wall=wall,
                stderr=p.stderr.strip()[-2000:])


def compare(results):
    """Galilean and mirror comparisons per timing x shift."""
    out = []
    for timing in TIMINGS:
        for shift in SHIFTS:
            tag = "%s_%s" % (timing, shift)
            c = {"case": tag}
            r0 = results.get("gal0_" + tag)
            r3 = results.get("gal0_v3_" + tag)
            rm = results.get("gal0_mirror_" + tag)
            if r0 is None or not r0.get("ok"):
                continue
            if r3 is not None and r3.get("ok"):
                e0, e3 = r0["_evt"], r3["_evt"]
                k0 = [(s, nd, k) for s, nd, k, _ in e0]
                k3 = [(s, nd, k) for s, nd, k, _ in e3]
                c["gal_events_identical"] = k0 == k3
                c["gal_events"] = [len(k0), len(k3)]
                first = next((i for i, (a, b) in enumerate(zip(k0, k3)) if a != b), None)
                if first is None and len(k0) != len(k3):
                    first = min(len(k0), len(k3))
                c["gal_first_difference"] = None if first is None else {
                    "index": first,
                    "gal0": list(k0[first]) if first < len(k0) else None,
                    "gal0_v3": list(k3[first]) if first < len(k3) else None}
                b0, b3 = r0["_prf"], r3["_prf"]
                if len(b0) == len(b3) and all(a[2].shape == b[2].shape for a, b in zip(b0, b3)):
                    s0 = np.concatenate([a[2][:, 3] for a in b0])
                    s3 = np.concatenate([a[2][:, 3] for a in b3])
                    smax = max(float(np.max(np.abs(s0))), 1e-300)
                    c["gal_stress_reldiff"] = fnum(np.max(np.abs(s3 - s0)) / smax)
                else:
                    c["gal_stress_reldiff"] = None
                m = r0["metrics"].get("mass")
                p0 = r0["metrics"].get("momentum_final")
                p3 = r3["metrics"].get("momentum_final")
                if m and p0 is not None and p3 is not None:
                    c["mass"] = m
                    c["gal_momentum_diff_minus_3M"] = fnum(p3 - p0 - 3.0 * m)
                    c["gal_momentum_rel"] = fnum(abs(p3 - p0 - 3.0 * m) / (3.0 * m))
            if rm is not None and rm.get("ok"):
                ev0, evm = r0["metrics"]["events"], rm["metrics"]["events"]
                c["mirror_counts"] = [ev0, evm]
                c["mirror_counts_equal"] = all(ev0.get(k, 0) == evm.get(k, 0)
                                               for k in set(ev0) | set(evm))
                ek0 = r0["metrics"].get("e_kin_final")
                ekm = rm["metrics"].get("e_kin_final")
                if ek0 is not None and ekm is not None:
                    c["mirror_ekin_final"] = [ek0, ekm]
                    c["mirror_ekin_reldiff"] = fnum(abs(ekm - ek0) / max(abs(ek0), 1e-300))
            out.append(c)
    return out


# --------------------------------------------------------------------------- printing
def g(x, w=10, p=2):
    if x is None:
        return "-".rjust(w)
    if isinstance(x, str):
        return x.rjust(w)
    return ("%.*e" % (p, x)).rjust(w)


MAIN_COLS = [
    ("run", 31), ("rc", 3), ("wall", 6), ("frac", 6), ("coll", 6), ("sep", 6), ("base", 5),
    ("exc", 10), ("exc_abs", 10), ("exc_end", 10), ("E/E0", 10), ("lost_dec", 10), ("ledger", 10),
    ("p_final", 10), ("p_bal", 10), ("p_shift", 10), ("overlap", 10), ("penetr", 10),
]
MAIN_UNITS = ["", "", "[s]", "[-]", "[-]", "[-]", "[-]", "[scale]", "[J/m2]", "[scale]", "[-]", "[scale]",
              "[scale]", "[kg/m/s]", "[kg/m/s]", "[kg/m/s]", "[dx]", "[dx]"]


def print_main(results, order, energy_column):
    lines = []
    lines.append("spallbar event study: one row per run (scale = max(e_kin+|e_strain| at t=0, "
                 "max|w_ext|))")
    if energy_column == "e_wave":
        measure = ("e_wave + e_pot + e_wave_g (and w_wave, e_lost_w, ledger_w in place of "
                   "w_ext, e_lost, ledger)")
    elif energy_column:
        measure = energy_column + " + e_pot"
    else:
        measure = "e_kin + e_strain + e_pot"
    lines.append("E = %s; exc = max_t (E - E0 - w_ext)/scale, exc_abs the same in J/m^2, "
                 "exc_end at t_end; E/E0 at t_end ('-': E0 = 0; E0 includes e_pot, may be < 0)"
                 % measure)
    lines.append("lost_dec = largest decrease of e_lost between rows /scale (<= 0: monotone); "
                 "ledger = max|ledger - ledger0|/scale")
    lines.append("p_bal = momentum - p0 - (i_gravity + i_ends + i_support + p_shift) at its "
                 "largest |.|; p_shift at t_end; overlap = max u(A_i)-u(B_i) /dx; penetr = max u(A_N)-u_base /dx "
                 "(base decks)")
    hdr = " ".join(n.rjust(w) if i else n.ljust(w) for i, (n, w) in enumerate(MAIN_COLS))
    unt = " ".join(u.rjust(w) if i else u.ljust(w)
                   for i, ((_, w), u) in enumerate(zip(MAIN_COLS, MAIN_UNITS)))
    lines += [hdr, unt, "-" * len(hdr)]
    for name in order:
        r = results[name]
        m = r.get("metrics", {})
        ev = m.get("events", {})
        rc = "-" if r.get("rc") is None else str(r["rc"])
        cells = [name.ljust(31), rc.rjust(3), ("%.2f" % r.get("wall", 0.0)).rjust(6)]
        for k, w in (("fracture", 6), ("collision", 6), ("separation", 6),
                     ("base-collision", 5)):
            cells.append(str(ev.get(k, "-")).rjust(w))
        cells += [g(m.get("excess_rel")), g(m.get("excess_abs")), g(m.get("excess_end_rel")),
                  g(m.get("E_over_E0")),
                  g(m.get("e_lost_max_decrease_rel")), g(m.get("ledger_drift_rel")),
                  g(m.get("momentum_final")), g(m.get("momentum_balance_abs")),
                  g(m.get("p_shift_final")),
                  g(m.get("overlap_dx")), g(m.get("penetration_dx"))]
        lines.append(" ".join(cells))
    return lines


def print_compare(comps):
    lines = ["", "Galilean (gal0 vs gal0_v3: velocity 3 m/s added) and mirror (gal0 vs "
             "gal0_mirror: bar reversed, load on the bottom)",
             "ev_same: .evt (step, node, kind) identical (n gal0/n v3); ds = max|s_v3 - s_0| "
             "over all profile rows / max|s_0|;",
             "dp = p_v3(t_end) - p_0(t_end) - 3M (M from the mesh), dp/3M; mirror: counts "
             "fracture/collision/separation equal?, |e_kin_m - e_kin_0|/e_kin_0 at t_end"]
    cols = [("timing_shift", 20), ("ev_same", 16), ("first_diff(gal0|v3)", 34), ("ds", 10),
            ("dp", 10), ("dp/3M", 10), ("mir_counts", 11), ("gal0 f/c/s", 14),
            ("mirror f/c/s", 14), ("dEkin", 10)]
    hdr = " ".join(n.rjust(w) if i else n.ljust(w) for i, (n, w) in enumerate(cols))
    unt = " ".join(u.rjust(w) if i else u.ljust(w) for i, ((_, w), u) in enumerate(
        zip(cols, ["", "", "step:node:kind", "[-]", "[kg/m/s]", "[-]", "", "", "", "[-]"])))
    lines += [hdr, unt, "-" * len(hdr)]
    for c in comps:
        if "gal_events_identical" in c:
            same = ("yes" if c["gal_events_identical"] else "NO") + " (%d/%d)" % tuple(
                c["gal_events"])
            fd = c.get("gal_first_difference")
            if fd:
                def s(e):
                    return "none" if e is None else "%d:%d:%s" % (e[0], e[1], e[2][:4])
                fdt = "%s|%s" % (s(fd["gal0"]), s(fd["gal0_v3"]))
            else:
                fdt = "-"
        else:
            same, fdt = "-", "-"

        def fcs(ev):
            return "%d/%d/%d" % (ev.get("fracture", 0), ev.get("collision", 0),
                                 ev.get("separation", 0))
        if "mirror_counts" in c:
            mc = "yes" if c["mirror_counts_equal"] else "NO"
            a, b = fcs(c["mirror_counts"][0]), fcs(c["mirror_counts"][1])
        else:
            mc, a, b = "-", "-", "-"
        lines.append(" ".join([c["case"].ljust(20), same.rjust(16), fdt.rjust(34),
                               g(c.get("gal_stress_reldiff")),
                               g(c.get("gal_momentum_diff_minus_3M")),
                               g(c.get("gal_momentum_rel")), mc.rjust(11), a.rjust(14),
                               b.rjust(14), g(c.get("mirror_ekin_reldiff"))]))
    return lines


# --------------------------------------------------------------------------- main
def documented_his_columns():
    """The PREFIX.his columns doc/outputs.md documents: the names in the first cell of each
    row of its table under "## PREFIX.his"."""
    cols, inside = set(), False
    with open(os.path.join(ROOT, "doc", "outputs.md"), encoding="utf-8") as f:
        for line in f:
            if line.startswith("## "):
                inside = line.startswith("## PREFIX.his")
            elif inside and line.startswith("| `"):
                cols.update(re.findall(r"`(\w+)`", line.split("|")[1]))
    return cols


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", required=True, help="path of the spallbar executable")
    ap.add_argument("--work", required=True, help="directory for decks and outputs")
    ap.add_argument("--energy-column", default=None,
                    help="use this .his column + e_pot as the energy E (if present)")
    ap.add_argument("--only", default=None,
                    help="comma-separated run names or shell patterns (gal0_*_above)")
    ap.add_argument("--json", default=None, help="write every number to this JSON file")
    ap.add_argument("--jobs", type=int, default=2, help="runs in parallel (default 2)")
    ap.add_argument("--label", default=None,
                    help="a line printed first (provenance: commit, build) and kept in the JSON")
    ap.add_argument("--list", action="store_true", help="list the run names and exit")
    args = ap.parse_args(argv)

    decks = build_decks()
    names = list(decks)
    if args.list:
        print("\n".join(names))
        return 0
    if args.only:
        pats = [p.strip() for p in args.only.split(",") if p.strip()]
        unknown = [p for p in pats if not any(fnmatch.fnmatchcase(n, p) for n in names)]
        if unknown:
            print("event_study: --only: no run matches %s (--list shows the names)"
                  % ", ".join(unknown), file=sys.stderr)
            return 2
        names = [n for n in names if any(fnmatch.fnmatchcase(n, p) for p in pats)]
    exe = os.path.abspath(args.exe)
    if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
        print("event_study: --exe %s: not an executable file" % args.exe, file=sys.stderr)
        return 1
    os.makedirs(args.work, exist_ok=True)
    work = os.path.abspath(args.work)

    texts = {}
    for n in names:
        texts[n], _ = deck_text(decks[n])

    t_start = time.perf_counter()
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futs = {pool.submit(run_one, exe, work, n, texts[n]): n for n in names}
        for fut in concurrent.futures.as_completed(futs):
            r = fut.result()
            results[r["name"]] = r
    total_wall = time.perf_counter() - t_start

    failed = []
    for n in names:
        r = results[n]
        r["notes"] = []
        r["ok"] = False
        if not r["started"]:
            failed.append(n)
            continue
        if r["rc"] != 0:
            r["notes"].append("exit status %s: %s" % (r["rc"], r["stderr"].splitlines()[-1]
                                                      if r["stderr"] else ""))
        prefix = os.path.join(work, n)
        if not os.path.exists(prefix + ".his"):
            r["notes"].append("no .his written")
            continue
        try:
            r["metrics"] = analyse(prefix, args.energy_column, r["notes"])
            r["_evt"], _ = read_evt(prefix + ".evt")
            r["_prf"] = read_prf(prefix + ".prf")
            r["ok"] = True
        except (OSError, ValueError, KeyError, IndexError) as e:
            r["notes"].append("could not read outputs: %s" % e)

    ok_names = [n for n in names if n not in failed]
    version = "?"
    for n in ok_names:
        try:
            with open(os.path.join(work, n + ".his")) as f:
                # the first '#' line names the program (a column-name line may come before it)
                version = next((line[1:].split("--")[0].strip() for line in f
                                if line.startswith("# spallbar")), "?")
            break
        except OSError:
            pass
    lines = ["label: %s" % args.label] if args.label else []
    lines.append("exe: %s (%s); work: %s" % (exe, version, work))
    lines += print_main(results, ok_names, args.energy_column)
    comps = compare(results)
    if comps:
        lines += print_compare(comps)
    notes = [(n, results[n]["notes"]) for n in names if results[n].get("notes")]
    doc_cols = documented_his_columns()
    cols_seen = set()
    for n in ok_names:
        cols_seen |= set(results[n].get("metrics", {}).get("columns", []) or [])
    extra = [c for c in next((results[n]["metrics"]["columns"] for n in ok_names
                              if results[n].get("ok")), []) if c not in doc_cols]
    lines.append("")
    lines.append("%d runs, %d could not start; total wall %.1f s with %d parallel jobs" % (
        len(names), len(failed), total_wall, args.jobs))
    if extra:
        lines.append(".his columns not in doc/outputs.md: %s" % " ".join(extra))
    missing = sorted(doc_cols - cols_seen) if cols_seen else []
    if missing:
        lines.append("doc/outputs.md columns missing from .his: %s" % " ".join(missing))
    for n, ns in notes:
        for s in ns:
            lines.append("note %s: %s" % (n, s))
    for n in failed:
        r = results[n]
        lines.append("FAILED TO START %s: exit status %s: %s" % (n, r["rc"], r["stderr"]))
    print("\n".join(lines))

    if args.json:
        out = {"label": args.label, "exe": exe, "version": version, "work": work, "energy_column": args.energy_column,
               "total_wall_s": total_wall, "jobs": args.jobs, "runs": {}, "comparisons": comps,
               "extra_his_columns": extra}
        for n in names:
            r = results[n]
            out["runs"][n] = {"rc": r["rc"], "started": r["started"], "wall_s": r["wall"],
                              "notes": r.get("notes", []), "deck": texts[n],
                              "metrics": {k: v for k, v in r.get("metrics", {}).items()}}
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1, sort_keys=False)
    if failed:
        print("event_study: %d run(s) could not start: %s" % (len(failed), ", ".join(failed)),
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
